// Polar decomposition F = R U (paper Eq. 26): R proper orthogonal, U = R^T F symmetric positive
// definite. The stress update needs R only.
#pragma once

#include "Core/Math/Simd.h"
#include "Core/Math/Types.h"

namespace anode {

// Requires det F > 0. Scaled Newton iteration (Higham 1986), converged to round-off; for a pack
// of particles each lane stops where it converges, so it gets the bits the scalar iteration gives.
template <class S>
Mat3Of<S> rotationOf(const Mat3Of<S>& F) {
  Mat3Of<S> R = F;
  auto converging = S(1.0) > S(0.0);
  for (int iter = 0; iter < 100; ++iter) {
    const Mat3Of<S> Rinv = R.inverse();
    // Frobenius-norm scaling makes the iteration converge in a few steps even for large stretch.
    const S gamma = sqrtOf(frobeniusNorm(Rinv) / frobeniusNorm(R));
    const Mat3Of<S> next = S(0.5) * (gamma * R + Rinv.transpose() / gamma);
    const S change = frobeniusNorm<S>(next - R);
    for (int k = 0; k < 9; ++k) R(k) = select(converging, next(k), R(k));
    converging = converging && !(change < S(1e-15 * 3.0));
    if (!anyOf(converging)) break;
  }
  return R;
}

inline Mat3 rotationOf(const Mat3& F) {
  return rotationOf<double>(F);
}

}  // namespace anode
