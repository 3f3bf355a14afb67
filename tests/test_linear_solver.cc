// Pins the equilibrium step's linear solver (Components/MPM/Implicit/LinearSolver.h) on a small
// elastic lattice (springs between each node and its 26 neighbours, the base held): the solution
// meets the tolerance on the unscaled system, fixed components stay exactly zero, and the second
// solve of one pattern reuses the first one's preconditioner and still meets its tolerance, and a
// preconditioner built anew for a changed matrix of the same pattern is fitted to that matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "Components/MPM/Implicit/LinearSolver.h"

namespace anode {
namespace {

// The stiffness of a lattice of kSide nodes per edge; springs whose first node has k < stiffLayers
// are `stiffer` times stiffer; `diagonal` times the identity added to each node's block.
// Coordinates: 3 per node.
BlockMatrix latticeStiffness(double stiffer, int stiffLayers, std::vector<double>& coordinates,
                             int kSide = 6, double diagonal = 0) {
  const auto nodeIndex = [kSide](int i, int j, int k) { return i + kSide * (j + kSide * k); };
  const int n = kSide * kSide * kSide;
  std::vector<std::map<int, Mat3>> rows(n);
  // Eigen leaves a new block uninitialized: each starts at zero.
  const auto block = [&rows](int r, int c) -> Mat3& {
    return rows[r].try_emplace(c, Mat3::Zero()).first->second;
  };
  coordinates.assign(3 * n, 0.0);
  for (int k = 0; k < kSide; ++k)
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i) {
        const int a = nodeIndex(i, j, k);
        coordinates[3 * a] = i, coordinates[3 * a + 1] = j, coordinates[3 * a + 2] = k;
        block(a, a) += diagonal * Mat3::Identity();
        for (int dk = -1; dk <= 1; ++dk)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              const int i2 = i + di, j2 = j + dj, k2 = k + dk;
              if (i2 < 0 || j2 < 0 || k2 < 0 || i2 >= kSide || j2 >= kSide || k2 >= kSide) continue;
              const int b = nodeIndex(i2, j2, k2);
              if (b <= a) continue;
              const Vec3 e = Vec3(di, dj, dk).normalized();
              const Mat3 s = (k < stiffLayers ? stiffer : 1.0) * e * e.transpose();
              block(a, a) += s, block(b, b) += s, block(a, b) -= s, block(b, a) -= s;
            }
      }
  BlockMatrix K;
  for (const auto& row : rows) {
    for (const auto& [c, entries] : row) {
      K.column.push_back(c);
      K.block.push_back(entries);
    }
    K.rowStart.push_back(static_cast<int>(K.column.size()));
  }
  return K;
}

// A load varying over the nodes; the base (z = 0) held.
std::vector<double> loadWithBaseHeld(const std::vector<double>& coordinates,
                                     std::vector<int>& fixed, std::vector<char>& isFixed) {
  fixed.clear();
  isFixed.assign(coordinates.size(), 0);
  std::vector<double> b(coordinates.size());
  for (size_t i = 0; i < b.size(); ++i) {
    b[i] = std::sin(1.7 * static_cast<double>(i)) + 0.3;
    if (coordinates[3 * (i / 3) + 2] == 0) fixed.push_back(static_cast<int>(i)), isFixed[i] = 1;
  }
  return b;
}

RowLayout oneRankOwnsEveryRow(const BlockMatrix& K) {
  RowLayout rows;
  rows.owned = K.rows();
  for (int r = 0; r < K.rows(); ++r) rows.globalRow.push_back(r);
  return rows;
}

// |K x - b| / |b| over the free components.
double relativeResidual(const BlockMatrix& K, const std::vector<double>& x,
                        const std::vector<double>& b, const std::vector<char>& isFixed) {
  double r2 = 0, b2 = 0;
  for (int r = 0; r < K.rows(); ++r) {
    Vec3 Kx = Vec3::Zero();
    for (int j = K.rowStart[r]; j < K.rowStart[r + 1]; ++j)
      Kx += K.block[j] * Vec3(x[3 * K.column[j]], x[3 * K.column[j] + 1], x[3 * K.column[j] + 2]);
    for (int a = 0; a < 3; ++a) {
      if (isFixed[3 * r + a]) continue;
      r2 += std::pow(Kx[a] - b[3 * r + a], 2);
      b2 += b[3 * r + a] * b[3 * r + a];
    }
  }
  return std::sqrt(r2 / b2);
}

