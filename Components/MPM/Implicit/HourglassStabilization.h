// Hourglass stabilization of the equilibrium step (docs/quasi-static.md). With about one particle
// per cell each cell's stiffness is sampled at one point, and the nodal displacement fields that
// no particle's gradient sees (hourglass modes) have zero energy: the Jacobian is singular apart
// from them and the Krylov solve stalls. Each particle therefore adds the energy of the part of
// the step's displacement increment that is not affine over its support:
//
//   E_p = kappa_p V_p / 2 sum_i S_ip |r_i|^2,  r_i = u_i - u_p - H_p (x_i - x_p),
//   u_p = sum_j S_jp u_j,  H_p = sum_j u_j (x) grad S_jp,
//
// kappa_p = epsilon * (mean diagonal of the particle's tangent dP/dH) / h^2, h^2 the mean of the
// squared cell sizes. r vanishes for every displacement field that is linear over the support,
// so uniform strains (the closed-form tests) and the rigid modes are untouched, and the
// stabilizing force of a smooth field falls as h^2 under refinement. The energy is quadratic in u:
// its stiffness is the same for every Newton iteration of the step.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "Components/MPM/Interpolator.h"
#include "Core/Grid/Grid.h"

namespace anode {

// The scalar matrix of particle i's stabilizing energy over its support entries (n x n, n =
// W.count[i]): M = A^T diag(S) A, A_ij = delta_ij - S_j - grad S_j . (x_i - x_p). The nodal
// stiffness between entries j and k is kappa V M_jk times the 3 x 3 identity. A = I - B C^T with
// the rows B_i = [1, x_i - x_p] and C_j = [S_j, grad S_j], so M is formed in O(n^2):
// M = W - W B C^T - C B^T W + C (B^T W B) C^T, W = diag(S).
inline Eigen::MatrixXd hourglassMatrix(const Grid& grid, const InterpolationWeights& W, long i,
                                       const Vec3& xp) {
  const int n = W.count[i];
  const size_t b = W.offset[i];
  Eigen::MatrixX4d B(n, 4), C(n, 4);
  Eigen::VectorXd S(n);
  for (int a = 0; a < n; ++a) {
    const Vec3i ijk = grid.nodeOf(W.node[b + a]);
    S[a] = W.weight[b + a];
    B.row(a) << 1, (grid.nodePosition(ijk.x(), ijk.y(), ijk.z()) - xp).transpose();
    C.row(a) << S[a], W.gradient[b + a].transpose();
  }
  const Eigen::MatrixX4d WB = S.asDiagonal() * B;
  const Eigen::MatrixXd WBC = WB * C.transpose();
  Eigen::MatrixXd M = C * (B.transpose() * WB) * C.transpose() - WBC - WBC.transpose();
  M.diagonal() += S;
  return M;
}

}  // namespace anode
