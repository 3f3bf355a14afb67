// A piecewise-linear load curve J(t) of <load_curve> (UINTAH_UPS.md §2.9): linear interpolation
// in the first interval whose end is >= t, extrapolation from the first interval before it, the
// last load after the last time.
#pragma once

#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

class LoadCurve {
 public:
  LoadCurve(std::vector<double> times, std::vector<double> loads);
  // Reads <load_curve> (<id> is read by the caller); times must be >= 0 and strictly increasing.
  static LoadCurve fromInput(const PSNode& node);

  double at(double t) const;
  // The first of its times after t (beyond t by more than 1e-12 of t, so a step that ended on one
  // does not name it again), where the curve's slope changes; infinity past the last.
  double nextTimeAfter(double t) const;
  // The segment t lies in: the number of the curve's times at or before t (within 1e-12 of t,
  // as nextTimeAfter), so 0 before the first time and times().size() after the last.
  size_t segmentAt(double t) const;
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& loads() const { return loads_; }

 private:
  std::vector<double> times_, loads_;
};

}  // namespace anode
