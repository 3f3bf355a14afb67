// ImplicitStep's step in order and its dt (ImplicitStep.h); the equilibrium problem it solves
// is ImplicitEquilibrium.cc's, the trapezoidal coupling TrapezoidalCoupling.cc's.
#include "Components/MPM/Implicit/ImplicitStep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

// MPM's tasks as the diffusion asks for them, each timed as the step's task it is part of.
class ImplicitStep::Transfer : public ConcentrationTransfer {
 public:
  explicit Transfer(MPM& mpm)
      : mpm_(mpm),
        timers_(mpm.timers()),
        particlesToGrid_(timers_.task("interpolateParticlesToGrid")),
        gridIntegration_(timers_.task("integrateGrid")),
        particleUpdate_(timers_.task("interpolateToParticlesAndUpdate")) {}
  void scatterConcentration(Collective every) override {
    mpm_.interpolateParticlesToGrid(every, true);
  }
  void computeNodalConcentration(bool withVelocity) override {
    ScopedTimer s(timers_, particlesToGrid_);
    if (withVelocity)
      mpm_.computeNodalVelocityAndConcentration();
    else
      mpm_.computeNodalConcentration();
  }
  void integrateConcentration(double dt) override {
    ScopedTimer s(timers_, gridIntegration_);
    mpm_.integrateConcentration(dt);
  }
  void gatherConcentrationChange(size_t m, double dt, std::vector<double>& change) override {
    ScopedTimer s(timers_, particleUpdate_);
    mpm_.interpolateConcentrationChange(m, dt, change);
  }
  void gatherConcentrationGradient(size_t m) override {
    ScopedTimer s(timers_, particleUpdate_);
    mpm_.interpolateConcentrationGradient(m);
  }
  void sumOverRanks(Collective every, std::vector<double>& nodal) override {
    if (GhostNodes* ghosts = mpm_.layout().ghosts())
      ghosts->sumOverRanks(every, {{nodal.data(), 1}});
  }
  const InterpolationWeights& weights(size_t m) const override {
    return mpm_.stepGrid().weights[m];
  }
  const std::vector<double>& nodalMass(size_t m) const override {
    return mpm_.stepGrid().fields[m].mass;
  }

 private:
  MPM& mpm_;
  TaskTimers& timers_;
  int particlesToGrid_, gridIntegration_, particleUpdate_;
};

std::string ImplicitStep::NewtonCounts::lastStep() const {
  return "Newton " + std::to_string(lastIterations) +
         (lastPredictorIterations > 0
              ? " + " + std::to_string(lastPredictorIterations) + " predicting"
              : std::string()) +
         ", Krylov " + std::to_string(lastKrylov);
}

