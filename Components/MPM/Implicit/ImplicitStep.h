// The implicit step (DESIGN.md §4b; docs/quasi-static.md), quasi-static or, with <dynamic>true,
// Newmark's dynamics: the weights of the start-of-step configuration, P2G of the masses,
// diffusion over dt on that configuration (ReactiveFlow/DiffusionPass.h), Newton for the
// equilibrium at t + dt with the swelling of the new concentration (EquilibriumSolver.h;
// retaken with a smaller dt when it fails), then the particles moved and their stresses set by
// the converged displacement increments. Its dt follows Newton's iterations (ImpMPM's rule) and
// the largest change of c.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "Components/MPM/Implicit/EquilibriumSolver.h"
#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"
#include "Components/MPM/ReactiveFlow/DiffusionPass.h"
#include "Components/MPM/TimestepController.h"

namespace anode {

class ImplicitStep : public Integrator {
 public:
  // Checks the implicit setup of the input (what it does not support is an input error); `dt`
  // rules the step's dt, its retakes and the diffusion sub-steps' share of the explicit limits.
  ImplicitStep(const PSNode& root, MPM& mpm, const TimestepController& dt);
  ~ImplicitStep() override;

  // ImpMPM's rule on the last step's Newton iterations (the first step takes <delt_max> or
  // <delt_init>) and the dt whose largest change of c would be <max_concentration_change>
  // (TimestepController's).
  StableTimestep stableTimestep(Collective) const override;
  // A step Newton does not converge in, or whose c changed too much, is retaken with the dt the
  // controller gives, or the run stops where it refuses one (SimulationError). The next step's
  // dt follows Newton's iterations from ruleDt (or the retake's dt).
  StepTaken advance(Collective, double t, double dt, double ruleDt) override;
  std::string describeLastStep(StableTimestep::Limit) const override { return newton_.lastStep(); }
  StepCounts lastStepCounts() const override {
    return {newton_.lastIterations + newton_.lastPredictorIterations,
            newton_.lastKrylov,
            newton_.lastCouplingCorrection,
            newton_.lastErrorEstimate,
            newton_.accumulatedErrorEstimate,
            newton_.lastRetakes};
  }
  std::string summary(long steps) const override { return newton_.summary(steps); }

  // Newton's iterations: of the last step, and the totals of the steps (and retaken attempts)
  // of this process.
  struct NewtonCounts {
    // The last step's: its equilibrium's Newton iterations (those the dt rule counts), the
    // prediction's (<concentration_coupling>trapezoidal) and the Krylov iterations of both.
    int lastIterations = 0, lastPredictorIterations = 0, lastKrylov = 0;
    // The last step's coupling correction (<concentration_coupling>trapezoidal; -1 otherwise):
    // sum m |dc_2 - dc_1| / 2 over every rank's particles, dc_1 and dc_2 the two passes' changes
    // of c, the lithium by which the step's mean differs from either pass.
    double lastCouplingCorrection = -1;
    // With <error_tolerance>: the last step's error estimate (-1 otherwise), the largest over
    // every rank's particles of the local error of the trapezoidal mean in c / c_max
    // (Implicit/TrapezoidalCoupling.cc); the largest over the particles of the sum of a
    // particle's signed local errors over the steps up to it (ParticleSet::
    // concentrationErrorEstimate); and the attempts retaken before the step was taken.
    double lastErrorEstimate = -1, accumulatedErrorEstimate = -1;
    int lastRetakes = 0;
    long iterations = 0, krylov = 0, retakes = 0, diffusionSubsteps = 0, preconditionerSetUps = 0,
         newTangents = 0;
    std::vector<std::pair<double, double>> lastRatios;  // NewtonReport::ratios of the last step
    std::vector<double> lastLinearTolerances;           // and its linearTolerances
    // One Newton solve's iterations, new tangents, Krylov iterations and set-ups into the totals.
    void add(const NewtonReport& r) {
      iterations += r.iterations;
      krylov += r.krylovIterations;
      preconditionerSetUps += r.preconditionerSetUps;
      newTangents += r.newTangents;
    }
    // "Newton 4, Krylov 31" ("Newton 4 + 2 predicting, ..."): the last step, for the progress
    // line.
    std::string lastStep() const;
    // The totals over `steps` steps, for the end summary.
    std::string summary(long steps) const;
  };
  // The options the run uses (the input's, with the diffusion integrator checkIntegrator chose).
  const ImplicitOptions& options() const { return options_; }
  const NewtonCounts& newtonCounts() const { return newton_; }

 private:
  class Transfer;  // MPM's tasks as the diffusion's ConcentrationTransfer

