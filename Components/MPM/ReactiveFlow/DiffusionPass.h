// The diffusion of a quasi-static step (DESIGN.md §4b, step 2; docs/quasi-static.md): the
// particles stay where the step began and their c changes over [t, t + dt] in explicit sub-steps
// of Eqs. 5, 18 and 8 (<diffusion_integrator>euler) or in the stages of one RKL2 step (rkl2,
// RungeKuttaLegendre.h), after the sub-cell relaxation where the input asks for it
// (<subcell_concentration_relaxation>, SubcellRelaxation.h). The grid's part is MPM's, asked for
// through ConcentrationTransfer; the rest is ReactiveFlow's (its diffusion state, Eq. 44 and the
// flux limit).
#pragma once

#include <optional>
#include <vector>

#include "Components/MPM/ImplicitOptions.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/ReactiveFlow/ConcentrationTransfer.h"
#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"
#include "Core/Util/Timers.h"

namespace anode {

class DiffusionPass {
 public:
  // The integrator the run's passes use: RKL2's conditions on the run (`diffusion` null without
  // diffusion) checked, errors for what a stage cannot do when the input asked for it, a warning
  // where there is nothing to integrate; RKL2 by default (ImplicitOptions::rkl2ByDefault) gives
  // way to Euler there instead.
  static ImplicitOptions::DiffusionIntegrator checkIntegrator(const PSNode& root,
                                                              const MPMFlags& flags,
                                                              const ImplicitOptions& options,
                                                              const ReactiveFlow* diffusion);
  // substepMultiplier: a sub-step's share of the explicit limits (<timestep_multiplier>).
  // `grid`: MPM's (its cell edges).
  DiffusionPass(ReactiveFlow& diffusion, const Grid& grid, const ImplicitOptions& options,
                double substepMultiplier, TaskTimers& timers);
  // The most sub-steps (euler) or stages (rkl2) of one pass: a pass's cost stays bounded however
  // small the sub-steps' limit is against dt (docs/quasi-static.md, "Failure and dt"). Under
  // error control the halves of an RKL2 pass take at most 142 stages each, since the reach of
  // 142 is above half of 200's, and the step of dt beside them for the estimate at most 200.
  static constexpr long kMaxRateEvaluations = 200;
  // A sub-step's length, the multiplier times the smaller of Eq. 44 and the flux
  // limit over all ranks.
  double substepLimit(Collective, const std::vector<MPMMaterial>& materials) const;
  // The longest pass kMaxRateEvaluations cover from the present diffusion state: that many
  // sub-steps of substepLimit, or the RKL2 step of that many stages.
  double longestPass(Collective every, const std::vector<MPMMaterial>& materials) const {
    return coveredBy(substepLimit(every, materials));
  }
  struct Pass {
    long evaluations = 0;  // of the rate: sub-steps or stages
    double covered = 0;    // the time the pass integrated: dt, or less where the cap stopped it
  };
  // c over [t, t + dt] of the particles (after the step's full P2G on `grid`); each particle's
  // change of c into change[m] (sized here), and the diffusion state of the end. A pass that
  // would need more than kMaxRateEvaluations (the limit fell during the sub-steps, or the step
  // started elsewhere than the state its dt was bounded from) stops there with `covered` < dt:
  // the caller retakes the step.
  // `c0Change` (per material and particle): what the c the particles' stress holds differs from
  // their c (the first pass's change, for a pass on the predicted end); null: nothing.
  // `passError` (rkl2 under error control only; null: none): each particle's estimate of the
  // pass's own local error in c (signed, the pass's c less the exact one), by step doubling: the
  // pass is two RKL2 steps of dt/2, and the one step of dt taken beside them differs from them
  // by three times their error (a second-order step's C dt^3 against 2 C (dt/2)^3).
  Pass diffuse(Collective, ConcentrationTransfer& grid, std::vector<MPMMaterial>& materials,
               double t, double dt, std::vector<std::vector<double>>& change,
               const std::vector<std::vector<double>>* c0Change = nullptr,
               std::vector<std::vector<double>>* passError = nullptr);
  // Keeps the diffusion state of the step's start (ReactiveFlow::StepState), which
  // returnToStepStart takes up again with the diffusion state of the particles at time t (the
  // step's start, or its predicted end: the start's particles are the caller's).
  void keepStepStart() { start_ = diffusion_.stepState(); }
  void returnToStepStart(Collective, std::vector<MPMMaterial>& materials, double t);
  // Frees that state once the step is taken (it holds the flux BCs' state).
  void releaseStepStart() { start_.reset(); }
  // A step dropped: that state as it was kept (the caller's particles hold the rest of the
  // start, their diffusion state as the step before left it), then freed.
  void dropStep() {
    diffusion_.restoreStepState(*start_);
    start_.reset();
  }

 private:
  // The time kMaxRateEvaluations cover with sub-steps of `limit` (rkl2: its stability interval).
  double coveredBy(double limit) const;
  Pass diffuseInSubsteps(Collective, ConcentrationTransfer& grid,
                         std::vector<MPMMaterial>& materials, double t, double dt,
                         std::vector<std::vector<double>>& change);
  // One RKL2 step over dt, or under error control two of dt/2, their stages as many as the
  // sub-steps' limit at the start needs; `passError` as diffuse's.
  Pass diffuseInLegendreStages(Collective, ConcentrationTransfer& grid,
                               std::vector<MPMMaterial>& materials, double t, double dt,
                               std::vector<std::vector<double>>& change,
                               std::vector<std::vector<double>>* passError);
  // The particles drawn towards the grid's c of their P2G over dt, their change added.
  void relaxSubcellConcentration(Collective, ConcentrationTransfer& grid,
                                 std::vector<MPMMaterial>& materials, double dt,
                                 std::vector<std::vector<double>>& change);
  void updateDiffusionState(Collective, std::vector<MPMMaterial>& materials, double t);
  // p.stressPotentialGradient, grad phi_0 + s_p grad c_0, of the stress-driven materials' particles
  // (ChemicalPotential.h) from their stress, F and c (and c0Change, as diffuse's); false when no
  // material's flux has a stress part.
  bool computeStressPotentialGradients(Collective, ConcentrationTransfer& grid,
                                       std::vector<MPMMaterial>& materials,
                                       const std::vector<std::vector<double>>* c0Change);

  ReactiveFlow& diffusion_;
  const Grid& grid_;
  ImplicitOptions::DiffusionIntegrator integrator_;
  bool relaxation_;
  bool halves_;  // an RKL2 pass in two steps of dt/2 (under error control)
  double substepMultiplier_;
  TaskTimers& timers_;
  int diffusionStateTask_, particleUpdateTask_;
  std::vector<double> nodeMassDiffusivity_;          // the relaxation's sum S m D
  std::vector<double> nodeMassStressPotential_;      // sum S m phi
  std::vector<double> nodeMassStressConcentration_;  // sum S m c_0
  std::optional<ReactiveFlow::StepState> start_;     // keepStepStart's
};

}  // namespace anode
