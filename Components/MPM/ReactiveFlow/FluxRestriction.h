// The flux restriction of paper Eq. 17, applied once per particle to the flux it takes up
// (docs/diffusion.md): R(c) = max(0, 1 + ln(1 - c)/4) for normalised c, 0 for c >= 1 (Uintah's
// clamp), vanishing at the root c = 1 - e^-4.
#pragma once

#include <algorithm>
#include <cmath>

namespace anode {

inline double fluxRestriction(double c) {
  if (c >= 1) return 0.0;
  return std::max(0.0, 1.0 + 0.25 * std::log(1.0 - c));
}

// The restriction of a flux into (inflow) or out of a particle at normalised c: R(c), or its
// mirror R(1 - c), which vanishes as the particle empties.
inline double fluxRestriction(double c, bool inflow) {
  return fluxRestriction(inflow ? c : 1 - c);
}

// The restriction's steepest slope before it reaches zero, |R'| at c = 1 - e^-4: a particle
// whose unrestricted rate is k cannot step past the zero of R when dt k kRestrictionSlope <= 1.
constexpr double kRestrictionSlope = 13.649537508286059;  // e^4 / 4 = 13.649537508286059769...

}  // namespace anode
