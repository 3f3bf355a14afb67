#include "Core/Math/PolarDecomposition.h"

#include <cmath>

namespace anode {

Mat3 rotationOf(const Mat3& F) {
  Mat3 R = F;
  for (int iter = 0; iter < 100; ++iter) {
    const Mat3 Rinv = R.inverse();
    // Frobenius-norm scaling makes the iteration converge in a few steps even for large stretch.
    const double gamma = std::sqrt(Rinv.norm() / R.norm());
    const Mat3 next = 0.5 * (gamma * R + Rinv.transpose() / gamma);
    const double change = (next - R).norm();
    R = next;
    if (change < 1e-15 * 3.0) break;
  }
  return R;
}

}  // namespace anode
