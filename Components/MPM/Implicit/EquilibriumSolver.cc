#include "Components/MPM/Implicit/EquilibriumSolver.h"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <utility>
#include <variant>

#include "Components/MPM/Implicit/HourglassStabilization.h"
#include "Components/MPM/Implicit/Newmark.h"
#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"

namespace anode {

namespace {

// Newton's linear solves are inexact (Eisenstat and Walker's second choice): the relative residual
// of iteration k's solve is 0.9 (|r_k| / |r_k-1|)^2, within [kLinearToleranceLeast,
// kLinearToleranceMost], and kLinearToleranceMost in the first iteration. Early iterations, far
// from the equilibrium, need no accurate correction; the last ones are solved to 1e-9.
constexpr double kLinearToleranceMost = 1e-1, kLinearToleranceLeast = 1e-9;
// The first iteration from a solved prediction taken (EquilibriumProblem::predictedIsSolved, the
// trapezoidal step's own solve): the iterate is near the equilibrium, where a correction to 0.1
// wastes the iteration. The large pillar's cycle, steps 13-14 from its step-12 checkpoint: 16
// Newton iterations with 3e-3 or 1e-3 (in the predictions' first iterations too), 18 with 1e-2,
// 20 with 0.1. Not from the last step's motion, an extrapolation: Figure 4's pillar with 3e-3
// there took 171 Newton and 1,717 Krylov iterations against 167 and 1,521.
constexpr double kLinearToleranceFromSolvedPrediction = 3e-3;
// The free body's rigid modes: alpha m I added to each node's diagonal block, alpha this fraction
// of the mean diagonal stiffness per unit nodal mass. It changes Newton's path, not the
// equilibrium it converges to (the residual is exact).
constexpr double kRigidModeRegularization = 1e-10;

// A node is an unknown when its mass exceeds this fraction of its field's largest nodal mass.
// Below it a node carries only round-off weights (a particle at the edge of its support): its
// displacement would be set by stiffness at round-off level, so it is left out with the particle
// entries that reach it, as an explicit step gives a massless node no acceleration.
constexpr double kUnknownNodeMass = 1e-9;

// Newton's line search: the fractions 1, 1/2, ... of the correction tried (this many) until the
// residual's norm falls below the last iterate's. When none lowers it, the fraction with the
// lowest residual is taken (near convergence, where round-off hides the descent, any of them
// is within Newton's tolerance of the others).
constexpr int kLineSearchTrials = 5;

// <jacobian_reuse>: Newton keeps the Jacobian of its last iteration (K and the linear solver's
// matrix as they are) for the next correction when the last correction was small and came fast: its
// |du|^2 ratio below kKeptTangentRatio and at most kKeptTangentContraction of the one before (the
// first's measured against 1). Then the Jacobian changes by O(|du|) of the step while the next
// correction is smaller still, and the iteration costs the residual and a linear solve, not the
// particles' tangents. Far from the equilibrium, or when Newton slowed, the tangent is assembled
// anew. The large pillar's cycle, steps 13-14 from the step-12 checkpoint (ratios of its own
// solves 4.7e-3, 1.5e-4, 3.2e-7 and 5.6e-3, 4.5e-5, 2.1e-6): 12 Newton iterations, 8 of them
// with a new Jacobian (the last of each solve kept it), as many as without the rule; with 1e-2
// instead (keeping it after the own solve's first correction, 7.5e-3) the second step took 17
// iterations instead of 3.
constexpr double kKeptTangentRatio = 1e-3, kKeptTangentContraction = 0.1;

bool keepsTangentOfLastIteration(const std::vector<std::pair<double, double>>& ratios) {
  const double last = ratios.back().first;
  const double before = ratios.size() > 1 ? ratios[ratios.size() - 2].first : 1.0;
  return last < kKeptTangentRatio && last <= kKeptTangentContraction * before;
}

}  // namespace

void EquilibriumSolver::useTimers(TaskTimers& timers) {
  timers_ = &timers;
  assemblyTask_ = timers.task("assembleEquilibrium");
  solveTask_ = timers.task("solveLinearSystem");
}

void EquilibriumSolver::numberUnknowns(const EquilibriumProblem& problem,
                                       double jacobianCouplingShare) {
  const int fields = 1 + *std::max_element(problem.fieldOf.begin(), problem.fieldOf.end());
  const int nodes = problem.grid.numNodes();
  const auto owns = [&](int k) { return problem.owned.empty() || problem.owned[k] != 0; };
  std::vector<double> least(fields);
  for (int f = 0; f < fields; ++f) {
    const std::vector<double>& mass = problem.mass[f];
    least[f] = *std::max_element(mass.begin(), mass.end());
  }
  collective::maximum(least.data(), fields);
  row_.assign(fields, std::vector<int>(nodes, -1));
  unknown_.clear();
  // Block rows in (field, node) order, this rank's own nodes first.
  for (bool own : {true, false}) {
    for (int f = 0; f < fields; ++f)
      for (int k = 0; k < nodes; ++k)
        if (problem.mass[f][k] > kUnknownNodeMass * least[f] && owns(k) == own) {
          row_[f][k] = static_cast<int>(unknown_.size());
          unknown_.emplace_back(f, k);
        }
    if (own) rows_.owned = static_cast<int>(unknown_.size());
  }
  // Global rows: the ranks' own rows in rank order; a shared node's from its owner.
  const int first = static_cast<int>(collective::exclusiveSum(rows_.owned));
  std::vector<double> global(unknown_.size(), -1.0);
  for (int r = 0; r < rows_.owned; ++r) global[r] = first + r;
  completeOverRanks(problem, global, 1, true);
  rows_.globalRow.resize(unknown_.size());
  for (size_t r = 0; r < unknown_.size(); ++r) {
    if (global[r] < 0)
      throw std::logic_error("a shared unknown node without its owner's row (GhostNodes reach)");
    rows_.globalRow[r] = static_cast<int>(global[r]);
  }
  // Which of each particle's unknown nodes it couples in Newton's Jacobian: those of which it
  // holds at least jacobianCouplingShare of the mass. And the order the assembly takes the
  // particles in: by their first node, so that consecutive particles add to nearby rows of K.
  reduced_ = jacobianCouplingShare > 0;
  strong_.resize(problem.materials.size());
  order_.resize(problem.materials.size());
  for (size_t m = 0; m < problem.materials.size(); ++m) {
    const InterpolationWeights& W = problem.weights[m];
    const ParticleSet& p = problem.materials[m].particles;
    const std::vector<double>& mass = problem.mass[problem.fieldOf[m]];
    const std::vector<int>& row = row_[problem.fieldOf[m]];
    strong_[m].assign(W.node.size(), 0);
    order_[m].resize(p.count());
    std::iota(order_[m].begin(), order_[m].end(), 0);
    const auto firstNode = [&](size_t i) { return W.count[i] > 0 ? W.node[W.offset[i]] : -1; };
    std::stable_sort(order_[m].begin(), order_[m].end(),
                     [&](size_t a, size_t b) { return firstNode(a) < firstNode(b); });
    for (size_t i = 0; i < p.count(); ++i)
      for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e)
        strong_[m][e] = row[W.node[e]] >= 0 &&
                        p.mass[i] * W.weight[e] >= jacobianCouplingShare * mass[W.node[e]];
  }
  // The particles reaching each row (numbered over the materials from each material's
  // particleStart, with whether they couple it), then each row's columns as the union of those
  // particles' unknown nodes (marked per row, no duplicates stored): in K_ those of the particles
  // coupling the row, the strong ones; all of them in couplings_ when the Jacobian is reduced
  // (otherwise they are K_'s).
  const int rows = static_cast<int>(unknown_.size());
  std::vector<long> particleStart(problem.materials.size() + 1, 0);
  for (size_t m = 0; m < problem.materials.size(); ++m)
    particleStart[m + 1] =
        particleStart[m] + static_cast<long>(problem.materials[m].particles.count());
  std::vector<long> reachStart(rows + 1, 0);
  const auto eachReach = [&](const auto& visit) {
    for (size_t m = 0; m < problem.materials.size(); ++m) {
      const InterpolationWeights& W = problem.weights[m];
      const std::vector<int>& row = row_[problem.fieldOf[m]];
      for (size_t i = 0; i < problem.materials[m].particles.count(); ++i)
        for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e)
          if (row[W.node[e]] >= 0)
            visit(row[W.node[e]], particleStart[m] + static_cast<long>(i), strong_[m][e]);
    }
  };
  eachReach([&](int r, long, bool) { ++reachStart[r + 1]; });
  for (int r = 0; r < rows; ++r) reachStart[r + 1] += reachStart[r];
  std::vector<long> reaching(reachStart[rows]);
  std::vector<char> couples(reachStart[rows]);
  {
    std::vector<long> next(reachStart.begin(), reachStart.end() - 1);
    eachReach([&](int r, long particle, bool strong) {
      couples[next[r]] = strong;
      reaching[next[r]++] = particle;
    });
  }
  K_ = BlockMatrix();
  couplings_ = BlockMatrix();
  std::vector<int> inCouplings(reduced_ ? rows : 0, -1), inK(rows, -1), all, coupled;
  const auto mark = [](std::vector<int>& marked, std::vector<int>& columns, int r, int c) {
    if (marked[c] == r) return;
    marked[c] = r;
    columns.push_back(c);
  };
  for (int r = 0; r < rows; ++r) {
    all.clear();
    coupled.clear();
    if (r < rows_.owned) {  // the owner's diagonal
      if (reduced_) mark(inCouplings, all, r, r);
      mark(inK, coupled, r, r);
    }
    for (long k = reachStart[r]; k < reachStart[r + 1]; ++k) {
      const size_t m = std::upper_bound(particleStart.begin(), particleStart.end(), reaching[k]) -
                       particleStart.begin() - 1;
      const size_t i = static_cast<size_t>(reaching[k] - particleStart[m]);
      const InterpolationWeights& W = problem.weights[m];
      const std::vector<int>& row = row_[problem.fieldOf[m]];
      for (size_t g = W.offset[i]; g < W.offset[i] + W.count[i]; ++g) {
        const int c = row[W.node[g]];
        if (c < 0) continue;
        if (reduced_) mark(inCouplings, all, r, c);
        // A particle not coupling row r keeps its stiffness there on the diagonal block.
        if (c == r || (couples[k] && strong_[m][g])) mark(inK, coupled, r, c);
      }
    }
    for (auto [pattern, columns] : {std::pair{&couplings_, &all}, std::pair{&K_, &coupled}}) {
      if (pattern == &couplings_ && !reduced_) continue;
      std::sort(columns->begin(), columns->end());
      pattern->column.insert(pattern->column.end(), columns->begin(), columns->end());
      pattern->rowStart.push_back(static_cast<int>(pattern->column.size()));
    }
  }
  diagonal_.resize(rows);
  for (int r = 0; r < rows; ++r)
    diagonal_[r] = K_.rowStart[r + 1] > K_.rowStart[r] ? K_.indexOf(r, r) : -1;
  coordinates_.resize(3 * static_cast<size_t>(rows_.owned));
  fixed_.clear();
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    const Vec3i ijk = problem.grid.nodeOf(k);
    const Vec3 x = problem.grid.nodePosition(ijk.x(), ijk.y(), ijk.z());
    for (int a = 0; a < 3; ++a) {
      if (static_cast<int>(r) < rows_.owned) coordinates_[3 * r + a] = x[a];
      if (!std::isnan(problem.prescribed[f][k][a])) fixed_.push_back(static_cast<int>(3 * r + a));
    }
  }
}

