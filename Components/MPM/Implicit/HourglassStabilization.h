// Hourglass stabilization of the equilibrium step (docs/quasi-static.md). With about one particle
// per cell each cell's stiffness is sampled at one point, and the nodal displacement fields that
// no particle's gradient sees (hourglass modes) have zero energy: the Jacobian is singular apart
// from them and the Krylov solve stalls. Each particle therefore carries the energy of the part
// of the displacement that is not linear over its support:
//
//   E_p = kappa_p V_p / 2 sum_i S_ip |m_i + r_i|^2,  r_i = u_i - u_p - H_p (x_i - x_p),
//   u_p = sum_j S_jp u_j,  H_p = sum_j u_j (x) grad S_jp,
//
// r that of the step's displacement increments u, m_i what the steps before left at node i (the
// particle's HourglassMemory: the sum of their r, turned with the particle, on the nodes it
// reached then; zero at a node outside that memory's box). kappa_p = epsilon * (mean diagonal of
// the particle's tangent dP/dH) / h^2, h^2 the mean of the squared cell sizes. r vanishes for
// every displacement field that is linear over the support, so uniform strains (the closed-form
// tests) and the rigid modes are untouched, and the stabilizing force of a smooth field falls as
// h^2 under refinement. The memory makes the energy one of the particle's state, not of the step:
// without it a step's stabilizing force would be dropped at the next step's start, a viscosity
// whose answer depends on how many steps reach a time. Within a step the energy is quadratic in
// u: its stiffness, kappa V M with M = A^T diag(S) A (r = A u), is the same for every Newton
// iteration, and the memory adds a constant force kappa V A^T diag(S) m.
#pragma once

#include <Eigen/Dense>
#include <limits>
#include <vector>

#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/ParticleSet.h"
#include "Core/Grid/Grid.h"
#include "Core/Math/PolarDecomposition.h"

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

// A of r = A u over particle i's support (n x n): A = I - B C^T, B and C as for hourglassMatrix.
inline Eigen::MatrixXd nonAffineOperator(const Grid& grid, const InterpolationWeights& W, long i,
                                         const Vec3& xp) {
  const int n = W.count[i];
  const size_t b = W.offset[i];
  Eigen::MatrixX4d B(n, 4), C(n, 4);
  for (int a = 0; a < n; ++a) {
    const Vec3i ijk = grid.nodeOf(W.node[b + a]);
    B.row(a) << 1, (grid.nodePosition(ijk.x(), ijk.y(), ijk.z()) - xp).transpose();
    C.row(a) << W.weight[b + a], W.gradient[b + a].transpose();
  }
  Eigen::MatrixXd A = -B * C.transpose();
  A.diagonal().array() += 1;
  return A;
}

// The slot of `node` in the memory's box, -1 outside it.
inline int memorySlot(const HourglassMemory& memory, const Grid& grid, int32_t node) {
  const Vec3i d = grid.nodeOf(node) - Vec3i(memory.origin[0], memory.origin[1], memory.origin[2]);
  if ((d.array() < 0).any() || (d.array() > 3).any()) return -1;
  return (d.z() * 4 + d.y()) * 4 + d.x();
}

// m_i S_ip of particle i's support entries (3 x n), zero without a memory.
inline Eigen::Matrix3Xd weightedMemory(const ParticleSet& p, size_t i, const Grid& grid,
                                       const InterpolationWeights& W) {
  const int n = W.count[i];
  Eigen::Matrix3Xd m = Eigen::Matrix3Xd::Zero(3, n);
  if (p.hourglassMemory.empty()) return m;
  const HourglassMemory& memory = p.hourglassMemory[i];
  for (int e = 0; e < n; ++e) {
    const int slot = memorySlot(memory, grid, W.node[W.offset[i] + e]);
    if (slot >= 0)
      m.col(e) = W.weight[W.offset[i] + e] * Eigen::Map<const Vec3>(memory.displacement[slot]);
  }
  return m;
}

// After a converged step with nodal displacement increments u (by node; the weights and positions
// of the step's start): each particle's memory becomes R (m + r) on the nodes of its support, R
// the rotation of its dF = I + H, in the box from the support's lowest node (the nodes of a
// support more than 4 nodes wide along an axis beyond it are not kept).
inline void rememberNonAffineDisplacement(const Grid& grid, const InterpolationWeights& W,
                                          const std::vector<Vec3>& u, ParticleSet& p) {
  const long count = static_cast<long>(p.count());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i) {
    const int n = W.count[i];
    const size_t b = W.offset[i];
    Eigen::Matrix3Xd U(3, n);
    Vec3i lowest = Vec3i::Constant(std::numeric_limits<int>::max());
    for (int e = 0; e < n; ++e) {
      U.col(e) = u[W.node[b + e]];
      lowest = lowest.cwiseMin(grid.nodeOf(W.node[b + e]));
    }
    const Eigen::Matrix3Xd r = U * nonAffineOperator(grid, W, i, p.x[i]).transpose();
    const Mat3 R = rotationOf(Mat3(Mat3::Identity() + displacementGradient(W, i, u)));
    const HourglassMemory& before = p.hourglassMemory[i];
    HourglassMemory after{};
    for (int d = 0; d < 3; ++d) after.origin[d] = lowest[d];
    for (int e = 0; e < n; ++e) {
      const int32_t node = W.node[b + e];
      const int slot = memorySlot(after, grid, node);
      if (slot < 0) continue;
      const int old = memorySlot(before, grid, node);
      Vec3 m = r.col(e);
      if (old >= 0) m += Eigen::Map<const Vec3>(before.displacement[old]);
      Eigen::Map<Vec3>(after.displacement[slot]) = R * m;
    }
    p.hourglassMemory[i] = after;
  }
}

}  // namespace anode
