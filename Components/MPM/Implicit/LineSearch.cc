// Newton's line search on the correction's energy (LineSearch.h).
#include "Components/MPM/Implicit/LineSearch.h"

#include <algorithm>
#include <cmath>

namespace anode {

LineSearchChoice searchAlongCorrection(double energy, double wholeSlope,
                                       const std::function<double(double)>& slopeAt) {
  const auto past = [&](double g) { return !(g > 0 && g < energy); };
  if (std::abs(wholeSlope) <= kEnergyReduction * energy || !past(wholeSlope)) return {1.0, true};
  double at = 1.0, lo = 0, gLo = energy, hi = 1, gHi = wholeSlope;
  double best = 1.0, bestSlope = std::abs(wholeSlope);  // NaN: any finite trial is better
  int kept = 0;                                         // -1: hi kept by the last trial, +1: lo
  for (int trial = 1; trial < kLineSearchTrials; ++trial) {
    at = std::clamp(std::isfinite(gHi) ? lo + (hi - lo) * gLo / (gLo - gHi) : 0.5 * (lo + hi),
                    lo + kLineSearchMargin * (hi - lo), hi - kLineSearchMargin * (hi - lo));
    const double g = slopeAt(at);
    if (std::abs(g) < bestSlope || std::isnan(bestSlope)) best = at, bestSlope = std::abs(g);
    if (std::abs(g) <= kEnergyReduction * energy) return {at, true};
    if (!past(g)) {
      lo = at, gLo = g;
      if (kept == -1 && gHi < 0) gHi *= 0.5;
      kept = -1;
    } else {
      hi = at, gHi = g;
      if (kept == 1) gLo *= 0.5;
      kept = 1;
    }
  }
  return {best, best == at};
}

}  // namespace anode