TEST(LinearSolver, SolvesTheLatticeAndReusesItsPreconditioner) {
  std::vector<double> coordinates;
  const BlockMatrix K = latticeStiffness(1.0, 0, coordinates);
  std::vector<int> fixed;
  std::vector<char> isFixed;
  const std::vector<double> b = loadWithBaseHeld(coordinates, fixed, isFixed);
  LinearSolver solver(Communicator::everyRank(), K, oneRankOwnsEveryRow(K), fixed, coordinates);
  const double tolerance = 1e-8;
  std::vector<double> x;
  const LinearSolve first = solver.solve(Communicator::everyRank(), K, b, tolerance, x);
  ASSERT_TRUE(first.converged) << first.reason;
  EXPECT_TRUE(first.newPreconditioner);
  EXPECT_GT(first.iterations, 0);
  // The tolerance bounds the diagonally scaled residual; the lattice's diagonal varies by less
  // than 4 over its nodes.
  EXPECT_LT(relativeResidual(K, x, b, isFixed), 4 * tolerance);
  for (int i : fixed) EXPECT_EQ(x[i], 0.0);

  // The same pattern with the lowest layers 3 times stiffer: the first preconditioner serves.
  const BlockMatrix stiffened = latticeStiffness(3.0, 2, coordinates);
  const LinearSolve second = solver.solve(Communicator::everyRank(), stiffened, b, tolerance, x);
  ASSERT_TRUE(second.converged) << second.reason;
  EXPECT_FALSE(second.newPreconditioner);
  EXPECT_LT(relativeResidual(stiffened, x, b, isFixed), 12 * tolerance);
  for (int i : fixed) EXPECT_EQ(x[i], 0.0);
  std::printf("Krylov iterations: %d (new preconditioner), %d (reused)\n", first.iterations,
              second.iterations);
}

// A preconditioner is built for a matrix of the lattice held by a large diagonal (as a mass
// term); the lattice alone (the same pattern; its scaled spectrum twice as wide) is solved with
// it once, slowly, so the next solve builds its own. That one must be fitted to its matrix:
// GAMG's default keeps the first's prolongator and, with it, the first's eigenvalue estimate for
// its Chebyshev smoothers, which then amplify the modes above that estimate (59 iterations
// instead of 16).
TEST(LinearSolver, APreconditionerBuiltAnewFitsItsOwnMatrix) {
  constexpr int kLatticeSide = 12;
  std::vector<double> coordinates;
  const BlockMatrix held = latticeStiffness(1.0, 0, coordinates, kLatticeSide, 200.0);
  const BlockMatrix free = latticeStiffness(1.0, 0, coordinates, kLatticeSide);
  std::vector<int> fixed;
  std::vector<char> isFixed;
  const std::vector<double> b = loadWithBaseHeld(coordinates, fixed, isFixed);
  const double tolerance = 1e-8;
  std::vector<double> x;
  LinearSolver alone(Communicator::everyRank(), free, oneRankOwnsEveryRow(free), fixed,
                     coordinates);
  const LinearSolve fresh = alone.solve(Communicator::everyRank(), free, b, tolerance, x);
  ASSERT_TRUE(fresh.converged) << fresh.reason;

  LinearSolver solver(Communicator::everyRank(), held, oneRankOwnsEveryRow(held), fixed,
                      coordinates);
  ASSERT_TRUE(solver.solve(Communicator::everyRank(), held, b, tolerance, x).converged);
  const LinearSolve second = solver.solve(Communicator::everyRank(), free, b, tolerance, x);
  ASSERT_TRUE(second.converged) << second.reason;
  const LinearSolve third = solver.solve(Communicator::everyRank(), free, b, tolerance, x);
  ASSERT_TRUE(third.converged) << third.reason;
  EXPECT_LT(relativeResidual(free, x, b, isFixed), 4 * tolerance);
  std::printf(
      "Krylov iterations on the lattice alone: %d (its own preconditioner), %d and %d "
      "(after the held lattice's)\n",
      fresh.iterations, second.iterations, third.iterations);
  EXPECT_FALSE(second.newPreconditioner);
  EXPECT_TRUE(third.newPreconditioner);
  EXPECT_LE(third.iterations, 2 * fresh.iterations);
}

}  // namespace
}  // namespace anode