void EquilibriumSolver::removeRigidMotionOfFreeBodies(const EquilibriumProblem& problem,
                                                      std::vector<double>& du) const {
  if (!problem.velocity.empty()) return;  // implicit dynamics: the inertia sets them
  // The six rigid modes at a node: translations, then rotations about the grid's centre (in
  // units of its half diagonal, so all six are of one size).
  const Vec3 centre = problem.grid.lower + 0.5 * (problem.grid.upper - problem.grid.lower);
  const double length = 0.5 * (problem.grid.upper - problem.grid.lower).norm();
  using Modes = Eigen::Matrix<double, 3, 6>;
  const auto modesAt = [&](int k) {
    const Vec3i ijk = problem.grid.nodeOf(k);
    const Vec3 x = (problem.grid.nodePosition(ijk.x(), ijk.y(), ijk.z()) - centre) / length;
    Modes phi;
    for (int a = 0; a < 3; ++a) {
      phi.col(a) = Vec3::Unit(a);
      phi.col(3 + a) = Vec3::Unit(a).cross(x);
    }
    return phi;
  };
  std::vector<char> isFixed(du.size(), 0);
  for (int i : fixed_) isFixed[i] = 1;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  for (size_t f = 0; f < row_.size(); ++f) {
    // Over the owned rows of the field: the modes' products on the fixed components, their
    // mass-weighted products, and du's mass-weighted part along each.
    double values[78] = {};
    struct {
      Eigen::Map<Mat6> fixed, mass;
      Eigen::Map<Vec6> du;
    } sums{Eigen::Map<Mat6>(values), Eigen::Map<Mat6>(values + 36), Eigen::Map<Vec6>(values + 72)};
    for (int r = 0; r < rows_.owned; ++r) {
      if (unknown_[r].first != static_cast<int>(f)) continue;
      const int k = unknown_[r].second;
      const Modes phi = modesAt(k);
      const double m = problem.mass[f][k];
      sums.mass += m * phi.transpose() * phi;
      sums.du += m * phi.transpose() * Vec3(du[3 * r], du[3 * r + 1], du[3 * r + 2]);
      for (int a = 0; a < 3; ++a)
        if (isFixed[3 * r + a]) sums.fixed += phi.row(a).transpose() * phi.row(a);
    }
    collective::sum(values, 78);
    if (!(sums.mass.trace() > 0)) continue;
    // The rigid modes the fixed components do not hold (those vanishing on every one of them).
    Eigen::SelfAdjointEigenSolver<Mat6> held(sums.fixed);
    const double scale = std::max(1.0, held.eigenvalues().maxCoeff());
    std::vector<int> free;
    for (int a = 0; a < 6; ++a)
      if (held.eigenvalues()[a] <= 1e-12 * scale) free.push_back(a);
    if (free.empty()) continue;
    Eigen::MatrixXd Z(6, free.size());
    for (size_t a = 0; a < free.size(); ++a) Z.col(a) = held.eigenvectors().col(free[a]);
    // du's part in them, by mass (least squares where the nodes do not tell the modes apart).
    const Eigen::MatrixXd inZ = Z.transpose() * sums.mass * Z;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> principal(inZ);
    const Eigen::VectorXd along = Z.transpose() * sums.du;
    Eigen::VectorXd amounts = Eigen::VectorXd::Zero(free.size());
    for (int a = 0; a < static_cast<int>(free.size()); ++a) {
      const double moment = principal.eigenvalues()[a];
      if (moment > 1e-12 * principal.eigenvalues().maxCoeff())
        amounts +=
            principal.eigenvectors().col(a) * (principal.eigenvectors().col(a).dot(along) / moment);
    }
    const Vec6 rigid = Z * amounts;
    for (size_t r = 0; r < unknown_.size(); ++r) {
      if (unknown_[r].first != static_cast<int>(f)) continue;
      const Vec3 motion = modesAt(unknown_[r].second) * rigid;
      for (int a = 0; a < 3; ++a) du[3 * r + a] -= motion[a];
    }
  }
}

