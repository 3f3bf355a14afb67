// The unknowns of the equilibrium step and their layout for the linear solver
// (EquilibriumSolver.h): which nodes of each velocity field carry unknowns, their block rows and
// global rows over the ranks, the patterns of the Jacobian and of the residual's couplings, the
// components the boundary conditions fix; the sums and dot products over the ranks' rows; and the
// linear solver built for (or kept with) that layout.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "Components/MPM/Implicit/EquilibriumSolver.h"

namespace anode {

namespace {

// A node is an unknown when its mass exceeds this fraction of its field's largest nodal mass.
// Below it a node carries only round-off weights (a particle at the edge of its support): its
// displacement would be set by stiffness at round-off level, so it is left out with the particle
// entries that reach it, as an explicit step gives a massless node no acceleration.
constexpr double kUnknownNodeMass = 1e-9;

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

void EquilibriumSolver::numberUnknowns(Collective every, const EquilibriumProblem& problem,
                                       double jacobianCouplingShare) {
  const int fields = 1 + *std::max_element(problem.fieldOf.begin(), problem.fieldOf.end());
  const int nodes = problem.grid.numNodes();
  const auto owns = [&](int k) { return problem.owned.empty() || problem.owned[k] != 0; };
  std::vector<double> least(fields);
  for (int f = 0; f < fields; ++f) {
    const std::vector<double>& mass = problem.mass[f];
    least[f] = *std::max_element(mass.begin(), mass.end());
  }
  collective::maximum(every, least.data(), fields);
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
  const int first = static_cast<int>(collective::exclusiveSum(every, rows_.owned));
  std::vector<double> global(unknown_.size(), -1.0);
  for (int r = 0; r < rows_.owned; ++r) global[r] = first + r;
  completeOverRanks(every, problem, global, 1, true);
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

void EquilibriumSolver::completeOverRanks(Collective every, const EquilibriumProblem& problem,
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
  problem.ghosts->sumOverRanks(every, arrays);
  for (int r = fromOwners ? rows_.owned : 0; r < rows; ++r) {
    const auto [f, k] = unknown_[r];
    for (int a = 0; a < width; ++a) values[width * r + a] = byNode[f][width * k + a];
  }
}

double EquilibriumSolver::ownedDot(Collective every, const std::vector<double>& a,
                                   const std::vector<double>& b) const {
  double d = 0;
  for (size_t i = 0; i < 3 * static_cast<size_t>(rows_.owned); ++i) d += a[i] * b[i];
  return collective::sum(every, d);
}

bool EquilibriumSolver::takesKeptLinearSolver(Collective every,
                                              const EquilibriumProblem& problem) const {
  if (!problem.useKeptLinearSolver) return false;
  const bool same = linearSolver_ && sameBits(problem.mass, numberedMass_) &&
                    sameBits(problem.prescribed, numberedPrescribed_);
  return collective::minimum(every, same ? 1.0 : 0.0) > 0;
}

void EquilibriumSolver::buildLinearSolver(Collective every, const EquilibriumProblem& problem) {
  linearSolver_.reset();  // its PETSc objects freed before the new ones are made
  linearSolver_ = std::make_unique<LinearSolver>(every, K_, rows_, fixed_, coordinates_);
  numberedMass_.clear();
  numberedPrescribed_.clear();
  if (!problem.keepLinearSolver) return;
  numberedMass_ = problem.mass;
  numberedPrescribed_ = problem.prescribed;
}

}  // namespace anode
