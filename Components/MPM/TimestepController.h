// The one place each step's dt is chosen (DESIGN.md §4c): from the limits of the state an
// integrator reports (StableTimestep: Eqs. 43-45 of the explicit step; ImpMPM's rule on Newton's
// iterations and the bound on the change of c of the implicit step, both computed here), the
// multiplier (explicit steps: an implicit run's <timestep_multiplier> is its diffusion
// sub-steps'), <Time>'s clamps in Uintah's order, the output times (<clamp_time_to_output>), and
// the dt of an implicit step retaken after a failed attempt, and with <error_tolerance> the PI
// controller on the steps' error estimates (whose state it keeps). Each plan says which of them
// set its dt.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Components/MPM/ImplicitOptions.h"
#include "Components/MPM/StableTimestep.h"
#include "Core/Grid/TimeControl.h"

namespace anode {

class TimestepController {
 public:
  // `implicit`: an implicit run's options (null for an explicit run).
  TimestepController(const TimeControl& time, const ImplicitOptions* implicit);

  // The step from t: its dt, the dt the limits and <Time>'s clamps chose (dt is less where it
  // ends on an output time, or is an even share of the steps to one), the limit that set the
  // stable dt, and whether the clamps or the output time it ends on changed it.
  struct Plan {
    double dt = 0, ruleDt = 0;
    StableTimestep::Limit limit = StableTimestep::Mechanics;
    bool setByTimeControl = false;
  };
  // `growsFrom`: the dt the last step's limits grow from (StepTaken::ruleDt; 0 before the first
  // step); `nextEnd`: the first time after t a step ends on (an output time where outputs fall
  // at times; under error control also a flux load curve's next time). With <error_tolerance>
  // the error controller's dt is one more limit, steps end on the output times (as with
  // <clamp_time_to_output>) and on the load curves' times, the steps to the next such time are of
  // one length (the remaining time over the number of steps of the limits' dt it needs), and the
  // last ends on <maxTime> (<end_at_max_time_exactly>).
  Plan plan(const StableTimestep& limits, double growsFrom, double t,
            std::optional<double> nextEnd) const;
  // Whether steps end on the output times (<clamp_time_to_output>, or <error_tolerance>).
  bool endsStepsOnOutputs() const;

  // Implicit steps. ImpMPM's rule: the dt after a step of `dt` that took `iterations` Newton
  // iterations (the first step takes <delt_max> or <delt_init>).
  double afterNewton(double dt, int iterations) const;
  // With diffusion: the dt whose largest change of a particle's c would be
  // <max_concentration_change>, after a step of dt whose largest change was `change` (scaled
  // linearly).
  double forConcentrationChange(double dt, double change) const;
  // Whether a step whose largest change of c was `change` is retaken (above twice the bound).
  bool retakesConcentrationChange(double change) const;
  // The dt an attempt over dt that failed is retaken with: dt x <delT_decrease_factor>, or, when
  // its change of c failed it (`change` > 0), the dt the bound allows but no less than a tenth.
  double retakeDt(double dt, double change) const;
  // Why a retake of dt `retake` after `retakes` earlier ones of the same step is not taken:
  // below <delt_min>, or past kMaxRetakes; empty when it is.
  std::string refusesRetake(double retake, int retakes) const;
  // A Newton solve of a step that failed: its dt and its last ratios (NewtonReport::ratios).
  struct FailedNewton {
    double dt, dispRatio, energyRatio;
  };
  // Why no retake is taken after the failed Newton solves of a step, oldest first, when Newton
  // stalls whatever dt: each last ratio within 5% of the newest solve's over attempts that span
  // 3 retakes or more and 8x or more in dt (a smaller dt then cures nothing); empty otherwise.
  static std::string refusesStalledNewton(const std::vector<FailedNewton>& failed);
  // The diffusion sub-steps' share of the explicit limits (<timestep_multiplier>).
  double substepMultiplier() const { return time_.multiplier; }

  // Error control (<error_tolerance>; the estimate is ImplicitStep's, of order dt^3 on a step).
  bool controlsError() const { return implicit_ && implicit_->errorTolerance > 0; }
  // Whether a step of that estimate is retaken (above the tolerance).
  bool rejectsErrorEstimate(double estimate) const;
  // The dt a step of dt whose estimate was rejected is retaken with.
  double retakeForError(double dt, double estimate) const;
  // What the controller keeps between steps (and the checkpoints hold): the estimates of the last
  // two steps (-1: none yet) and the last one's dt, a step shortened to end on an output time
  // counting as the one it was cut from; and the dt the last step took (0 before the first),
  // which the next step's estimate needs. (The accumulated estimate is the particles'.)
  struct ErrorControl {
    double lastEstimate = -1, previousEstimate = -1, lastDt = 0, takenDt = 0;
  };
  // After a step taken over dt (of ruleDt) with that estimate (negative: none).
  void recordStep(double estimate, double dt, double ruleDt);
  const ErrorControl& errorControl() const { return error_; }
  void resumeErrorControl(const ErrorControl& state) { error_ = state; }

 private:
  // The PI controller's dt for the next step (DESIGN.md §4c).
  double afterErrorEstimate() const;

  TimeControl time_;
  const ImplicitOptions* implicit_;
  ErrorControl error_;
};

}  // namespace anode
