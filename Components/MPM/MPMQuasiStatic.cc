// The quasi-static step of an implicit run (DESIGN.md §4b; docs/quasi-static.md): the weights of
// the start-of-step configuration, P2G of the masses, diffusion over dt in explicit sub-steps on
// that configuration, Newton for the equilibrium at t + dt with the swelling of the new
// concentration (Implicit/EquilibriumSolver.h; retaken with a smaller dt when it fails), then the
// particles moved and their stresses set by the converged displacement increments.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <variant>

#include "Components/MPM/Implicit/ConcentrationSubstep.h"
#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Implicit/RungeKuttaLegendre.h"
#include "Components/MPM/MPM.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/ParticleLoops.h"
#include "Components/MPM/ReactiveFlow/SubcellRelaxation.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {
constexpr int kMaxRetakes = 20;  // of one step
// A step whose largest change of c exceeds <max_concentration_change> by this factor is retaken,
// at dt x bound / change, but no less than dt x kSmallestConcentrationRetake.
constexpr double kConcentrationChangeRetake = 2, kSmallestConcentrationRetake = 0.1;
// <concentration_coupling>trapezoidal: the prediction of the step's end needs the particles' J,
// positions and stress to the order of the step's change, not to Newton's last digits: its
// <convergence_criteria_disp> (and 4x this for the energy). Figure 4's pillar to 4 s in steps of
// 1 s: c within 5e-4 with 1e-2, 1e-3 and 1e-4, in 34, 35 and 38 Newton iterations in all; the
// rank counts' predictions part at this tolerance (their inexact linear solves differ), so the
// results of 1 to 4 ranks agree to 1.8e-5, 2.0e-7 and 1.8e-9 of an array's scale
// (ranks_implicit_trapezoidal_agree).
constexpr double kPredictorConvergence = 1e-3;
}  // namespace

double MPM::largestConcentrationChange() const {
  double largest = 0;
  for (const std::vector<double>& dc : concentrationChange_)
    for (double d : dc) largest = std::max(largest, std::abs(d));
  return largest;
}

std::string MPM::NewtonCounts::lastStep() const {
  return "Newton " + std::to_string(lastIterations) +
         (lastPredictorIterations > 0
              ? " + " + std::to_string(lastPredictorIterations) + " predicting"
              : std::string()) +
         ", Krylov " + std::to_string(lastKrylov);
}

std::string MPM::NewtonCounts::summary(long steps) const {
  char line[360];
  std::snprintf(line, sizeof line,
                "Newton iterations %ld (%.2f per step), %ld of them with a new Jacobian, Krylov "
                "iterations %ld (%.1f per Newton iteration, %ld preconditioner set-ups), steps "
                "retaken with a smaller dt %ld, diffusion sub-steps %ld",
                iterations, static_cast<double>(iterations) / std::max(steps, 1L), newTangents,
                krylov, iterations > 0 ? static_cast<double>(krylov) / iterations : 0.0,
                preconditionerSetUps, retakes, diffusionSubsteps);
  return line;
}

void MPM::checkImplicitSetup(const PSNode& root) const {
  if (contact_.excluded >= 0)
    root.requireChild("MaterialProperties")
        .requireChild("MPM")
        .requireChild("contact")
        .requireChild("ExcludeMaterial")
        .fail("<ExcludeMaterial> with <time_integrator>implicit is not supported");
  if (!diffusion_ &&
      flags_.implicit->concentrationCoupling == ImplicitOptions::ConcentrationCoupling::Trapezoidal)
    root.requireChild("MPM")
        .requireChild("concentration_coupling")
        .warn(
            "<concentration_coupling>trapezoidal without <do_scalar_diffusion>true: there is "
            "no diffusion to couple, the steps are the staggered ones");
  if (flags_.implicit->diffusionIntegrator == ImplicitOptions::DiffusionIntegrator::Rkl2) {
    const PSNode tag = root.requireChild("MPM").requireChild("diffusion_integrator");
    // A stage needs the particles' rate of c; a Dirichlet node sets c instead, and the
    // auto-cycle's turn is a decision on the state of a step's end, not of a stage.
    if (diffusion_ && diffusion_->hasConcentrationBCs())
      tag.unsupported("<diffusion_integrator>rkl2 with SD-Type concentration boundary conditions");
    if (flags_.autoCycle) tag.unsupported("<diffusion_integrator>rkl2 with <do_auto_cycle_bc>");
    if (!diffusion_)
      tag.warn(
          "<diffusion_integrator> without <do_scalar_diffusion>true: there is no diffusion to "
          "integrate");
  }
  if (!diffusion_ && flags_.implicit->subcellConcentrationRelaxation)
    root.requireChild("MPM")
        .requireChild("subcell_concentration_relaxation")
        .warn(
            "<subcell_concentration_relaxation> without <do_scalar_diffusion>true: there is no "
            "concentration to relax");
}

