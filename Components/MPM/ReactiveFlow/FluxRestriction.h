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

// The restriction's root c* = 1 - e^-4, where the inflow into a particle stops.
constexpr double kRestrictionRoot = 0.98168436111126578;  // 1 - e^-4 = 0.981684361111265779...

// The longest explicit step, in units of 1/k, that takes a particle at normalised c, filling at
// dc/dt = k R(c), no further than the root: (c* - c) / R(c) (docs/diffusion.md, "Time step").
// It falls as c rises (R is concave, so R(c) >= |R'(c)| (c* - c)), from 0.98 at c = 0 to
// 1/kRestrictionSlope at the root, and keeps dt k |R'(c)| <= 1, a monotone approach. Near the
// root the quotient of two small numbers is held at its limit 1/kRestrictionSlope.
inline double fluxStepToRoot(double c) {
  const double R = fluxRestriction(c);
  if (R <= 0) return 1.0 / kRestrictionSlope;
  return std::max((kRestrictionRoot - c) / R, 1.0 / kRestrictionSlope);
}

}  // namespace anode
