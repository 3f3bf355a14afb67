// ImplicitStep's equilibrium problem from the grid of the step's start (EquilibriumSolver.h), and
// the particles updated from its solution (ParticleEquilibrium.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <variant>

#include "Components/MPM/Implicit/CellMeanSwelling.h"
#include "Components/MPM/Implicit/HourglassStabilization.h"
#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/Util/Errors.h"

namespace anode {

EquilibriumProblem ImplicitStep::equilibriumProblem(Collective every, double dt) {
  const Grid& grid = mpm_.grid();
  std::vector<MPMMaterial>& materials = mpm_.materials();
  const std::vector<GridFields>& nodal = mpm_.stepGrid().fields;
  const ActiveNodes& active = mpm_.stepGrid().active;
  const GridBoundaryConditions& bcs = mpm_.problem().gridBCs;
  const int nodes = grid.numNodes();
  EquilibriumProblem problem{grid,
                             materials,
                             mpm_.stepGrid().weights,
                             fieldOf_,
                             {},
                             {},
                             mpm_.problem().flags.gravity,
                             {},
                             nullptr,
                             {},
                             {},
                             {},
                             {}};
  if (GhostNodes* ghosts = mpm_.layout().ghosts()) {
    // A node's unknowns belong to the rank owning the cell of the node's index.
    problem.ghosts = ghosts;
    problem.owned.resize(nodes);
    const int me = Communicator::rank();
    for (int k = 0; k < nodes; ++k)
      problem.owned[k] = mpm_.layout().boxes().ownerOfCell(grid.nodeOf(k)) == me;
  }
  computeSwelling(every);
  problem.concentrationChange = swelling_;
  problem.mass.assign(fields_, std::vector<double>(nodes, 0.0));
  const double free = std::numeric_limits<double>::quiet_NaN();
  problem.prescribed.assign(fields_, std::vector<Vec3>(nodes, Vec3::Constant(free)));
  for (size_t m = 0; m < materials.size(); ++m) {
    const int f = fieldOf_[m];
    forEachNode(active.rows, [&](long k) { problem.mass[f][k] += nodal[m].mass[k]; });
    // The faces' conditions as in the explicit step (Velocity, then Symmetric on it) on a field
    // of NaN: what they set is prescribed, velocity times dt.
    std::vector<Vec3> set(nodes, Vec3::Constant(free));
    applyVelocityDirichlet(grid, bcs.velocity, static_cast<int>(m), set);
    applySymmetry(grid, bcs.symmetric, static_cast<int>(m), active.box, set);
    for (int k = 0; k < nodes; ++k)
      for (int a = 0; a < 3; ++a)
        if (!std::isnan(set[k][a])) problem.prescribed[f][k][a] = set[k][a] * dt;
  }
  if (options_.dynamic)
    addStartOfStepMotion(every, problem, dt);
  else
    addPredictedIncrement(problem, dt);
  return problem;
}

void ImplicitStep::addPredictedIncrement(EquilibriumProblem& problem, double dt) {
  const int nodes = mpm_.grid().numNodes();
  const ActiveNodes& active = mpm_.stepGrid().active;
  problem.predicted.assign(problem.mass.size(), std::vector<Vec3>(nodes, Vec3::Zero()));
  for (size_t m = 0; m < fieldOf_.size(); ++m) {
    std::vector<Vec3>& momentum = problem.predicted[fieldOf_[m]];
    const GridFields& g = mpm_.stepGrid().fields[m];
    forEachNode(active.rows, [&](long k) { momentum[k] += g.momentum[k]; });
  }
  for (size_t f = 0; f < problem.predicted.size(); ++f)
    for (int k = 0; k < nodes; ++k)
      if (problem.mass[f][k] > 0) problem.predicted[f][k] *= dt / problem.mass[f][k];
}

void ImplicitStep::addStartOfStepMotion(Collective every, EquilibriumProblem& problem, double dt) {
  const int nodes = mpm_.grid().numNodes();
  const ActiveNodes& active = mpm_.stepGrid().active;
  const size_t fields = problem.mass.size();
  problem.velocity.assign(fields, std::vector<Vec3>(nodes, Vec3::Zero()));
  problem.acceleration.assign(fields, std::vector<Vec3>(nodes, Vec3::Zero()));
  for (size_t m = 0; m < fieldOf_.size(); ++m) {
    std::vector<Vec3>& momentum = problem.velocity[fieldOf_[m]];
    std::vector<Vec3>& sum = problem.acceleration[fieldOf_[m]];
    const GridFields& g = mpm_.stepGrid().fields[m];
    forEachNode(active.rows, [&](long k) { momentum[k] += g.momentum[k]; });
    // sum m a S, particle by particle (the accelerations are needed only here)
    const ParticleSet& p = mpm_.materials()[m].particles;
    const InterpolationWeights& W = mpm_.stepGrid().weights[m];
    for (size_t i = 0; i < p.count(); ++i)
      for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e)
        sum[W.node[e]] += p.mass[i] * W.weight[e] * p.acceleration[i];
  }
  if (GhostNodes* ghosts = mpm_.layout().ghosts()) {
    std::vector<NodeArray> sums;
    for (std::vector<Vec3>& a : problem.acceleration) sums.push_back({a.data()->data(), 3});
    ScopedTimer s(mpm_.timers(), tasks_.communication);
    ghosts->sumOverRanks(every, sums);
  }
  // Mass-weighted means; the faces' prescribed components move at the faces' velocity.
  for (size_t f = 0; f < fields; ++f)
    for (int k = 0; k < nodes; ++k) {
      const double mass = problem.mass[f][k];
      if (!(mass > 0)) continue;
      problem.velocity[f][k] /= mass;
      problem.acceleration[f][k] /= mass;
      for (int a = 0; a < 3; ++a)
        if (!std::isnan(problem.prescribed[f][k][a])) {
          problem.velocity[f][k][a] = problem.prescribed[f][k][a] / dt;
          problem.acceleration[f][k][a] = 0;
        }
    }
}

