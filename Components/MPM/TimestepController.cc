#include "Components/MPM/TimestepController.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace anode {

namespace {
constexpr int kMaxRetakes = 20;  // of one step: with <delt_min> 0, 0.6^20 = 4e-5 of its dt
// A step whose largest change of c exceeds <max_concentration_change> by this factor is retaken,
// at dt x bound / change, but no less than dt x kSmallestConcentrationRetake.
constexpr double kConcentrationChangeRetake = 2, kSmallestConcentrationRetake = 0.1;
// The PI controller of Hairer's DOPRI5 (Hairer, Norsett & Wanner, Solving ODEs I, §II.4) for an
// estimate e of order dt^k, k = 3 (the trapezoidal coupling's local error): dt x safety x (tol /
// e_n)^alpha x (e_{n-1} / tol)^beta, beta = 0.04, alpha = 1/k - 0.75 beta, after the first estimate
// dt x safety x (tol / e)^(1/k), by a factor of at most kLargestGrowth and at least
// kSmallestShrink; a rejected step is retaken at dt x safety x (tol / e)^(1/k), at least dt x
// kSmallestShrink.
constexpr double kEstimateOrder = 3, kSafety = 0.9, kLargestGrowth = 5, kSmallestShrink = 0.2;
constexpr double kBeta = 0.04, kAlpha = 1 / kEstimateOrder - 0.75 * kBeta;
}  // namespace

TimestepController::TimestepController(const TimeControl& time, const ImplicitOptions* implicit)
    : time_(time), implicit_(implicit) {
  // Under error control the last step ends on <maxTime> (<end_at_max_time_exactly>).
  if (controlsError()) time_.endAtMaxTimeExactly = true;
}

TimestepController::Plan TimestepController::plan(const StableTimestep& limits, double growsFrom,
                                                  double t, std::optional<double> nextEnd) const {
  Plan p;
  StableTimestep all = limits;
  if (controlsError() && error_.lastEstimate >= 0)
    all.bound[StableTimestep::ErrorEstimate] = afterErrorEstimate();
  // Eq. 45 times the multiplier; an implicit step's limits are its dt already.
  const double scaled = (implicit_ ? 1.0 : time_.multiplier) * all.dt();
  p.dt = time_.clamp(scaled, growsFrom, t);
  p.limit = all.binding();
  p.setByTimeControl = p.dt != scaled;
  p.ruleDt = p.dt;
  // <clamp_time_to_output>: a step that would pass an output time ends on it, so the outputs fall
  // at the times the input asks for (without it, on the first step after each, as Uintah's); and
  // under error control on a load curve's time, where the load's slope changes.
  if (endsStepsOnOutputs() && nextEnd && t + p.dt > *nextEnd * (1 + 1e-12)) {
    p.dt = *nextEnd - t;
    p.setByTimeControl = true;
  } else if (controlsError() && nextEnd) {
    // Under error control the steps to the next such time are of one length, at most the
    // controller's: no short step left before it. Each is an even share of the limit's dt, which
    // the plan still names.
    const double remaining = std::min(*nextEnd, time_.maxTime) - t;
    const double steps = std::ceil(remaining / p.dt * (1 - 1e-12));
    if (steps > 1) p.dt = std::min(p.dt, remaining / steps);
  }
  return p;
}

bool TimestepController::endsStepsOnOutputs() const {
  return time_.clampTimeToOutput || controlsError();
}

double TimestepController::afterNewton(double dt, int iterations) const {
  if (iterations >= implicit_->itersToDecrease) return dt * implicit_->decreaseFactor;
  // Under error control the error grows dt; Newton's iterations only shrink it.
  if (controlsError()) return std::numeric_limits<double>::infinity();
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

bool TimestepController::rejectsErrorEstimate(double estimate) const {
  return estimate > implicit_->errorTolerance;
}

double TimestepController::retakeForError(double dt, double estimate) const {
  return dt * std::max(kSmallestShrink, kSafety * std::pow(implicit_->errorTolerance / estimate,
                                                           1 / kEstimateOrder));
}

void TimestepController::recordStep(double estimate, double dt, double ruleDt) {
  if (estimate < 0) return;
  // A step shortened to end on an output time counts as the step it was cut from: its estimate
  // scaled to that dt by the estimate's order.
  const double base = std::max(dt, ruleDt);
  error_.previousEstimate = error_.lastEstimate;
  error_.lastEstimate = estimate * std::pow(base / dt, kEstimateOrder);
  error_.lastDt = base;
  error_.takenDt = dt;
}

double TimestepController::afterErrorEstimate() const {
  const double tolerance = implicit_->errorTolerance, estimate = error_.lastEstimate;
  if (estimate <= 0) return error_.lastDt * kLargestGrowth;
  const double factor = error_.previousEstimate > 0
                            ? std::pow(tolerance / estimate, kAlpha) *
                                  std::pow(error_.previousEstimate / tolerance, kBeta)
                            : std::pow(tolerance / estimate, 1 / kEstimateOrder);
  return error_.lastDt * std::clamp(kSafety * factor, kSmallestShrink, kLargestGrowth);
}

std::string TimestepController::refusesRetake(double retake, int retakes) const {
  if (retake < time_.deltMin)
    return "a retake with dt = " + std::to_string(retake) + " would be below <delt_min> " +
           std::to_string(time_.deltMin);
  if (retakes >= kMaxRetakes)
    return std::to_string(kMaxRetakes) + " retakes with a smaller dt failed";
  return {};
}

std::string TimestepController::refusesStalledNewton(const std::vector<FailedNewton>& failed) {
  if (failed.size() < 4) return {};
  const FailedNewton& newest = failed.back();
  const auto near = [](double a, double b) { return std::abs(a - b) <= 0.05 * std::abs(b); };
  double largestDt = newest.dt;
  for (size_t k = failed.size() - 1; k-- > 0;) {
    const FailedNewton& f = failed[k];
    if (!near(f.dispRatio, newest.dispRatio) || !near(f.energyRatio, newest.energyRatio)) return {};
    largestDt = std::max(largestDt, f.dt);
    const size_t attempts = failed.size() - k;
    if (attempts >= 4 && largestDt >= 8 * newest.dt) {
      std::ostringstream s;
      s.precision(3);
      s << "Newton stalls whatever dt: its last ratios stayed within 5% of (" << newest.dispRatio
        << ", " << newest.energyRatio << ") over " << attempts
        << " attempts from dt = " << largestDt << " to " << newest.dt
        << ", so a smaller dt cures nothing (the equilibrium problem itself, not the step, "
           "stops it)";
      return s.str();
    }
  }
  return {};
}

}  // namespace anode
