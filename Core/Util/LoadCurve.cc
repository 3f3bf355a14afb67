#include "Core/Util/LoadCurve.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace anode {

LoadCurve::LoadCurve(std::vector<double> times, std::vector<double> loads)
    : times_(std::move(times)), loads_(std::move(loads)) {
  if (times_.empty() || times_.size() != loads_.size())
    throw std::invalid_argument("a load curve needs matching, non-empty times and loads");
}

LoadCurve LoadCurve::fromInput(const PSNode& node) {
  std::vector<double> times, loads;
  for (const PSNode& point : node.children("time_point")) {
    const double t = point.require<double>("time");
    if (t < 0) point.requireChild("time").fail("load curve times must be >= 0");
    if (!times.empty() && !(t > times.back()))
      point.requireChild("time").fail("load curve times must be strictly increasing");
    times.push_back(t);
    loads.push_back(point.require<double>("load"));
  }
  if (times.empty()) node.fail("<load_curve> needs at least one <time_point>");
  node.acceptInert("material");  // Uintah's flux BC ignores it (UINTAH_UPS.md §2.9)
  return LoadCurve(times, loads);
}

double LoadCurve::at(double t) const {
  const size_t n = times_.size();
  if (n == 1 || t >= times_.back()) return loads_.back();
  size_t i = 1;
  while (i < n - 1 && times_[i] < t) ++i;
  const double s = (t - times_[i - 1]) / (times_[i] - times_[i - 1]);
  return loads_[i - 1] + s * (loads_[i] - loads_[i - 1]);
}

double LoadCurve::nextTimeAfter(double t) const {
  for (double time : times_)
    if (time > t + 1e-12 * std::abs(t)) return time;
  return std::numeric_limits<double>::infinity();
}

size_t LoadCurve::segmentAt(double t) const {
  size_t segment = 0;
  while (segment < times_.size() && !(times_[segment] > t + 1e-12 * std::abs(t))) ++segment;
  return segment;
}

}  // namespace anode
