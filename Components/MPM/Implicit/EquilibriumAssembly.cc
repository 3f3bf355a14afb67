// The assembly of the equilibrium step (EquilibriumSolver.h) at the current nodal displacement
// increments u: the particles' trial stresses and tangents (Implicit/ParticleEquilibrium.h), the
// residual r = f_ext - f_int (- m a) and Newton's Jacobian K, the hourglass stabilization
// (Implicit/HourglassStabilization.h) and the regularization of the free bodies' rigid modes.
#include <omp.h>

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <variant>

#include "Components/MPM/Implicit/EquilibriumSolver.h"
#include "Components/MPM/Implicit/HourglassStabilization.h"
#include "Components/MPM/Implicit/Newmark.h"
#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"

namespace anode {

namespace {

// The free body's rigid modes: alpha m I added to each node's diagonal block, alpha this fraction
// of the mean diagonal stiffness per unit nodal mass. It changes Newton's path, not the
// equilibrium it converges to (the residual is exact).
constexpr double kRigidModeRegularization = 1e-10;

}  // namespace

void EquilibriumSolver::assemble(Collective every, const EquilibriumProblem& problem, double dt,
                                 double stabilization, bool withTangent) {
  if (withTangent) K_.clearValues();
  const size_t materials = problem.materials.size();
  P_.resize(materials);
  A_.resize(materials);
  for (size_t m = 0; m < materials; ++m)
    std::visit(
        [&](const auto* model) {
          evaluateTrialStress(problem.materials[m].particles, problem.weights[m], *model,
                              u_[problem.fieldOf[m]], problem.concentrationChange[m], dt, P_[m],
                              withTangent ? &A_[m] : nullptr);
        },
        problem.materials[m].model->concrete().model);
  const bool firstOfStep = stabilization > 0 && hourglass_.empty();
  if (firstOfStep) {
    hourglass_.assign(residualPattern().column.size(), 0.0);
    if (reduced_) hourglassTangent_.assign(K_.column.size(), 0.0);
    hourglassLoad_.assign(3 * unknown_.size(), 0.0);
  }
  residual_.assign(3 * unknown_.size(), 0.0);
  // Each thread sums the rows of one range of block rows, particle by particle: every row's sum
  // has the order of one thread's, whatever the number of threads.
  const int rows = static_cast<int>(unknown_.size());
#pragma omp parallel
  {
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    const int first = static_cast<int>(static_cast<long>(rows) * t / threads);
    const int last = static_cast<int>(static_cast<long>(rows) * (t + 1) / threads);
    for (size_t m = 0; m < materials; ++m) {
      addInternalForce(problem, m, first, last, withTangent);
      if (firstOfStep) addHourglassStiffness(problem, m, stabilization, first, last);
    }
    if (stabilization > 0) applyHourglassStiffness(first, last, withTangent);
  }
  completeOverRanks(every, problem, residual_, 3, false);
  // Gravity and, in implicit dynamics, the inertia (the nodal masses, velocities and
  // accelerations are complete on every rank), the fixed components' rows.
  const bool dynamic = !problem.velocity.empty();
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    Vec3 force = problem.mass[f][k] * problem.gravity;
    if (dynamic)
      force -= problem.mass[f][k] * newmarkAcceleration(u_[f][k], problem.velocity[f][k],
                                                        problem.acceleration[f][k], dt);
    for (int a = 0; a < 3; ++a) residual_[3 * r + a] += force[a];
  }
  for (int i : fixed_) residual_[i] = 0;
  if (!withTangent) return;
  if (dynamic)  // on the owner's rows, as each rank's K holds its particles' parts
    for (int r = 0; r < rows_.owned; ++r) {
      const auto [f, k] = unknown_[r];
      K_.at(r, r) += newmarkStiffnessPerMass(dt) * problem.mass[f][k] * Mat3::Identity();
    }
  // The rigid-mode regularization, on the owner's rows (each rank's K holds its particles' parts).
  double sums[2] = {0, 0};  // diagonal, mass
  for (int r = 0; r < static_cast<int>(unknown_.size()); ++r) {
    const auto [f, k] = unknown_[r];
    if (K_.rowStart[r + 1] > K_.rowStart[r]) sums[0] += K_.at(r, r).trace();
    if (r < rows_.owned) sums[1] += 3 * problem.mass[f][k];
  }
  collective::sum(every, sums, 2);
  const double alpha = sums[1] > 0 ? kRigidModeRegularization * sums[0] / sums[1] : 0;
  for (int r = 0; r < rows_.owned; ++r) {
    const auto [f, k] = unknown_[r];
    K_.at(r, r) += alpha * problem.mass[f][k] * Mat3::Identity();
  }
}