  void checkSetup(const PSNode& root) const;
  // The equilibrium problem of the step: fields, nodal masses, the displacement increments the
  // Velocity and Symmetric faces prescribe over dt, and the swelling of concentrationChange_
  // (swelling_, which the particles' update after it takes too).
  EquilibriumProblem equilibriumProblem(Collective, double dt);
  // Implicit dynamics: the problem's nodal velocities and accelerations of the step's start, from
  // the particles (momentum from the P2G of the step, sum m a S here; Newmark.h).
  void addStartOfStepMotion(Collective, EquilibriumProblem& problem, double dt);
  // A quasi-static step's predicted increments: the start-of-step nodal velocity times dt.
  void addPredictedIncrement(EquilibriumProblem& problem, double dt);
  // The diffusion over the step on its start-of-step configuration (after the step's full P2G);
  // concentrationChange_ receives each particle's change; `c0Change` as DiffusionPass::diffuse's.
  // Returns the time the pass covered: dt, or less where DiffusionPass's cap stopped it.
  // `passError` as DiffusionPass::diffuse's.
  double diffuseOverStep(Collective, double t, double dt,
                         const std::vector<std::vector<double>>* c0Change = nullptr,
                         std::vector<std::vector<double>>* passError = nullptr);
  // The failure of an attempt whose pass covered `covered` of dt.
  std::string passCapFailure(double dt, double covered);
  // <concentration_coupling>trapezoidal: after diffuseOverStep on the step's start (`start`, the
  // diffusion's `atStart`), a Newton solve to kPredictorConvergence predicts the step's end; the
  // diffusion runs again on those particles from the start's c, and the particles are set back to
  // the start with c changed by the mean of the two passes (concentrationChange_ too). Returns the
  // prediction's Newton (a failed one: the step is retaken), its increments by field in
  // `predicted`, and the coupling correction in `correction`
  // (NewtonCounts::lastCouplingCorrection), the error estimate in `estimate`
  // (NewtonCounts::lastErrorEstimate) and the particles' largest accumulated estimate in
  // `accumulated` (NewtonCounts::accumulatedErrorEstimate).
  NewtonReport averageConcentrationChangeOverStep(Collective, double t, double dt,
                                                  const std::vector<ParticleSet>& start,
                                                  std::vector<std::vector<Vec3>>& predicted,
                                                  double& correction, double& estimate,
                                                  double& accumulated);
  // Steps 2-4 from t over dt: the diffusion (twice with the trapezoidal coupling) and Newton,
  // retaken with a smaller dt (and ruleDt) until they hold; `start` holds the step's particles
  // with diffusion. Leaves the particles as the diffusion left them and Newton's increments.
  void takeEquilibriumStep(Collective, double t, double& dt, double& ruleDt,
                           const std::vector<ParticleSet>& start);
  // The particles of `start` and the diffusion state of the step's start, at t (with diffusion).
  void returnToStepStart(Collective, double t, const std::vector<ParticleSet>& start);
  // The largest |dc| of a particle over the diffusion of the step.
  double largestConcentrationChange() const;
  // swelling_ from concentrationChange_ (<swelling_strain>).
  void computeSwelling(Collective);
  // The particles after the converged step (positions, F, stress, the models' state).
  void updateParticlesFromEquilibrium(double dt);
  // The weights and P2G of the particles as they are now (timed).
  void computeWeights(Collective);
  // The failure of the step from t over dt that no retake can cure: rank 0 throws
  // SimulationError, the others StoppedOnAnotherRank.
  [[noreturn]] void stop(double t, double dt, const std::string& refusal,
                         const NewtonReport& report) const;
  // The user's note on a step retaken with dt = smaller (rank 0 prints it).
  static void reportRetake(double t, double smaller, const NewtonReport& report);

  MPM& mpm_;
  // The input's options, with the diffusion integrator the run uses (checkIntegrator).
  ImplicitOptions options_;
  const TimestepController& dt_;
  EquilibriumSolver equilibrium_;
  std::optional<DiffusionPass> diffusion_;  // with <do_scalar_diffusion>true
  std::unique_ptr<Transfer> transfer_;
  std::vector<int> fieldOf_;  // material -> its velocity field (single_velocity members share one)
  int fields_ = 0;
  std::vector<std::vector<double>> concentrationChange_;  // per material: dc of the step
  // Per material: the first pass's estimate of its own error (DiffusionPass::diffuse's
  // passError; empty where its integrator makes none).
  std::vector<std::vector<double>> passError_;
  // Per material, of the last equilibrium problem (<swelling_strain>): the dc its swelling takes,
  // which the problem and the particles' update read (null: no swelling); with cell_mean, the
  // increments and the cell-mean c the swelling reaches (CellMeanSwelling.h).
  std::vector<const double*> swelling_;
  std::vector<std::vector<double>> swellingIncrement_, swellingReached_;
  double lastDt_ = 0;
  double ruleDt_ = 0;  // what ImpMPM's rule scales: the last step's dt, or its ruleDt
  // The largest |dc| of a particle in the last step (with diffusion).
  double maxConcentrationChange_ = 0;
  NewtonCounts newton_;
  struct Tasks {  // timer indices
    int interpolationWeights, particleUpdate, splitting, diffusionState, communication, swelling;
  } tasks_;
};

}  // namespace anode
