// ImplicitStep's trapezoidal coupling of diffusion and mechanics (<concentration_coupling>
// trapezoidal; docs/quasi-static.md, stage 2b): the step's diffusion taken again on its
// predicted end, and the mean of the two passes.
#include <algorithm>
#include <cmath>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {
// The prediction of the step's end needs the particles' J, positions and stress to the order of
// the step's change, not to Newton's last digits: its <convergence_criteria_disp> (and 4x this
// for the energy). Figure 4's pillar to 4 s in steps of 1 s: c within 5e-4 with 1e-2, 1e-3 and
// 1e-4, in 34, 35 and 38 Newton iterations in all; the rank counts' predictions part at this
// tolerance (their inexact linear solves differ), so the results of 1 to 4 ranks agree to
// 1.8e-5, 2.0e-7 and 1.8e-9 of an array's scale (ranks_implicit_trapezoidal_agree).
constexpr double kPredictorConvergence = 1e-3;

// The local error of a particle's trapezoidal change of c over a step of dt (the mean of a pass on
// the step's start and one on its end), estimated from the coupling rates r = (dc_2 - dc_1) / dt^2
// of this step and of the last one (of lastDt; 0 before the first step). Let f(c, M) be the rate
// of c under the mechanics' state M(t) (J, pressure). The mean integrates f with M linear between
// the step's ends; M's curvature leaves an error dt^3/12 (df/dM) M'' = dt^3/12 g', g = (df/dM) M'.
// The passes differ by dc_2 - dc_1 = dt^2 g at the step's middle (to first order), so r samples g
// at the middles of consecutive steps, (dt + lastDt) / 2 apart. Before the first step g is 0 (a
// body at rest under a flux switched on at its start): r_last = 0 and lastDt = 0. Signed, so that a
// particle's errors over the steps add up as they do in its c.
double localCouplingError(double rate, double lastRate, double dt, double lastDt) {
  return dt * dt * dt * (rate - lastRate) / (6 * (dt + lastDt));
}
}  // namespace

NewtonReport ImplicitStep::averageConcentrationChangeOverStep(
    Collective every, double t, double dt, const std::vector<ParticleSet>& start,
    std::vector<std::vector<Vec3>>& predicted, double& correction, double& estimate,
    double& accumulated) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  // Never tighter than the step's own criteria.
  ImplicitOptions loose = options_;
  loose.convergenceDisp = std::max(kPredictorConvergence, loose.convergenceDisp);
  loose.convergenceEnergy = std::max(4 * kPredictorConvergence, loose.convergenceEnergy);
  EquilibriumProblem problem = equilibriumProblem(every, dt);
  problem.keepLinearSolver = true;  // for the step's own solve from the same start
  NewtonReport report = equilibrium_.solve(every, problem, dt, loose);
  newton_.add(report);
  if (!report.converged) return report;
  predicted.clear();
  for (int f = 0; f < fields_; ++f) predicted.push_back(equilibrium_.displacement(f));
  // What the first pass leaves on the particles: the change of c, and the gradient of c the next
  // sub-step uses (p.concentrationGradient, lagged).
  const std::vector<std::vector<double>> firstPassChange = concentrationChange_;
  std::vector<std::vector<Vec3>> firstPassGradient;
  for (const MPMMaterial& mat : materials)
    firstPassGradient.push_back(diffusionParticles(mat.particles).concentrationGradient);
  try {
    {
      ScopedTimer s(mpm_.timers(), tasks_.particleUpdate);
      collective::stopTogether(every, [&] { updateParticlesFromEquilibrium(dt); });
    }
    // The predicted end with the diffusion arrays and state of the step's start.
    for (size_t m = 0; m < materials.size(); ++m) {
      DiffusionParticles d = diffusionParticles(materials[m].particles);
      const ConstDiffusionParticles s = diffusionParticles(start[m]);
      d.concentration = s.concentration;
      d.concentrationGradient = s.concentrationGradient;
    }
    diffusion_->returnToStepStart(every, materials, t);  // D of the predicted stress
    computeWeights(every);
    // The predicted end's limits may hold the pass past its cap: on every rank alike (the
    // limits are over all ranks), the step is retaken as for a failed prediction.
    // (The predicted end's stress holds the first pass's c: a stress-driven flux's reference.)
    const double covered = diffuseOverStep(every, t, dt, &firstPassChange);
    if (covered < dt) throw SimulationError(passCapFailure(dt, covered));
    // The start's particles with the means of the two passes (trapezoidal in the geometry, the
    // stress and J), the lithium by which the mean differs from either pass, and under
    // <error_tolerance> the estimate of the mean's local error, and each particle's sum of its
    // estimates over the steps.
    correction = 0;
    estimate = 0;
    accumulated = 0;
    const double lastDt = dt_.errorControl().takenDt;
    for (size_t m = 0; m < materials.size(); ++m) {
      const double maxConcentration = mpm_.diffusion()->model(m).maxConcentration;
      const std::vector<Vec3> secondPassGradient =
          diffusionParticles(materials[m].particles).concentrationGradient;
      materials[m].particles = start[m];
      DiffusionParticles d = diffusionParticles(materials[m].particles);
      const std::vector<double>& mass = materials[m].particles.mass;
      std::vector<double>& change = concentrationChange_[m];
      std::vector<double>& couplingRate = materials[m].particles.couplingRate;
      std::vector<double>& errorSum = materials[m].particles.concentrationErrorEstimate;
      for (size_t i = 0; i < d.concentration.size(); ++i) {
        const double difference = change[i] - firstPassChange[m][i];
        correction += mass[i] * 0.5 * std::abs(difference);
        if (!couplingRate.empty()) {
          const double rate = difference / (dt * dt);
          // The coupling's error and the first pass's own (each pass makes about as much).
          const double passError = passError_.empty() ? 0 : passError_[m][i];
          const double local = (localCouplingError(rate, couplingRate[i], dt, lastDt) + passError) /
                               maxConcentration;
          estimate = std::max(estimate, std::abs(local));
          errorSum[i] += local;
          accumulated = std::max(accumulated, std::abs(errorSum[i]));
          couplingRate[i] = rate;
        }
        change[i] = 0.5 * (firstPassChange[m][i] + change[i]);
        d.concentration[i] += change[i];
        d.concentrationGradient[i] = 0.5 * (firstPassGradient[m][i] + secondPassGradient[i]);
      }
    }
    correction = collective::sum(every, correction);
    estimate = collective::maximum(every, estimate);
    accumulated = collective::maximum(every, accumulated);
    maxConcentrationChange_ = collective::maximum(every, largestConcentrationChange());
    {
      ScopedTimer s(mpm_.timers(), tasks_.diffusionState);
      mpm_.diffusion()->updateDiffusionState(every, materials, t + dt);
    }
  } catch (const SimulationError& e) {
    // A prediction solved to kPredictorConvergence may invert a particle, or its second pass
    // leave c's range: on every rank together (stopTogether), the step is retaken at a smaller dt.
    for (size_t m = 0; m < materials.size(); ++m) materials[m].particles = start[m];
    computeWeights(every);
    report.converged = false;
    report.failure = e.what();
    return report;
  }
  computeWeights(every);
  return report;
}

}  // namespace anode