void EquilibriumSolver::addInternalForce(const EquilibriumProblem& problem, size_t m, int first,
                                         int last, bool withTangent) {
  const ParticleSet& p = problem.materials[m].particles;
  const InterpolationWeights& W = problem.weights[m];
  const std::vector<int>& row = row_[problem.fieldOf[m]];
  const std::vector<char>& strong = strong_[m];
  // Tm(a + 3 c, f) = V sum_d ge_d A(3 a + d, 3 c + f): the block (e, g) of K, column-major as a
  // Mat3 stores it, is Tm gg.
  Eigen::Matrix<double, 9, 3> Tm;
  std::vector<std::pair<int, int>> columns;  // (column, g) of the nodes it couples, sorted
  for (const size_t i : order_[m]) {
    const double V = p.volume[i];
    const size_t b = W.offset[i];
    if (withTangent) {
      columns.clear();
      for (int g = 0; g < W.count[i]; ++g)
        if (strong[b + g]) columns.emplace_back(row[W.node[b + g]], g);
      // The nodes come in grid order, and so do the rows of one rank's own nodes.
      if (!std::is_sorted(columns.begin(), columns.end()))
        std::sort(columns.begin(), columns.end());
    }
    for (int e = 0; e < W.count[i]; ++e) {
      const int r = row[W.node[b + e]];
      if (r < first || r >= last) continue;
      const Vec3& ge = W.gradient[b + e];
      const Vec3 force = V * P_[m][i] * ge;  // f_int of this particle at node e
      for (int a = 0; a < 3; ++a) residual_[3 * r + a] -= force[a];
      if (!withTangent) continue;
      const Mat9& A = A_[m][i];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          for (int f = 0; f < 3; ++f)
            Tm(a + 3 * c, f) = V * (ge[0] * A(3 * a, 3 * c + f) + ge[1] * A(3 * a + 1, 3 * c + f) +
                                    ge[2] * A(3 * a + 2, 3 * c + f));
      // A node the particle does not couple: its stiffness there on the diagonal block alone.
      if (!strong[b + e]) {
        Eigen::Map<Eigen::Matrix<double, 9, 1>>(K_.block[diagonal_[r]].data()) += Tm * ge;
        continue;
      }
      // Row r holds every column of the nodes it couples: one pass along it finds their blocks.
      int j = K_.rowStart[r];
      for (const auto& [column, g] : columns) {
        while (K_.column[j] < column) ++j;
        Eigen::Map<Eigen::Matrix<double, 9, 1>>(K_.block[j].data()) += Tm * W.gradient[b + g];
      }
    }
  }
}

