// The options of an implicit run, in Uintah's ImpMPM vocabulary (<MPM><time_integrator>implicit,
// ImpMPMFlags; defaults equal Uintah's): Newton's convergence criteria and the rules that retake
// a step and grow or shrink dt by Newton's iteration count (docs/quasi-static.md).
#pragma once

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct ImplicitOptions {
  // <dynamic>: Newmark (ImpMPM's default, true) or quasi-static equilibrium (false).
  bool dynamic = true;
  // Newton stops when both ratios fall to these: |du|^2 over its largest value in the step, and
  // du.r over its value in the first iteration (or when those largest/first values fall to them).
  double convergenceDisp = 1e-10, convergenceEnergy = 4e-10;
  // A step taking more Newton iterations than this is retaken with dt x decreaseFactor.
  int maxIterations = 25;
  // The next dt is dt x decreaseFactor after a step of at least itersToDecrease iterations,
  // dt x increaseFactor after one of at most itersToIncrease (TimestepController::afterNewton).
  int itersToDecrease = 12, itersToIncrease = 4;
  double decreaseFactor = 0.6, increaseFactor = 2;
  // <hourglass_stabilization> (ours, not ImpMPM's): epsilon of Implicit/HourglassStabilization.h,
  // the stiffness of each particle's non-affine displacement relative to its own; 0 turns it off.
  double hourglassStabilization = 0.1;
  // <jacobian_coupling_share> (ours): Newton's Jacobian leaves out a particle's coupling of two
  // nodes unless it holds at least this share of each one's mass (its stiffness at such a node
  // kept on the node's diagonal block): a CPDI corner just across a cell face reaches a layer of
  // nodes two cells away with weights of round-off to 1e-4. The residual keeps every coupling, so
  // Newton converges to the same equilibrium (docs/quasi-static.md, "Assembly"). 0 (the default)
  // keeps all, and the exact Jacobian's quadratic convergence; the large pillar's cycle takes
  // 1e-4. At most 1e-3: at 1e-2, on the CPDI compression of test_quasi_static, Newton stopped with
  // the stresses 43% from those of the full Jacobian (57 iterations against 12). Under
  // <error_tolerance> the default is kErrorControlCouplingShare.
  static constexpr double kErrorControlCouplingShare = 1e-4;
  double jacobianCouplingShare = 0;
  // <jacobian_reuse> (ours): Newton keeps its last Jacobian for the next correction after a small,
  // fast one (Implicit/EquilibriumSolver.cc, kKeptTangentRatio): an iteration without the
  // particles' tangents, but its converged u is within Newton's criteria, not to round-off beyond
  // them as a last quadratic iteration leaves it. False (the default, as ImpMPM): a new Jacobian
  // every iteration.
  bool jacobianReuse = false;
  // <max_concentration_change> (ours): with diffusion, the next dt is at most the one whose
  // largest change of a particle's c would be this (the last step's change scaled linearly); 0:
  // no such bound (the default with <error_tolerance>).
  double maxConcentrationChange = 0.05;
  // <error_tolerance> (ours): with diffusion, quasi-static steps chosen by their error estimate
  // (ImplicitStep's: the largest local error of a particle's c / c_max that the trapezoidal mean
  // of the step's two diffusion passes leaves, Implicit/TrapezoidalCoupling.h), each step's held
  // to this and retaken above it, dt from a PI controller (TimestepController::afterErrorEstimate).
  // It makes the coupling trapezoidal (a staggered one is an input error), Newton's iterations
  // only shrink dt, and <max_concentration_change> applies only where given. The default is
  // kDefaultErrorTolerance on quasi-static steps with diffusion unless the input asks for
  // <concentration_coupling>staggered; 0 otherwise, and 0 turns it off.
  static constexpr double kDefaultErrorTolerance = 0.01;
  double errorTolerance = 0;
  // <concentration_coupling> (ours): how a quasi-static step's diffusion sees the mechanics.
  // Staggered: the diffusion sub-steps run on the particles of the step's start, then Newton.
  // Trapezoidal: a Newton solve to kPredictorConvergence predicts the step's end; the sub-steps
  // run again on those particles from the start's c; the step takes the mean of the two changes of
  // c and solves Newton for it from the prediction (docs/quasi-static.md).
  enum class ConcentrationCoupling { Staggered, Trapezoidal };
  ConcentrationCoupling concentrationCoupling = ConcentrationCoupling::Staggered;
  // <diffusion_integrator> (ours): how a quasi-static step's diffusion passes over dt. Euler:
  // forward-Euler sub-steps at <timestep_multiplier> x the explicit limits (Eq. 44 and the flux
  // limit), each with the gradient of the sub-step before. RKL2: one second-order
  // Runge-Kutta-Legendre step (ReactiveFlow/RungeKuttaLegendre.h) of as many stages as the same
  // limit needs, each stage's rate with the gradient of its own c and the load curves at the
  // pass's midpoint (docs/quasi-static.md).
  // Under <error_tolerance> without the tag it is RKL2, unless the run has what RKL2 does not
  // support (DiffusionPass::checkIntegrator then takes Euler): rkl2ByDefault.
  enum class DiffusionIntegrator { Euler, Rkl2 };
  DiffusionIntegrator diffusionIntegrator = DiffusionIntegrator::Euler;
  bool rkl2ByDefault = false;
  // <subcell_concentration_relaxation> (ours): each step's diffusion first draws the particles
  // towards the grid's c at their places, so differences the grid does not see fade
  // (ReactiveFlow/SubcellRelaxation.h); off, Eq. 8 carries them unchanged.
  bool subcellConcentrationRelaxation = false;
  // <swelling_strain> (ours): the concentration change a particle's swelling takes in the
  // equilibrium of a step with diffusion. Particle (the default): its own dc, as the explicit step
  // takes it. Cell mean: the volume-weighted mean of dc over the cells its domain overlaps
  // (Implicit/CellMeanSwelling.h), which a displacement varying along one axis can meet: on a
  // film whose c varies with depth it removes the stress normal to the film that alternates from
  // one layer of particles to the next; on a lithiated sphere it gains nothing (docs/
  // quasi-static.md, "Swelling on cells").
  enum class SwellingStrain { Particle, CellMean };
  SwellingStrain swellingStrain = SwellingStrain::Particle;

  // Reads the ImpMPM tags of <MPM> (only with <time_integrator>implicit); `diffusion`: whether
  // the run diffuses lithium (<do_scalar_diffusion>), which sets <error_tolerance>'s default.
  static ImplicitOptions fromInput(const PSNode& mpm, bool diffusion);
};

}  // namespace anode
