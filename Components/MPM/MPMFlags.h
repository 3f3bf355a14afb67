// Options of the <MPM> block (UINTAH_UPS.md §2.4) and <PhysicalConstants>.
#pragma once

#include <optional>

#include "Components/MPM/ImplicitOptions.h"
#include "Components/MPM/Interpolator.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct MPMFlags {
  InterpolatorKind interpolator = InterpolatorKind::Linear;
  int minimumSubcyclesForF = 1;
  double minimumMassForAcc = 0.0;
  double minimumParticleMass = 3e-15;
  double artificialDampingCoeff = 0.0;
  Vec3 gravity = Vec3::Zero();
  bool doScalarDiffusion = false;
  bool useLoadCurves = false;
  // SD-Type Dirichlet acting on particles by relaxation (true) or through Uintah's nodal rate.
  bool particleDirichlet = true;
  // How a node's flux source G reaches particles (docs/diffusion.md step 5): by m S R(c)
  // (`restricted`, default) or by m S as Uintah (`weights`); and whether G is in c* (Eq. 18).
  bool restrictedFluxReceivers = true;
  bool fluxSourceInCStar = true;
  // do_auto_cycle_bc: the flux sign flips when the concentration crosses these thresholds.
  bool autoCycle = false, autoCycleUseMinMax = false;
  double autoCycleMax = 0.9, autoCycleMin = 0.1;
  bool refineParticles = false;
  double stretchRatio = 0;  // split a particle whose domain is stretched beyond this ratio
  int refineMaterial = -1;  // -1: all materials
  // <time_integrator>implicit: each step solves equilibrium (DESIGN.md §4b); empty: explicit.
  std::optional<ImplicitOptions> implicit;

  // Reads <MPM>, <PhysicalConstants> and checks <SimulationComponent> and <AMR>.
  static MPMFlags fromInput(const PSNode& root);
};

}  // namespace anode