void ImplicitStep::computeSwelling(Collective every) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  swelling_.assign(materials.size(), nullptr);
  swellingIncrement_.resize(materials.size());
  swellingReached_.resize(materials.size());
  for (size_t m = 0; m < materials.size(); ++m) {
    if (!mpm_.diffusion() || !materials[m].model->swells()) continue;
    if (options_.swellingStrain == ImplicitOptions::SwellingStrain::Particle) {
      swelling_[m] = concentrationChange_[m].data();
      continue;
    }
    // The cell means of what the particle's swelling lacks at the step's end: its c less the
    // concentration its swelling has reached (CellMeanSwelling.h); before its first step, its
    // c at the step's start.
    ScopedTimer s(mpm_.timers(), tasks_.swelling);
    const ParticleSet& p = materials[m].particles;
    const std::vector<double>& c = diffusionParticles(p).concentration;
    const std::vector<double>& dc = concentrationChange_[m];
    std::vector<double>& reached = swellingReached_[m];
    std::vector<double> lacking(c.size());
    reached.resize(c.size());
    for (size_t i = 0; i < c.size(); ++i) {
      const double before = p.swellingConcentration[i];
      const bool first = std::isnan(before);
      reached[i] = first ? c[i] - dc[i] : before;
      lacking[i] = first ? dc[i] : c[i] - before;
    }
    std::vector<double>& increment = swellingIncrement_[m];
    cellMeanOf(every, mpm_.grid(), mpm_.layout().ghosts(), p, lacking, increment);
    for (size_t i = 0; i < c.size(); ++i) reached[i] += increment[i];
    swelling_[m] = increment.data();
  }
}

void ImplicitStep::updateParticlesFromEquilibrium(double dt) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  for (size_t m = 0; m < materials.size(); ++m) {
    MPMMaterial& mat = materials[m];
    const std::vector<Vec3>& u = equilibrium_.displacement(fieldOf_[m]);
    if (mat.particles.has(Physics::Hourglass))
      rememberNonAffineDisplacement(mpm_.grid(), mpm_.stepGrid().weights[m], u, mat.particles);
    long firstInverted = 0;
    std::visit(
        [&](const auto* model) {
          firstInverted = updateParticlesFromDisplacement(
              mat.particles, mpm_.stepGrid().weights[m], *model, mat.density, u,
              options_.dynamic ? &equilibrium_.acceleration(fieldOf_[m]) : nullptr, swelling_[m],
              dt);
        },
        mat.model->concrete().model);
    if (mat.particles.has(Physics::CellSwelling) && swelling_[m])
      mat.particles.swellingConcentration = swellingReached_[m];
    if (firstInverted < static_cast<long>(mat.particles.count())) {
      std::ostringstream s;
      s << describeParticle(mat, m, firstInverted)
        << " would reach det F <= 0 in the converged step (inverted or degenerate deformation)";
      throw SimulationError(s.str());
    }
  }
}

}  // namespace anode