void EquilibriumSolver::completeOverRanks(const EquilibriumProblem& problem,
                                          std::vector<double>& values, int width,
                                          bool fromOwners) const {
  if (!problem.ghosts) return;
  const int rows = static_cast<int>(unknown_.size());
  const size_t nodes = static_cast<size_t>(problem.grid.numNodes());
  std::vector<std::vector<double>> byNode(row_.size(), std::vector<double>(width * nodes, 0.0));
  for (int r = 0; r < (fromOwners ? rows_.owned : rows); ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < width; ++a) byNode[f][width * k + a] = values[width * r + a];
  }
  std::vector<NodeArray> arrays;
  for (std::vector<double>& a : byNode) arrays.push_back({a.data(), width});
  problem.ghosts->sumOverRanks(Collective{}, arrays);
  for (int r = fromOwners ? rows_.owned : 0; r < rows; ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < width; ++a) values[width * r + a] = byNode[f][width * k + a];
  }
}

double EquilibriumSolver::ownedDot(const std::vector<double>& a,
                                   const std::vector<double>& b) const {
  double d = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(rows_.owned); ++i) d += a[i] * b[i];
  return collective::sum(d);
}

void EquilibriumSolver::assemble(const EquilibriumProblem& problem, double dt, double stabilization,
                                 bool withTangent) {
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
  completeOverRanks(problem, residual_, 3, false);
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
  collective::sum(sums, 2);
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
      for (int k = 0; k < n; ++k)
        if (row[W.node[b + k]] < 0) {  // a node left out: its u stays as set at the start
          const Vec3 force = stiffness * M(j, k) * u_[f][W.node[b + k]];
          for (int a = 0; a < 3; ++a) hourglassLoad_[3 * r + a] += force[a];
        }
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

void EquilibriumSolver::addToDisplacement(const std::vector<double>& du, double scale) {
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    u_[f][k] += scale * Vec3(du[3 * r], du[3 * r + 1], du[3 * r + 2]);
  }
}

