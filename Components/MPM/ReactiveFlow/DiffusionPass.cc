#include "Components/MPM/ReactiveFlow/DiffusionPass.h"

#include <algorithm>

#include "Components/MPM/ReactiveFlow/ChemicalPotential.h"
#include "Components/MPM/ReactiveFlow/RungeKuttaLegendre.h"
#include "Components/MPM/ReactiveFlow/SubcellRelaxation.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/StepActivity.h"

namespace anode {

DiffusionPass::DiffusionPass(ReactiveFlow& diffusion, const Grid& grid,
                             const ImplicitOptions& options, double substepMultiplier,
                             TaskTimers& timers)
    : diffusion_(diffusion),
      grid_(grid),
      integrator_(options.diffusionIntegrator),
      relaxation_(options.subcellConcentrationRelaxation),
      halves_(options.errorTolerance > 0),
      substepMultiplier_(substepMultiplier),
      timers_(timers),
      diffusionStateTask_(timers.task("updateDiffusionState")),
      particleUpdateTask_(timers.task("interpolateToParticlesAndUpdate")) {}

ImplicitOptions::DiffusionIntegrator DiffusionPass::checkIntegrator(const PSNode& root,
                                                                    const MPMFlags& flags,
                                                                    const ImplicitOptions& options,
                                                                    const ReactiveFlow* diffusion) {
  using Integrator = ImplicitOptions::DiffusionIntegrator;
  if (options.diffusionIntegrator != Integrator::Rkl2) return options.diffusionIntegrator;
  // A stage needs the particles' rate of c; a Dirichlet node sets c instead, and the
  // auto-cycle's turn is a decision on the state of a step's end, not of a stage. The default
  // under error control then falls back to Euler; the tag asked for is an error.
  const bool concentrationBCs = diffusion && diffusion->hasConcentrationBCs();
  if (options.rkl2ByDefault)
    return concentrationBCs || flags.autoCycle ? Integrator::Euler : Integrator::Rkl2;
  const PSNode tag = root.requireChild("MPM").requireChild("diffusion_integrator");
  if (concentrationBCs)
    tag.unsupported("<diffusion_integrator>rkl2 with SD-Type concentration boundary conditions");
  if (flags.autoCycle) tag.unsupported("<diffusion_integrator>rkl2 with <do_auto_cycle_bc>");
  if (!diffusion)
    tag.warn(
        "<diffusion_integrator> without <do_scalar_diffusion>true: there is no diffusion to "
        "integrate");
  return Integrator::Rkl2;
}

double DiffusionPass::substepLimit(Collective every,
                                   const std::vector<MPMMaterial>& materials) const {
  // Eq. 44 over every rank's particles and the flux limit: each rank's sub-steps are the same.
  return substepMultiplier_ *
         std::min(collective::minimum(every, diffusion_.diffusionTimestep(grid_)),
                  diffusion_.fluxTimestep(every, materials));
}

void DiffusionPass::updateDiffusionState(Collective every, std::vector<MPMMaterial>& materials,
                                         double t) {
  ScopedTimer s(timers_, diffusionStateTask_);
  diffusion_.updateDiffusionState(every, materials, t);  // range, D, flux rates
}

void DiffusionPass::returnToStepStart(Collective every, std::vector<MPMMaterial>& materials,
                                      double t) {
  diffusion_.restoreStepState(*start_);
  updateDiffusionState(every, materials, t);
}

double DiffusionPass::coveredBy(double limit) const {
  const double n = static_cast<double>(kMaxRateEvaluations);
  return integrator_ == ImplicitOptions::DiffusionIntegrator::Rkl2
             ? limit * (n * n + n - 2) / 4  // rkl2Stages's reach
             : limit * n;
}

DiffusionPass::Pass DiffusionPass::diffuse(Collective every, ConcentrationTransfer& grid,
                                           std::vector<MPMMaterial>& materials, double t, double dt,
                                           std::vector<std::vector<double>>& change,
                                           const std::vector<std::vector<double>>* c0Change,
                                           std::vector<std::vector<double>>* passError) {
  change.resize(materials.size());
  if (passError) passError->clear();
  for (size_t m = 0; m < materials.size(); ++m)
    change[m].assign(materials[m].particles.count(), 0.0);
  const bool stressDriven = computeStressPotentialGradients(every, grid, materials, c0Change);
  if (relaxation_) relaxSubcellConcentration(every, grid, materials, dt, change);
  // The sums of the relaxed c, and for the first Euler sub-step those of the flux with the
  // pass's grad phi (each RKL2 stage takes its own).
  const bool rkl2 = integrator_ == ImplicitOptions::DiffusionIntegrator::Rkl2;
  if (relaxation_ || (stressDriven && !rkl2)) grid.scatterConcentration(every);
  if (rkl2) return diffuseInLegendreStages(every, grid, materials, t, dt, change, passError);
  return diffuseInSubsteps(every, grid, materials, t, dt, change);
}

DiffusionPass::Pass DiffusionPass::diffuseInSubsteps(Collective every, ConcentrationTransfer& grid,
                                                     std::vector<MPMMaterial>& materials, double t,
                                                     double dt,
                                                     std::vector<std::vector<double>>& change) {
  long substeps = 0;
  double done = 0;
  // At dt = coveredBy(limit) and a constant limit, the remainder rule below makes the last of
  // kMaxRateEvaluations sub-steps end at t + dt.
  while (done < dt && substeps < kMaxRateEvaluations) {
    collective::stopIfRequested(every);  // a stop drops the step between sub-steps
    noteStepActivity(0, "diffusion sub-step", substeps + 1);
    const double limit = substepLimit(every, materials);
    // The last sub-step ends at t + dt exactly (a remainder below 1e-12 dt joins the one before).
    double h = std::min(limit, dt - done);
    if (dt - done - h < 1e-12 * dt) h = dt - done;
    // The concentration's sums of the start-of-step particles, again, of the materials whose c
    // changes (the rest of P2G stands: the particles change nothing else).
    if (done > 0) grid.scatterConcentration(every);
    grid.computeNodalConcentration(done == 0);  // Eq. 5 and the diffusion interface
    grid.integrateConcentration(h);             // c* and the rate (Eq. 18)
    for (size_t m = 0; m < materials.size(); ++m)
      if (diffusion_.computesConcentration(m))  // otherwise its c stays: nothing to gather
        grid.gatherConcentrationChange(m, h, change[m]);
    done = h == dt - done ? dt : done + h;
    ++substeps;
    updateDiffusionState(every, materials, t + done);
  }
  return {substeps, done};
}

DiffusionPass::Pass DiffusionPass::diffuseInLegendreStages(
    Collective every, ConcentrationTransfer& grid, std::vector<MPMMaterial>& materials, double t,
    double dt, std::vector<std::vector<double>>& change,
    std::vector<std::vector<double>>* passError) {
  // As many stages as the sub-steps' limit at the pass's start needs: more than the cap, and
  // the pass does not start.
  const double limit = substepLimit(every, materials);
  const int s = rkl2Stages(dt / limit);
  if (s > kMaxRateEvaluations) return {0, coveredBy(limit)};
  grid.computeNodalConcentration(true);  // the step's P2G (the nodal velocity)
  // c of the particles of the materials whose c changes, one after the other.
  std::vector<size_t> changing;
  for (size_t m = 0; m < materials.size(); ++m)
    if (diffusion_.computesConcentration(m)) changing.push_back(m);
  const auto concentrations = [&] {
    std::vector<double> y;
    for (size_t m : changing) {
      const std::vector<double>& c = diffusionParticles(materials[m].particles).concentration;
      y.insert(y.end(), c.begin(), c.end());
    }
    return y;
  };
  const auto setConcentrations = [&](const std::vector<double>& y) {
    auto at = y.begin();
    for (size_t m : changing) {
      std::vector<double>& c = diffusionParticles(materials[m].particles).concentration;
      std::copy(at, at + static_cast<long>(c.size()), c.begin());
      at += static_cast<long>(c.size());
    }
  };
  // The particles' grad c from the nodal c of their c (P2G of m c).
  const auto gradientOfNodalConcentration = [&] {
    grid.scatterConcentration(every);
    grid.computeNodalConcentration(false);
    for (size_t m : changing) grid.gatherConcentrationGradient(m);
  };
  double middle = t + dt / 2;  // the load curves' time of a step's stages
  long stages = 0;
  // dc/dt of every particle at c = y: the diffusion state (D, flux rates) of y with the load
  // curves at the pass's midpoint, P2G of m c, grad c at the particles from the nodal c, P2G of
  // m D grad c and the flux sources, and the nodal rates gathered with the sources each particle
  // receives (ConcentrationGather's update over a unit time).
  const auto rate = [&](const std::vector<double>& y, std::vector<double>& f) {
    collective::stopIfRequested(every);  // a stop drops the step between stages
    noteStepActivity(0, "RKL2 stage", stages + 1);
    setConcentrations(y);
    updateDiffusionState(every, materials, middle);
    gradientOfNodalConcentration();
    grid.scatterConcentration(every);
    grid.computeNodalConcentration(false);
    grid.integrateConcentration(1.0);
    size_t first = 0;
    for (size_t m : changing) {
      std::vector<double> dc(materials[m].particles.count(), 0.0);
      grid.gatherConcentrationChange(m, 1.0, dc);
      std::copy(dc.begin(), dc.end(), f.begin() + static_cast<long>(first));
      first += dc.size();
    }
    setConcentrations(y);
    ++stages;
  };
  const std::vector<double> start = concentrations();
  // Under error control the pass is two RKL2 steps of dt/2; `passError` asks for the one step of
  // dt first, from the same start and diffusion state, which the halves then take up again as
  // if it had not been (step doubling).
  std::vector<double> whole;
  if (passError) {
    const ReactiveFlow::StepState state = diffusion_.stepState();
    whole = start;
    stepRkl2(whole, dt, s, rate);
    diffusion_.restoreStepState(state);
  }
  std::vector<double> y = start;
  if (halves_) {
    const int h = rkl2Stages(dt / 2 / limit);
    middle = t + dt / 4;
    stepRkl2(y, dt / 2, h, rate);
    middle = t + 3 * dt / 4;
    stepRkl2(y, dt / 2, h, rate);
  } else {
    stepRkl2(y, dt, s, rate);
  }
  setConcentrations(y);
  if (passError)  // zero for the materials whose c does not change
    for (const MPMMaterial& mat : materials) passError->emplace_back(mat.particles.count(), 0.0);
  size_t first = 0;
  for (size_t m : changing) {
    std::vector<double>& dc = change[m];
    for (size_t i = 0; i < dc.size(); ++i) dc[i] += y[first + i] - start[first + i];
    // A second-order step's local error C dt^3 against C dt^3 / 4 for the two halves: the
    // halves' error is a third of their difference from the one step.
    if (passError) {
      std::vector<double>& e = (*passError)[m];
      for (size_t i = 0; i < dc.size(); ++i) e[i] = (whole[first + i] - y[first + i]) / 3;
    }
    first += dc.size();
  }
  // grad c of the end (as a sub-step leaves it for the next one) and its diffusion state.
  gradientOfNodalConcentration();
  updateDiffusionState(every, materials, t + dt);
  return {stages, dt};
}

bool DiffusionPass::computeStressPotentialGradients(
    Collective every, ConcentrationTransfer& grid, std::vector<MPMMaterial>& materials,
    const std::vector<std::vector<double>>* c0Change) {
  bool any = false;
  for (size_t m = 0; m < materials.size(); ++m) {
    if (!diffusion_.stressDriven(m)) continue;
    ScopedTimer s(timers_, particleUpdateTask_);
    ParticleSet& p = materials[m].particles;
    const std::vector<double>& nodeMass = grid.nodalMass(m);
    const ScalarDiffusionModel& model = diffusion_.model(m);
    scatterStressPotential(model.stressPotentialPerStress(), model.maxConcentration, p.mass,
                           p.stress, p.F, diffusionParticles(p).concentration,
                           c0Change ? &(*c0Change)[m] : nullptr, grid.weights(m), nodeMass.size(),
                           nodeMassStressPotential_, nodeMassStressConcentration_);
    grid.sumOverRanks(every, nodeMassStressPotential_);
    grid.sumOverRanks(every, nodeMassStressConcentration_);
    gatherStressPotentialGradient(
        grid.weights(m), nodeMassStressPotential_, nodeMassStressConcentration_, nodeMass,
        model.stressPotentialStabilization(), p.F, diffusionParticles(p).stressPotentialGradient);
    any = true;
  }
  return any;
}

void DiffusionPass::relaxSubcellConcentration(Collective every, ConcentrationTransfer& grid,
                                              std::vector<MPMMaterial>& materials, double dt,
                                              std::vector<std::vector<double>>& change) {
  ScopedTimer s(timers_, particleUpdateTask_);
  const double perDiffusivity = subcellRelaxationPerDiffusivity(dt, grid_.dx.maxCoeff());
  for (size_t m = 0; m < materials.size(); ++m) {
    if (!diffusion_.computesConcentration(m)) continue;
    ParticleSet& p = materials[m].particles;
    DiffusionParticles d = diffusionParticles(p);
    const std::vector<double>& nodeMass = grid.nodalMass(m);
    scatterMassDiffusivity(p.mass, d.diffusivity, grid.weights(m), nodeMass.size(),
                           nodeMassDiffusivity_);
    grid.sumOverRanks(every, nodeMassDiffusivity_);
    relaxSubcellDifferences(d.concentration, grid.weights(m),
                            diffusion_.gridFields()[m].massConcentration, nodeMass,
                            nodeMassDiffusivity_, perDiffusivity, change[m]);
  }
}

}  // namespace anode