std::string ImplicitStep::NewtonCounts::summary(long steps) const {
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

ImplicitStep::ImplicitStep(const PSNode& root, MPM& mpm, const TimestepController& dt)
    : mpm_(mpm),
      options_(*mpm.problem().flags.implicit),
      dt_(dt),
      transfer_(std::make_unique<Transfer>(mpm)) {
  checkSetup(root);
  options_.diffusionIntegrator =
      DiffusionPass::checkIntegrator(root, mpm.problem().flags, options_, mpm.diffusion());
  // Materials in single_velocity contact share one field of unknowns; others have their own.
  const Contact& contact = mpm.problem().contact;
  fieldOf_.assign(mpm.materials().size(), -1);
  if (contact.type == Contact::Type::SingleVelocity) {
    for (int m : contact.materials) fieldOf_[m] = 0;
    fields_ = 1;
  }
  for (int& f : fieldOf_)
    if (f < 0) f = fields_++;
  TaskTimers& timers = mpm.timers();
  equilibrium_.useTimers(timers);
  if (mpm.diffusion())
    diffusion_.emplace(*mpm.diffusion(), mpm.grid(), options_, dt.substepMultiplier(), timers);
  tasks_ = {timers.task("computeInterpolationWeights"),
            timers.task("interpolateToParticlesAndUpdate"),
            timers.task("splitParticles"),
            timers.task("updateDiffusionState"),
            mpm.layout().distributed() ? timers.task("communication") : -1,
            mpm.diffusion() && options_.swellingStrain == ImplicitOptions::SwellingStrain::CellMean
                ? timers.task("cellMeanSwelling")
                : -1};
}

ImplicitStep::~ImplicitStep() = default;

void ImplicitStep::checkSetup(const PSNode& root) const {
  const ReactiveFlow* diffusion = mpm_.diffusion();
  if (mpm_.problem().contact.excluded >= 0)
    root.requireChild("MaterialProperties")
        .requireChild("MPM")
        .requireChild("contact")
        .requireChild("ExcludeMaterial")
        .fail("<ExcludeMaterial> with <time_integrator>implicit is not supported");
  if (!diffusion &&
      options_.concentrationCoupling == ImplicitOptions::ConcentrationCoupling::Trapezoidal)
    root.requireChild("MPM")
        .requireChild("concentration_coupling")
        .warn(
            "<concentration_coupling>trapezoidal without <do_scalar_diffusion>true: there is "
            "no diffusion to couple, the steps are the staggered ones");
  if (!diffusion && options_.subcellConcentrationRelaxation)
    root.requireChild("MPM")
        .requireChild("subcell_concentration_relaxation")
        .warn(
            "<subcell_concentration_relaxation> without <do_scalar_diffusion>true: there is no "
            "concentration to relax");
}

StableTimestep ImplicitStep::stableTimestep(Collective every) const {
  StableTimestep limits;  // the first step takes <delt_max> (or <delt_init>)
  limits.bound[StableTimestep::Newton] = ruleDt_ > 0
                                             ? dt_.afterNewton(ruleDt_, newton_.lastIterations)
                                             : std::numeric_limits<double>::max();
  // The accuracy bound on c (docs/quasi-static.md), unless <error_tolerance> without
  // <max_concentration_change> leaves it out.
  if (maxConcentrationChange_ > 0 && options_.maxConcentrationChange > 0)
    limits.bound[StableTimestep::ConcentrationChange] =
        dt_.forConcentrationChange(lastDt_, maxConcentrationChange_);
  // The pass's cap of sub-steps, from the diffusion state the step's pass starts from.
  if (diffusion_)
    limits.bound[StableTimestep::DiffusionPassCap] =
        diffusion_->longestPass(every, mpm_.materials());
  // The first step under error control, before any estimate: <error_tolerance> x the flux limit,
  // the time in which the flux BCs change the fastest-filling particle's c by about the
  // tolerance (g(c) / k <= 0.98 / k, docs/diffusion.md "Time step"); later steps the controller's.
  if (diffusion_ && dt_.controlsError() && dt_.errorControl().lastEstimate < 0) {
    StableTimestep explicitLimits;
    mpm_.diffusion()->boundTimestep(every, mpm_.grid(), mpm_.materials(), explicitLimits);
    limits.bound[StableTimestep::ErrorEstimate] =
        options_.errorTolerance * explicitLimits.bound[StableTimestep::Flux];
  }
  return limits;
}

double ImplicitStep::largestConcentrationChange() const {
  double largest = 0;
  for (const std::vector<double>& dc : concentrationChange_)
    for (double d : dc) largest = std::max(largest, std::abs(d));
  return largest;
}

void ImplicitStep::computeWeights(Collective every) {
  {
    ScopedTimer s(mpm_.timers(), tasks_.interpolationWeights);
    mpm_.computeWeightsAndActiveNodes(every);
  }
  mpm_.interpolateParticlesToGrid(every);
}

double ImplicitStep::diffuseOverStep(Collective every, double t, double dt,
                                     const std::vector<std::vector<double>>* c0Change,
                                     std::vector<std::vector<double>>* passError) {
  const DiffusionPass::Pass pass = diffusion_->diffuse(every, *transfer_, mpm_.materials(), t, dt,
                                                       concentrationChange_, c0Change, passError);
  newton_.diffusionSubsteps += pass.evaluations;
  return pass.covered;
}

std::string ImplicitStep::passCapFailure(double dt, double covered) {
  std::ostringstream s;
  s.precision(3);
  s << "the diffusion pass over dt = " << dt << " needs more than "
    << DiffusionPass::kMaxRateEvaluations
    << (options_.diffusionIntegrator == ImplicitOptions::DiffusionIntegrator::Rkl2 ? " stages"
                                                                                   : " sub-steps")
    << ", which cover " << covered;
  return s.str();
}

StepTaken ImplicitStep::advance(Collective every, double t, double dt, double ruleDt) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  const bool diffusion = mpm_.diffusion();
  {
    ScopedTimer s(mpm_.timers(), tasks_.interpolationWeights);
    mpm_.computeWeightsAndActiveNodes(every);  // 1: S_ip, grad S_ip at the start of the step
  }
  // A step retaken with a smaller dt diffuses again from the particles of the step's start.
  std::vector<ParticleSet> start;
  if (diffusion) {
    for (const MPMMaterial& mat : materials) start.push_back(mat.particles);
    diffusion_->keepStepStart();
  }
  // A stop request in a long phase drops the step: its particles and diffusion state are set
  // back to its start, as the last completed step left them (bit for bit: its checkpoint is
  // the run's last).
  try {
    takeEquilibriumStep(every, t, dt, ruleDt, start);  // 2-4: c over dt, then Newton
  } catch (const StopRequestedInStep&) {
    for (size_t m = 0; m < start.size(); ++m) materials[m].particles = start[m];
    if (diffusion) diffusion_->dropStep();
    throw;
  }
  if (diffusion) diffusion_->releaseStepStart();
  {
    ScopedTimer s(mpm_.timers(), tasks_.particleUpdate);
    // 5: x, F, stress and the models' state
    collective::stopTogether(every, [&] { updateParticlesFromEquilibrium(dt); });
  }
  if (mpm_.problem().flags.refineParticles) {
    ScopedTimer s(mpm_.timers(), tasks_.splitting);
    mpm_.splitParticles(every);
  }
  if (mpm_.layout().distributed()) {
    ScopedTimer s(mpm_.timers(), tasks_.communication);
    mpm_.migrateParticles(every);  // particles that left the rank's box go to its owner
  }
  lastDt_ = dt;
  ruleDt_ = ruleDt;
  return {dt, ruleDt};
}