bool EquilibriumSolver::takeStep(const EquilibriumProblem& problem, double dt, double stabilization,
                                 const std::vector<double>& du, double residualNorm) {
  std::optional<ScopedTimer> s;
  if (timers_) s.emplace(*timers_, assemblyTask_);
  double lowest = std::numeric_limits<double>::infinity(), best = 1.0;
  for (int halvings = 0; halvings < kLineSearchTrials; ++halvings) {
    const double step = std::ldexp(1.0, -halvings);
    addToDisplacement(du, step);
    assemble(problem, dt, stabilization, false);
    const double norm = ownedDot(residual_, residual_);
    if (norm < residualNorm) return true;  // false for NaN
    if (norm < lowest) lowest = norm, best = step;
    addToDisplacement(du, -step);
  }
  addToDisplacement(du, best);
  return false;
}

bool EquilibriumSolver::tryPrediction(const EquilibriumProblem& problem, double dt,
                                      double stabilization, double& normReference,
                                      double& energyReference) {
  if (problem.predicted.empty()) return false;
  std::optional<ScopedTimer> s;
  if (timers_) s.emplace(*timers_, assemblyTask_);
  std::vector<double> step(residual_.size(), 0.0);
  for (size_t r = 0; r < unknown_.size(); ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < 3; ++a)
      if (std::isnan(problem.prescribed[f][k][a])) step[3 * r + a] = problem.predicted[f][k][a];
  }
  const double startNorm = ownedDot(residual_, residual_);
  const double size = ownedDot(step, step), work = std::abs(ownedDot(step, residual_));
  if (!(size > 0)) return false;
  std::vector<double> startResidual = residual_;
  addToDisplacement(step, 1.0);
  assemble(problem, dt, stabilization, false);
  if (ownedDot(residual_, residual_) < startNorm) {  // false for NaN
    normReference = size;
    energyReference = work;
    return true;
  }
  addToDisplacement(step, -1.0);
  residual_ = std::move(startResidual);
  return false;
}

