#include "Components/MPM/TimestepController.h"

#include <algorithm>

namespace anode {

namespace {
constexpr int kMaxRetakes = 20;  // of one step: with <delt_min> 0, 0.6^20 = 4e-5 of its dt
// A step whose largest change of c exceeds <max_concentration_change> by this factor is retaken,
// at dt x bound / change, but no less than dt x kSmallestConcentrationRetake.
constexpr double kConcentrationChangeRetake = 2, kSmallestConcentrationRetake = 0.1;
}  // namespace

TimestepController::TimestepController(const TimeControl& time, const ImplicitOptions* implicit)
    : time_(time), implicit_(implicit) {}

TimestepController::Plan TimestepController::plan(const StableTimestep& limits, double growsFrom,
                                                  double t,
                                                  std::optional<double> nextOutputTime) const {
  Plan p;
  // Eq. 45 times the multiplier; an implicit step's limits are its dt already.
  const double scaled = (implicit_ ? 1.0 : time_.multiplier) * limits.dt();
  p.dt = time_.clamp(scaled, growsFrom, t);
  p.limit = limits.binding();
  p.setByTimeControl = p.dt != scaled;
  p.ruleDt = p.dt;
  // <clamp_time_to_output>: a step that would pass an output time ends on it, so the outputs fall
  // at the times the input asks for (without it, on the first step after each, as Uintah's).
  if (time_.clampTimeToOutput && nextOutputTime && t + p.dt > *nextOutputTime * (1 + 1e-12)) {
    p.dt = *nextOutputTime - t;
    p.setByTimeControl = true;
  }
  return p;
}

double TimestepController::afterNewton(double dt, int iterations) const {
  if (iterations >= implicit_->itersToDecrease) return dt * implicit_->decreaseFactor;
  if (iterations <= implicit_->itersToIncrease) return dt * implicit_->increaseFactor;
  return dt;
}

double TimestepController::forConcentrationChange(double dt, double change) const {
  return dt * implicit_->maxConcentrationChange / change;
}

bool TimestepController::retakesConcentrationChange(double change) const {
  return change > kConcentrationChangeRetake * implicit_->maxConcentrationChange;
}

double TimestepController::retakeDt(double dt, double change) const {
  if (change > 0)
    return dt * std::max(implicit_->maxConcentrationChange / change, kSmallestConcentrationRetake);
  return dt * implicit_->decreaseFactor;
}

std::string TimestepController::refusesRetake(double retake, int retakes) const {
  if (retake < time_.deltMin)
    return "a retake with dt = " + std::to_string(retake) + " would be below <delt_min> " +
           std::to_string(time_.deltMin);
  if (retakes >= kMaxRetakes)
    return std::to_string(kMaxRetakes) + " retakes with a smaller dt failed";
  return {};
}

}  // namespace anode