void ImplicitStep::takeEquilibriumStep(Collective every, double t, double& dt, double& ruleDt,
                                       const std::vector<ParticleSet>& start) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  const bool diffusion = mpm_.diffusion();
  int retakes = 0;
  std::vector<TimestepController::FailedNewton> failedNewton;  // of this step's attempts
  while (true) {
    mpm_.interpolateParticlesToGrid(every);  // the nodal masses (and the concentration's sums)
    // 2: c over dt; a step in which c changed by more than twice the bound of
    // <max_concentration_change> somewhere is retaken at the dt that bound allows.
    NewtonReport report;
    double failedChange = 0;      // the change of c that failed the attempt
    double rejectedEstimate = 0;  // the error estimate that failed it
    double covered = dt;          // by the diffusion pass: less where its cap stopped it
    if (diffusion) {
      // Under error control the first pass also estimates its own error (passError_).
      covered = diffuseOverStep(every, t, dt, nullptr, dt_.controlsError() ? &passError_ : nullptr);
      maxConcentrationChange_ = collective::maximum(every, largestConcentrationChange());
      if (covered < dt) {
        report.failure = passCapFailure(dt, covered);
      } else if (options_.maxConcentrationChange > 0 &&
                 dt_.retakesConcentrationChange(maxConcentrationChange_)) {
        std::ostringstream s;
        s.precision(3);
        s << "c changed by " << maxConcentrationChange_ << " in a particle, above twice "
          << "<max_concentration_change> " << options_.maxConcentrationChange;
        report.failure = s.str();
        failedChange = maxConcentrationChange_;
      }
    }
    // 2b (<concentration_coupling>trapezoidal): c over dt again on the predicted end
    std::vector<std::vector<Vec3>> predicted;
    NewtonReport prediction;
    double couplingCorrection = -1, errorEstimate = -1, accumulatedEstimate = -1;
    if (report.failure.empty() && diffusion &&
        options_.concentrationCoupling == ImplicitOptions::ConcentrationCoupling::Trapezoidal) {
      prediction = averageConcentrationChangeOverStep(
          every, t, dt, start, predicted, couplingCorrection, errorEstimate, accumulatedEstimate);
      if (!prediction.converged) {
        report = prediction;
        report.failure = "the prediction of the step's end: " + report.failure;
      } else if (dt_.controlsError() && dt_.rejectsErrorEstimate(errorEstimate)) {
        // 2c (<error_tolerance>): a step whose estimate is above the tolerance is retaken
        std::ostringstream s;
        s.precision(3);
        s << "its error estimate " << errorEstimate << " is above <error_tolerance> "
          << options_.errorTolerance;
        report.failure = s.str();
        rejectedEstimate = errorEstimate;
      }
    }
    if (report.failure.empty()) {
      // 3: Newton, retaken with a smaller dt until it converges
      EquilibriumProblem problem = equilibriumProblem(every, dt);
      if (!predicted.empty()) {
        problem.predicted = std::move(predicted);
        problem.predictedIsSolved = true;
        problem.useKeptLinearSolver = true;
      }
      report = equilibrium_.solve(every, problem, dt, options_);
      newton_.add(report);
      if (report.converged) {
        newton_.lastIterations = report.iterations;
        newton_.lastPredictorIterations = prediction.iterations;
        newton_.lastKrylov = report.krylovIterations + prediction.krylovIterations;
        newton_.lastCouplingCorrection = couplingCorrection;
        newton_.lastErrorEstimate = dt_.controlsError() ? errorEstimate : -1;
        newton_.accumulatedErrorEstimate = dt_.controlsError() ? accumulatedEstimate : -1;
        newton_.lastRetakes = retakes;
        newton_.lastRatios = report.ratios;
        newton_.lastLinearTolerances = report.linearTolerances;
        break;
      }
      // The first iteration's ratios are 1 by definition: a stall shows from the second on.
      if (report.ratios.size() >= 2)
        failedNewton.push_back({dt, report.ratios.back().first, report.ratios.back().second});
    }
    // A pass stopped by its cap is retaken over the time it covered; every retake's pass keeps
    // to the cap from the diffusion state it starts from.
    double smaller = covered < dt           ? covered
                     : rejectedEstimate > 0 ? dt_.retakeForError(dt, rejectedEstimate)
                                            : dt_.retakeDt(dt, failedChange);
    if (diffusion) {
      returnToStepStart(every, t, start);
      smaller = std::min(smaller, diffusion_->longestPass(every, materials));
    }
    std::string refusal = dt_.refusesRetake(smaller, retakes);
    if (refusal.empty()) refusal = TimestepController::refusesStalledNewton(failedNewton);
    if (!refusal.empty()) stop(t, dt, refusal, report);
    ++retakes;
    ++newton_.retakes;
    reportRetake(t, smaller, report);
    dt = smaller;
    ruleDt = smaller;
  }
}

void ImplicitStep::returnToStepStart(Collective every, double t,
                                     const std::vector<ParticleSet>& start) {
  std::vector<MPMMaterial>& materials = mpm_.materials();
  for (size_t m = 0; m < start.size(); ++m) materials[m].particles = start[m];
  diffusion_->returnToStepStart(every, materials, t);
}

void ImplicitStep::stop(double t, double dt, const std::string& refusal,
                        const NewtonReport& report) const {
  std::ostringstream s;
  s.precision(3);
  s << "the equilibrium step from t = " << t << " over dt = " << dt << " failed: " << report.failure
    << "; " << refusal << ". Newton's ratios |du|^2/max, du.r/first by iteration:";
  for (const auto& [disp, energy] : report.ratios) s << " (" << disp << ", " << energy << ")";
  s << "; their linear solves' relative tolerances:";
  for (double tolerance : report.linearTolerances) s << " " << tolerance;
  // Every rank decides this alike (Newton's tests are sums over all ranks): rank 0 reports.
  if (!Communicator::isRoot()) throw StoppedOnAnotherRank(0);
  throw SimulationError(s.str());
}

void ImplicitStep::reportRetake(double t, double smaller, const NewtonReport& report) {
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
}

}  // namespace anode