EquilibriumProblem MPM::equilibriumProblem(double dt) {
  const int nodes = grid_.numNodes();
  const int fields = 1 + *std::max_element(fieldOf_.begin(), fieldOf_.end());
  EquilibriumProblem problem{grid_, materials_, weights_, fieldOf_, {}, {}, flags_.gravity,
                             {},    nullptr,    {},       {},       {}, {}};
  if (distributed_) {
    // A node's unknowns belong to the rank owning the cell of the node's index.
    problem.ghosts = &ghosts_;
    problem.owned.resize(nodes);
    const int me = Communicator::rank();
    for (int k = 0; k < nodes; ++k)
      problem.owned[k] = decomposition_.ownerOfCell(grid_.nodeOf(k)) == me;
  }
  for (size_t m = 0; m < materials_.size(); ++m)
    problem.concentrationChange.push_back(
        diffusion_ && materials_[m].model->swells() ? concentrationChange_[m].data() : nullptr);
  problem.mass.assign(fields, std::vector<double>(nodes, 0.0));
  const double free = std::numeric_limits<double>::quiet_NaN();
  problem.prescribed.assign(fields, std::vector<Vec3>(nodes, Vec3::Constant(free)));
  for (size_t m = 0; m < materials_.size(); ++m) {
    const int f = fieldOf_[m];
    forEachNode(active_.rows, [&](long k) { problem.mass[f][k] += fields_[m].mass[k]; });
    // The faces' conditions as in the explicit step (Velocity, then Symmetric on it) on a field
    // of NaN: what they set is prescribed, velocity times dt.
    std::vector<Vec3> set(nodes, Vec3::Constant(free));
    applyVelocityDirichlet(grid_, gridBCs_.velocity, static_cast<int>(m), set);
    applySymmetry(grid_, gridBCs_.symmetric, static_cast<int>(m), active_.box, set);
    for (int k = 0; k < nodes; ++k)
      for (int a = 0; a < 3; ++a)
        if (!std::isnan(set[k][a])) problem.prescribed[f][k][a] = set[k][a] * dt;
  }
  if (flags_.implicit->dynamic)
    addStartOfStepMotion(problem, dt);
  else
    addPredictedIncrement(problem, dt);
  return problem;
}

void MPM::addPredictedIncrement(EquilibriumProblem& problem, double dt) {
  const int nodes = grid_.numNodes();
  problem.predicted.assign(problem.mass.size(), std::vector<Vec3>(nodes, Vec3::Zero()));
  for (size_t m = 0; m < materials_.size(); ++m) {
    std::vector<Vec3>& momentum = problem.predicted[fieldOf_[m]];
    forEachNode(active_.rows, [&](long k) { momentum[k] += fields_[m].momentum[k]; });
  }
  for (size_t f = 0; f < problem.predicted.size(); ++f)
    for (int k = 0; k < nodes; ++k)
      if (problem.mass[f][k] > 0) problem.predicted[f][k] *= dt / problem.mass[f][k];
}