void EquilibriumSolver::addHourglassStiffness(const EquilibriumProblem& problem, size_t m,
                                              double stabilization, int first, int last) {
  const ParticleSet& p = problem.materials[m].particles;
  const InterpolationWeights& W = problem.weights[m];
  const int f = problem.fieldOf[m];
  const std::vector<int>& row = row_[f];
  const std::vector<char>& strong = strong_[m];
  const double h2 = problem.grid.dx.squaredNorm() / 3;
  const BlockMatrix& pattern = residualPattern();
  std::vector<std::pair<int, int>> all, coupled;
  for (const size_t i : order_[m]) {
    const size_t b = W.offset[i];
    const int n = W.count[i];
    bool reaches = false;
    for (int j = 0; j < n && !reaches; ++j)
      reaches = row[W.node[b + j]] >= first && row[W.node[b + j]] < last;
    if (!reaches) continue;
    // kappa V, fixed in the step's first assembly (at the first iterate): the energy stays
    // quadratic in u, and Newton's Jacobian exact.
    const double stiffness = stabilization * p.volume[i] * A_[m][i].trace() / 9 / h2;
    const Eigen::MatrixXd M = hourglassMatrix(problem.grid, W, static_cast<long>(i), p.x[i]);
    // The memory's force kappa V A^T diag(S) m, by support entry (columns).
    Eigen::Matrix3Xd remembered = weightedMemory(p, i, problem.grid, W);
    if (!remembered.isZero(0))
      remembered =
          stiffness * remembered * nonAffineOperator(problem.grid, W, static_cast<long>(i), p.x[i]);
    // (column, k) of the particle's unknown nodes and, in a reduced Jacobian, of those it couples
    // in K_, sorted: one pass along a row finds their entries.
    all.clear();
    coupled.clear();
    for (int k = 0; k < n; ++k) {
      const int c = row[W.node[b + k]];
      if (c >= 0) all.emplace_back(c, k);
      if (reduced_ && strong[b + k]) coupled.emplace_back(c, k);
    }
    if (!std::is_sorted(all.begin(), all.end())) {
      std::sort(all.begin(), all.end());
      std::sort(coupled.begin(), coupled.end());
    }
    for (int j = 0; j < n; ++j) {
      const int r = row[W.node[b + j]];
      if (r < first || r >= last) continue;
      int at = pattern.rowStart[r];
      for (const auto& [c, k] : all) {
        while (pattern.column[at] < c) ++at;
        hourglass_[at] += stiffness * M(j, k);
      }
      // In a reduced Jacobian as the particle's stiffness (addInternalForce); otherwise all of
      // hourglass_ is in it.
      if (reduced_) {
        if (strong[b + j]) {
          at = K_.rowStart[r];
          for (const auto& [c, k] : coupled) {
            while (K_.column[at] < c) ++at;
            hourglassTangent_[at] += stiffness * M(j, k);
          }
        } else {
          hourglassTangent_[diagonal_[r]] += stiffness * M(j, j);
        }
      }
      Vec3 force = remembered.col(j);
      for (int k = 0; k < n; ++k)
        if (row[W.node[b + k]] < 0)  // a node left out: its u stays as set at the start
          force += stiffness * M(j, k) * u_[f][W.node[b + k]];
      for (int a = 0; a < 3; ++a) hourglassLoad_[3 * r + a] += force[a];
    }
  }
}

void EquilibriumSolver::applyHourglassStiffness(int first, int last, bool withTangent) {
  const BlockMatrix& pattern = residualPattern();
  const std::vector<double>& tangent = reduced_ ? hourglassTangent_ : hourglass_;
  for (int r = first; r < last; ++r) {
    Vec3 force(hourglassLoad_[3 * r], hourglassLoad_[3 * r + 1], hourglassLoad_[3 * r + 2]);
    for (int j = pattern.rowStart[r]; j < pattern.rowStart[r + 1]; ++j) {
      const auto [f, k] = unknown_[pattern.column[j]];
      force += hourglass_[j] * u_[f][k];
    }
    for (int a = 0; a < 3; ++a) residual_[3 * r + a] -= force[a];
    if (withTangent)
      for (int j = K_.rowStart[r]; j < K_.rowStart[r + 1]; ++j)
        K_.block[j].diagonal().array() += tangent[j];
  }
}

EquilibriumSolver::Linearization EquilibriumSolver::linearizeAt(
    Collective every, const EquilibriumProblem& problem, double dt, const ImplicitOptions& options,
    const std::vector<std::vector<Vec3>>& u, const std::vector<std::vector<Vec3>>& du) {
  if (problem.ghosts) throw std::invalid_argument("EquilibriumSolver::linearizeAt: one rank only");
  numberUnknowns(every, problem, options.jacobianCouplingShare);
  startFromPrescribed(problem);
  K_.block.assign(K_.column.size(), Mat3::Zero());
  hourglass_.clear();
  hourglassTangent_.clear();
  // At the start first: the hourglass stiffness fixed where a solve's first assembly fixes it, so
  // that r is one function of u over calls.
  assemble(every, problem, dt, options.hourglassStabilization, true);
  u_ = u;
  assemble(every, problem, dt, options.hourglassStabilization, true);
  std::vector<double> product(residual_.size(), 0.0);
  for (int r = 0; r < K_.rows(); ++r)
    for (int j = K_.rowStart[r]; j < K_.rowStart[r + 1]; ++j) {
      const auto [f, k] = unknown_[K_.column[j]];
      const Vec3 y = K_.block[j] * du[f][k];
      for (int a = 0; a < 3; ++a) product[3 * r + a] += y[a];
    }
  for (int i : fixed_) product[i] = 0;
  const std::vector<Vec3> none(problem.grid.numNodes(), Vec3::Zero());
  Linearization at{std::vector<std::vector<Vec3>>(row_.size(), none),
                   std::vector<std::vector<Vec3>>(row_.size(), none)};
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < 3; ++a) {
      at.residual[f][k][a] = residual_[3 * r + a];
      at.jacobianTimesDirection[f][k][a] = product[3 * r + a];
    }
  }
  return at;
}

}  // namespace anode