void EquilibriumSolver::computeEndOfStepAcceleration(const EquilibriumProblem& problem, double dt) {
  acceleration_.assign(row_.size(), std::vector<Vec3>(problem.grid.numNodes(), Vec3::Zero()));
  for (const auto& [f, k] : unknown_)
    acceleration_[f][k] =
        newmarkAcceleration(u_[f][k], problem.velocity[f][k], problem.acceleration[f][k], dt);
}

namespace {

// The same values bit for bit (the free components' NaN included).
template <class T>
bool sameBits(const std::vector<std::vector<T>>& a, const std::vector<std::vector<T>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t f = 0; f < a.size(); ++f)
    if (a[f].size() != b[f].size() ||
        std::memcmp(a[f].data(), b[f].data(), a[f].size() * sizeof(T)) != 0)
      return false;
  return true;
}

}  // namespace

bool EquilibriumSolver::takesKeptLinearSolver(const EquilibriumProblem& problem) const {
  if (!problem.useKeptLinearSolver) return false;
  const bool same = linearSolver_ && sameBits(problem.mass, numberedMass_) &&
                    sameBits(problem.prescribed, numberedPrescribed_);
  return collective::minimum(same ? 1.0 : 0.0) > 0;
}

void EquilibriumSolver::buildLinearSolver(const EquilibriumProblem& problem) {
  linearSolver_.reset();  // its PETSc objects freed before the new ones are made
  linearSolver_ = std::make_unique<LinearSolver>(K_, rows_, fixed_, coordinates_);
  numberedMass_.clear();
  numberedPrescribed_.clear();
  if (!problem.keepLinearSolver) return;
  numberedMass_ = problem.mass;
  numberedPrescribed_ = problem.prescribed;
}