void MPM::addStartOfStepMotion(EquilibriumProblem& problem, double dt) {
  const int nodes = grid_.numNodes();
  const size_t fields = problem.mass.size();
  problem.velocity.assign(fields, std::vector<Vec3>(nodes, Vec3::Zero()));
  problem.acceleration.assign(fields, std::vector<Vec3>(nodes, Vec3::Zero()));
  for (size_t m = 0; m < materials_.size(); ++m) {
    std::vector<Vec3>& momentum = problem.velocity[fieldOf_[m]];
    std::vector<Vec3>& sum = problem.acceleration[fieldOf_[m]];
    forEachNode(active_.rows, [&](long k) { momentum[k] += fields_[m].momentum[k]; });
    // sum m a S, particle by particle (the accelerations are needed only here)
    const ParticleSet& p = materials_[m].particles;
    const InterpolationWeights& W = weights_[m];
    for (size_t i = 0; i < p.count(); ++i)
      for (size_t e = W.offset[i]; e < W.offset[i] + W.count[i]; ++e)
        sum[W.node[e]] += p.mass[i] * W.weight[e] * p.acceleration[i];
  }
  if (distributed_) {
    std::vector<NodeArray> sums;
    for (std::vector<Vec3>& a : problem.acceleration) sums.push_back({a.data()->data(), 3});
    ScopedTimer s(timers_, tasks_.communication);
    ghosts_.sumOverRanks(Collective{}, sums);
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

void MPM::updateParticlesFromEquilibrium(double dt) {
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    const std::vector<Vec3>& u = equilibrium_.displacement(fieldOf_[m]);
    long firstInverted = 0;
    std::visit(
        [&](const auto* model) {
          firstInverted = updateParticlesFromDisplacement(
              mat.particles, weights_[m], *model, mat.density, u,
              flags_.implicit->dynamic ? &equilibrium_.acceleration(fieldOf_[m]) : nullptr,
              diffusion_ && model->swells() ? concentrationChange_[m].data() : nullptr, dt);
        },
        mat.model->concrete().model);
    if (firstInverted < static_cast<long>(mat.particles.count())) {
      std::ostringstream s;
      s << describeParticle(mat, m, firstInverted)
        << " would reach det F <= 0 in the converged step (inverted or degenerate deformation)";
      throw SimulationError(s.str());
    }
  }
}

void MPM::interpolateAndSumOverRanks(bool concentrationOnly) {
  {
    ScopedTimer s(timers_, tasks_.particlesToGrid);
    interpolateParticlesToGrid(concentrationOnly);
  }
  if (distributed_) {
    ScopedTimer s(timers_, tasks_.communication);
    sumGhostNodes(concentrationOnly);
  }
}

double MPM::diffusionSubstepLimit(double substepMultiplier) const {
  // Eq. 44 over every rank's particles and the flux limit: each rank's sub-steps are the same.
  return substepMultiplier * std::min(collective::minimum(diffusion_->diffusionTimestep(grid_)),
                                      diffusion_->fluxTimestep(Collective{}, materials_));
}

void MPM::diffuseOverStep(double t, double dt, double substepMultiplier) {
  concentrationChange_.resize(materials_.size());
  for (size_t m = 0; m < materials_.size(); ++m)
    concentrationChange_[m].assign(materials_[m].particles.count(), 0.0);
  if (flags_.implicit->subcellConcentrationRelaxation) {
    relaxSubcellConcentration(dt);
    interpolateAndSumOverRanks(true);  // the sums of the relaxed c
  }
  if (flags_.implicit->diffusionIntegrator == ImplicitOptions::DiffusionIntegrator::Rkl2) {
    diffuseInLegendreStages(t, dt, substepMultiplier);
    return;
  }
  double done = 0;
  while (done < dt) {
    const double limit = diffusionSubstepLimit(substepMultiplier);
    // The last sub-step ends at t + dt exactly (a remainder below 1e-12 dt joins the one before).
    double h = std::min(limit, dt - done);
    if (dt - done - h < 1e-12 * dt) h = dt - done;
    // The concentration's sums of the start-of-step particles, again, of the materials whose c
    // changes (the rest of P2G stands: the particles change nothing else).
    if (done > 0) interpolateAndSumOverRanks(true);
    {
      ScopedTimer s(timers_, tasks_.particlesToGrid);
      if (done > 0)
        computeNodalConcentration();  // Eq. 5 and the diffusion interface
      else
        computeNodalVelocityAndConcentration();
    }
    {
      ScopedTimer s(timers_, tasks_.gridIntegration);
      diffusion_->integrateConcentration(fields_, h, active_.rows);  // c* and the rate (Eq. 18)
    }
    {
      ScopedTimer s(timers_, tasks_.particleUpdate);
      for (size_t m = 0; m < materials_.size(); ++m) {
        if (!diffusion_->computesConcentration(m)) continue;  // its c stays: nothing to gather
        withGatherKernel(diffusion_.get(), m, materials_[m].particles, [&](const auto& kernel) {
          fillGatherQuads(fields_[m], kernel, active_.rows, nodeQuads_.data());
          updateConcentrationOnly(materials_[m].particles, weights_[m], nodeQuads_.data(), kernel,
                                  h, concentrationChange_[m]);
        });
      }
    }
    done = h == dt - done ? dt : done + h;
    ++newton_.diffusionSubsteps;
    ScopedTimer s(timers_, tasks_.diffusionState);
    diffusion_->updateDiffusionState(Collective{}, materials_, t + done);  // range, D, flux rates
  }
}

void MPM::diffuseInLegendreStages(double t, double dt, double substepMultiplier) {
  {
    ScopedTimer s(timers_, tasks_.particlesToGrid);
    computeNodalVelocityAndConcentration();  // the step's P2G (the nodal velocity)
  }
  // c of the particles of the materials whose c changes, one after the other.
  std::vector<size_t> changing;
  for (size_t m = 0; m < materials_.size(); ++m)
    if (diffusion_->computesConcentration(m)) changing.push_back(m);
  const auto concentrations = [&] {
    std::vector<double> y;
    for (size_t m : changing) {
      const std::vector<double>& c = diffusionParticles(materials_[m].particles).concentration;
      y.insert(y.end(), c.begin(), c.end());
    }
    return y;
  };
  const auto setConcentrations = [&](const std::vector<double>& y) {
    auto at = y.begin();
    for (size_t m : changing) {
      std::vector<double>& c = diffusionParticles(materials_[m].particles).concentration;
      std::copy(at, at + static_cast<long>(c.size()), c.begin());
      at += static_cast<long>(c.size());
    }
  };
  // The particles' grad c from the nodal c of their c (P2G of m c).
  const auto gradientOfNodalConcentration = [&] {
    interpolateAndSumOverRanks(true);
    {
      ScopedTimer s(timers_, tasks_.particlesToGrid);
      computeNodalConcentration();
    }
    ScopedTimer s(timers_, tasks_.particleUpdate);
    for (size_t m : changing)
      gatherConcentrationGradient(materials_[m].particles, weights_[m],
                                  diffusion_->gridFields()[m].concentration);
  };
  const double middle = t + dt / 2;
  // dc/dt of every particle at c = y: the diffusion state (D, flux rates) of y with the load
  // curves at the pass's midpoint, P2G of m c, grad c at the particles from the nodal c, P2G of
  // m D grad c and the flux sources, and the nodal rates gathered with the sources each particle
  // receives (ConcentrationGather's update over a unit time).
  const auto rate = [&](const std::vector<double>& y, std::vector<double>& f) {
    setConcentrations(y);
    {
      ScopedTimer s(timers_, tasks_.diffusionState);
      diffusion_->updateDiffusionState(Collective{}, materials_, middle);
    }
    gradientOfNodalConcentration();
    interpolateAndSumOverRanks(true);
    {
      ScopedTimer s(timers_, tasks_.particlesToGrid);
      computeNodalConcentration();
    }
    {
      ScopedTimer s(timers_, tasks_.gridIntegration);
      diffusion_->integrateConcentration(fields_, 1.0, active_.rows);
    }
    ScopedTimer s(timers_, tasks_.particleUpdate);
    size_t first = 0;
    for (size_t m : changing) {
      const size_t n = materials_[m].particles.count();
      std::vector<double> change(n, 0.0);
      withGatherKernel(diffusion_.get(), m, materials_[m].particles, [&](const auto& kernel) {
        fillGatherQuads(fields_[m], kernel, active_.rows, nodeQuads_.data());
        updateConcentrationOnly(materials_[m].particles, weights_[m], nodeQuads_.data(), kernel,
                                1.0, change);
      });
      std::copy(change.begin(), change.end(), f.begin() + static_cast<long>(first));
      first += n;
    }
    setConcentrations(y);
    ++newton_.diffusionSubsteps;
  };
  // As many stages as the sub-steps' limit at the pass's start needs.
  const double limit = diffusionSubstepLimit(substepMultiplier);
  const std::vector<double> start = concentrations();
  std::vector<double> y = start;
  stepRkl2(y, dt, rkl2Stages(dt / limit), rate);
  setConcentrations(y);
  size_t first = 0;
  for (size_t m : changing) {
    std::vector<double>& change = concentrationChange_[m];
    for (size_t i = 0; i < change.size(); ++i) change[i] += y[first + i] - start[first + i];
    first += change.size();
  }
  // grad c of the end (as a sub-step leaves it for the next one) and its diffusion state.
  gradientOfNodalConcentration();
  ScopedTimer s(timers_, tasks_.diffusionState);
  diffusion_->updateDiffusionState(Collective{}, materials_, t + dt);
}

void MPM::relaxSubcellConcentration(double dt) {
  ScopedTimer s(timers_, tasks_.particleUpdate);
  const double perDiffusivity = subcellRelaxationPerDiffusivity(dt, grid_.dx.maxCoeff());
  for (size_t m = 0; m < materials_.size(); ++m) {
    if (!diffusion_->computesConcentration(m)) continue;
    ParticleSet& p = materials_[m].particles;
    DiffusionParticles d = diffusionParticles(p);
    const std::vector<double>& nodeMass = fields_[m].mass;
    scatterMassDiffusivity(p.mass, d.diffusivity, weights_[m], nodeMass.size(),
                           nodeMassDiffusivity_);
    if (distributed_) ghosts_.sumOverRanks(Collective{}, {{nodeMassDiffusivity_.data(), 1}});
    relaxSubcellDifferences(d.concentration, weights_[m],
                            diffusion_->gridFields()[m].massConcentration, nodeMass,
                            nodeMassDiffusivity_, perDiffusivity, concentrationChange_[m]);
  }
}

NewtonReport MPM::averageConcentrationChangeOverStep(double t, double dt, double substepMultiplier,
                                                     const std::vector<ParticleSet>& start,
                                                     const ReactiveFlow::StepState& atStart,
                                                     std::vector<std::vector<Vec3>>& predicted,
                                                     double& correction) {
  // Never tighter than the step's own criteria.
  ImplicitOptions loose = *flags_.implicit;
  loose.convergenceDisp = std::max(kPredictorConvergence, loose.convergenceDisp);
  loose.convergenceEnergy = std::max(4 * kPredictorConvergence, loose.convergenceEnergy);
  EquilibriumProblem problem = equilibriumProblem(dt);
  problem.keepLinearSolver = true;  // for the step's own solve from the same start
  NewtonReport report = equilibrium_.solve(problem, dt, loose);
  newton_.add(report);
  if (!report.converged) return report;
  predicted.clear();
  const int fields = 1 + *std::max_element(fieldOf_.begin(), fieldOf_.end());
  for (int f = 0; f < fields; ++f) predicted.push_back(equilibrium_.displacement(f));
  // What the first pass's sub-steps leave on the particles: the change of c, and the gradient of
  // c the next sub-step uses (p.concentrationGradient, lagged).
  const std::vector<std::vector<double>> firstPassChange = concentrationChange_;
  std::vector<std::vector<Vec3>> firstPassGradient;
  for (const MPMMaterial& mat : materials_)
    firstPassGradient.push_back(diffusionParticles(mat.particles).concentrationGradient);
  const auto weightsOfTheParticles = [&] {
    {
      ScopedTimer s(timers_, tasks_.interpolationWeights);
      computeWeightsAndActiveNodes();
    }
    interpolateAndSumOverRanks();
  };
  try {
    {
      ScopedTimer s(timers_, tasks_.particleUpdate);
      collective::stopTogether([&] { updateParticlesFromEquilibrium(dt); });
    }
    // The predicted end with the diffusion arrays and state of the step's start.
    for (size_t m = 0; m < materials_.size(); ++m) {
      DiffusionParticles d = diffusionParticles(materials_[m].particles);
      const ConstDiffusionParticles s = diffusionParticles(start[m]);
      d.concentration = s.concentration;
      d.concentrationGradient = s.concentrationGradient;
    }
    diffusion_->restoreStepState(atStart);
    {
      ScopedTimer s(timers_, tasks_.diffusionState);
      diffusion_->updateDiffusionState(Collective{}, materials_, t);  // D of the predicted stress
    }
    weightsOfTheParticles();
    diffuseOverStep(t, dt, substepMultiplier);
    // The start's particles with the means of the two passes (trapezoidal in the geometry, the
    // stress and J), and the lithium by which the mean differs from either pass.
    correction = 0;
    for (size_t m = 0; m < materials_.size(); ++m) {
      const std::vector<Vec3> secondPassGradient =
          diffusionParticles(materials_[m].particles).concentrationGradient;
      materials_[m].particles = start[m];
      DiffusionParticles d = diffusionParticles(materials_[m].particles);
      const std::vector<double>& mass = materials_[m].particles.mass;
      std::vector<double>& change = concentrationChange_[m];
      for (size_t i = 0; i < d.concentration.size(); ++i) {
        correction += mass[i] * 0.5 * std::abs(change[i] - firstPassChange[m][i]);
        change[i] = 0.5 * (firstPassChange[m][i] + change[i]);
        d.concentration[i] += change[i];
        d.concentrationGradient[i] = 0.5 * (firstPassGradient[m][i] + secondPassGradient[i]);
      }
    }
    correction = collective::sum(correction);
    maxConcentrationChange_ = collective::maximum(largestConcentrationChange());
    {
      ScopedTimer s(timers_, tasks_.diffusionState);
      diffusion_->updateDiffusionState(Collective{}, materials_, t + dt);
    }
  } catch (const SimulationError& e) {
    // A prediction solved to kPredictorConvergence may invert a particle, or its second pass
    // leave c's range: on every rank together (stopTogether), the step is retaken at a smaller dt.
    for (size_t m = 0; m < materials_.size(); ++m) materials_[m].particles = start[m];
    weightsOfTheParticles();
    report.converged = false;
    report.failure = e.what();
    return report;
  }
  weightsOfTheParticles();
  return report;
}

double MPM::advanceQuasiStatic(Collective, double t, double dt, double ruleDt, double dtMin,
                               double substepMultiplier) {
  {
    ScopedTimer s(timers_, tasks_.interpolationWeights);
    computeWeightsAndActiveNodes();  // 1: S_ip, grad S_ip at the start of the step
  }
  // A step retaken with a smaller dt diffuses again from the particles of the step's start.
  std::vector<ParticleSet> start;
  std::optional<ReactiveFlow::StepState> diffusionAtStart;
  int retakes = 0;
  if (diffusion_) {
    for (const MPMMaterial& mat : materials_) start.push_back(mat.particles);
    diffusionAtStart = diffusion_->stepState();
  }
  while (true) {
    interpolateAndSumOverRanks();  // the nodal masses (and the concentration's sums)
    // 2: c over dt; a step in which c changed by more than twice the bound of
    // <max_concentration_change> somewhere is retaken at the dt that bound allows.
    NewtonReport report;
    double smaller = dt * flags_.implicit->decreaseFactor;
    if (diffusion_) {
      diffuseOverStep(t, dt, substepMultiplier);
      const double bound = flags_.implicit->maxConcentrationChange;
      maxConcentrationChange_ = collective::maximum(largestConcentrationChange());
      if (maxConcentrationChange_ > kConcentrationChangeRetake * bound) {
        std::ostringstream s;
        s.precision(3);
        s << "c changed by " << maxConcentrationChange_ << " in a particle, above twice "
          << "<max_concentration_change> " << bound;
        report.failure = s.str();
        smaller = dt * std::max(bound / maxConcentrationChange_, kSmallestConcentrationRetake);
      }
    }
    // 2b (<concentration_coupling>trapezoidal): c over dt again on the predicted end
    std::vector<std::vector<Vec3>> predicted;
    NewtonReport prediction;
    double couplingCorrection = -1;
    if (report.failure.empty() && diffusion_ &&
        flags_.implicit->concentrationCoupling ==
            ImplicitOptions::ConcentrationCoupling::Trapezoidal) {
      prediction = averageConcentrationChangeOverStep(
          t, dt, substepMultiplier, start, *diffusionAtStart, predicted, couplingCorrection);
      if (!prediction.converged) {
        report = prediction;
        report.failure = "the prediction of the step's end: " + report.failure;
      }
    }
    if (report.failure.empty()) {
      // 3: Newton, retaken with a smaller dt until it converges
      EquilibriumProblem problem = equilibriumProblem(dt);
      if (!predicted.empty()) {
        problem.predicted = std::move(predicted);
        problem.predictedIsSolved = true;
        problem.useKeptLinearSolver = true;
      }
      report = equilibrium_.solve(problem, dt, *flags_.implicit);
      newton_.add(report);
      if (report.converged) {
        newton_.lastIterations = report.iterations;
        newton_.lastPredictorIterations = prediction.iterations;
        newton_.lastKrylov = report.krylovIterations + prediction.krylovIterations;
        newton_.lastCouplingCorrection = couplingCorrection;
        newton_.lastRatios = report.ratios;
        newton_.lastLinearTolerances = report.linearTolerances;
        break;
      }
    }
    // With <delt_min> 0 the retakes end after kMaxRetakes (0.6^20: 4e-5 of the first dt).
    if (smaller < dtMin || ++retakes > kMaxRetakes) {
      std::ostringstream s;
      s.precision(3);
      s << "the equilibrium step from t = " << t << " over dt = " << dt
        << " failed: " << report.failure << "; "
        << (smaller < dtMin ? "a retake with dt = " + std::to_string(smaller) +
                                  " would be below <delt_min> " + std::to_string(dtMin)
                            : std::to_string(kMaxRetakes) + " retakes with a smaller dt failed")
        << ". Newton's ratios |du|^2/max, du.r/first by iteration:";
      for (const auto& [disp, energy] : report.ratios) s << " (" << disp << ", " << energy << ")";
      s << "; their linear solves' relative tolerances:";
      for (double tolerance : report.linearTolerances) s << " " << tolerance;
      // Every rank decides this alike (Newton's tests are sums over all ranks): rank 0 reports.
      if (!Communicator::isRoot()) throw StoppedOnAnotherRank(0);
      throw SimulationError(s.str());
    }
    ++newton_.retakes;
    std::ostringstream note;
    note.precision(2);
    note << "sus: the step from t = " << t << " retaken with dt = " << smaller << ": "
         << report.failure;
    if (report.iterations > 0) {
      note << "; Newton " << report.iterations << ", last ratios";
      for (size_t k = report.ratios.size() > 3 ? report.ratios.size() - 3 : 0;
           k < report.ratios.size(); ++k)
        note << " (" << report.ratios[k].first << ", " << report.ratios[k].second << ")";
    }
    if (Communicator::isRoot()) std::fprintf(stderr, "%s\n", note.str().c_str());
    dt = smaller;
    ruleDt = smaller;
    for (size_t m = 0; m < start.size(); ++m) materials_[m].particles = start[m];
    if (diffusion_) {
      diffusion_->restoreStepState(*diffusionAtStart);
      diffusion_->updateDiffusionState(Collective{}, materials_, t);
    }
  }
  {
    ScopedTimer s(timers_, tasks_.particleUpdate);
    // 5: x, F, stress and the models' state
    collective::stopTogether([&] { updateParticlesFromEquilibrium(dt); });
  }
  if (flags_.refineParticles) {
    ScopedTimer s(timers_, tasks_.splitting);
    splitParticles();
  }
  if (distributed_) {
    ScopedTimer s(timers_, tasks_.communication);
    migrateParticles();  // particles that left the rank's box go to its owner
  }
  lastQuasiStaticDt_ = dt;
  newtonRuleDt_ = ruleDt;
  return dt;
}

}  // namespace anode