NewtonReport EquilibriumSolver::solve(const EquilibriumProblem& problem, double dt,
                                      const ImplicitOptions& options) {
  std::optional<ScopedTimer> setUp;
  if (timers_) setUp.emplace(*timers_, assemblyTask_);
  // A kept solver's unknowns and pattern are this solve's, and so are its solve's last tangent
  // and the hourglass stiffness of the same start: the first iteration assembles the residual.
  const bool solverKept = takesKeptLinearSolver(problem);
  if (!solverKept) numberUnknowns(problem, options.jacobianCouplingShare);
  u_.assign(row_.size(), std::vector<Vec3>(problem.grid.numNodes(), Vec3::Zero()));
  for (size_t f = 0; f < row_.size(); ++f)
    for (int k = 0; k < problem.grid.numNodes(); ++k)
      for (int a = 0; a < 3; ++a)
        if (!std::isnan(problem.prescribed[f][k][a])) u_[f][k][a] = problem.prescribed[f][k][a];
  const bool tangentKept = solverKept && !kept_.block.empty();
  if (tangentKept) {
    K_.block = std::move(kept_.block);
    hourglass_ = std::move(kept_.hourglass);
    hourglassTangent_ = std::move(kept_.hourglassTangent);
    hourglassLoad_ = std::move(kept_.hourglassLoad);
  }
  kept_ = KeptTangent{};  // freed before a new K's values are allocated
  if (!tangentKept) {
    K_.block.assign(K_.column.size(), Mat3::Zero());
    hourglass_.clear();
    hourglassTangent_.clear();
  }
  if (!solverKept) buildLinearSolver(problem);
  setUp.reset();
  // Every return frees the linear solver unless the next solve is to take it.
  struct Release {
    std::unique_ptr<LinearSolver>& solver;
    bool keep;
    ~Release() {
      if (!keep) solver.reset();
    }
  } release{linearSolver_, problem.keepLinearSolver};
  NewtonReport report;
  double normMax = 0, qNorm0 = 0, lastResidualNorm = 0;
  std::vector<double> du;
  bool residualCurrent = false;  // residual_ is at u (the line search's accepted trial)
  while (true) {
    if (report.iterations >= options.maxIterations) {
      report.failure = "no convergence in " + std::to_string(options.maxIterations) +
                       " iterations (<iters_before_timestep_restart>)";
      return report;
    }
    ++report.iterations;
    const bool keepTangent =
        report.iterations == 1
            ? tangentKept
            : options.jacobianReuse && keepsTangentOfLastIteration(report.ratios);
    if (!(keepTangent && residualCurrent)) {
      std::optional<ScopedTimer> s;
      if (timers_) s.emplace(*timers_, assemblyTask_);
      assemble(problem, dt, options.hourglassStabilization, !keepTangent);
    }
    if (!keepTangent) ++report.newTangents;
    bool fromSolvedPrediction = false;
    if (report.iterations == 1)
      fromSolvedPrediction =
          tryPrediction(problem, dt, options.hourglassStabilization, normMax, qNorm0) &&
          problem.predictedIsSolved;
    const double residualNorm = ownedDot(residual_, residual_);
    const double tolerance =
        report.iterations == 1
            ? (fromSolvedPrediction ? kLinearToleranceFromSolvedPrediction : kLinearToleranceMost)
            : std::clamp(0.9 * residualNorm / lastResidualNorm, kLinearToleranceLeast,
                         kLinearToleranceMost);
    lastResidualNorm = residualNorm;
    report.linearTolerances.push_back(tolerance);
    LinearSolve linear;
    {
      std::optional<ScopedTimer> s;
      if (timers_) s.emplace(*timers_, solveTask_);
      linear = linearSolver_->solve(K_, residual_, tolerance, du, !keepTangent);
      du.resize(residual_.size());
      completeOverRanks(problem, du, 3, true);
    }
    report.krylovIterations += linear.iterations;
    if (linear.newPreconditioner) ++report.preconditionerSetUps;
    if (!linear.converged) {
      report.failure = "the linear solve did not converge (" + linear.reason + ", " +
                       std::to_string(linear.iterations) + " iterations)";
      return report;
    }
    removeRigidMotionOfFreeBodies(problem, du);
    const double norm = ownedDot(du, du), qNorm = ownedDot(du, residual_);
    normMax = std::max(normMax, norm);
    if (report.iterations == 1) qNorm0 = std::max(qNorm0, std::abs(qNorm));
    // The ratios measure the whole correction, the distance Newton still sees to the
    // equilibrium, whatever fraction of it the line search takes.
    const double dispRatio = norm / (normMax + 1e-100), energyRatio = qNorm / (qNorm0 + 1e-100);
    report.ratios.emplace_back(dispRatio, energyRatio);
    if (!std::isfinite(dispRatio) || !std::isfinite(energyRatio)) {
      report.failure = "a residual that is not a number";
      return report;
    }
    // du.r = du.K du up to the linear solve's error: a negative du.r beyond that error shows K
    // is not positive along du; within it, |du.r| is what the energy test measures.
    if (qNorm < -linear.energySlack) {
      report.failure = "a negative energy norm du.r (the Jacobian is not positive there)";
      return report;
    }
    const bool dispDone =
        dispRatio <= options.convergenceDisp || normMax <= options.convergenceDisp;
    const bool energyDone =
        std::abs(energyRatio) <= options.convergenceEnergy || qNorm0 <= options.convergenceEnergy;
    if (dispDone && energyDone) {
      // The last correction is taken whole: within Newton's tolerance the line search has
      // nothing to choose.
      addToDisplacement(du, 1.0);
      report.converged = true;
      if (problem.keepLinearSolver)
        kept_ = KeptTangent{std::move(K_.block), std::move(hourglass_),
                            std::move(hourglassTangent_), std::move(hourglassLoad_)};
      if (!problem.velocity.empty()) computeEndOfStepAcceleration(problem, dt);
      return report;
    }
    residualCurrent = takeStep(problem, dt, options.hourglassStabilization, du, residualNorm);
  }
}

}  // namespace anode
