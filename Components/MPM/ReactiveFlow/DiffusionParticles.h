// The particle arrays of the diffusion subcomponent. They exist only with
// <do_scalar_diffusion>true, the flux arrays only for materials whose particles a <scalar_flux>
// can reach; ParticleSet holds them with the mechanics arrays (one list: ParticleSet::eachArray).
#pragma once

#include <vector>

#include "Core/Math/Types.h"

namespace anode {

struct DiffusionParticles {
  std::vector<double> concentration;        // p.concentration, normalised
  std::vector<Vec3> concentrationGradient;  // p.concentrationGradient, from the previous step
  std::vector<double> diffusivity;          // p.diffusivity (Eq. 23 or 24)
  // Flux boundary conditions (only when <scalar_flux> blocks exist).
  std::vector<double> externalScalarFlux;   // p.externalScalarFlux: dc/dt from the flux BCs (Eq. 16)
  std::vector<Vec3i> loadCurveID;           // p.loadCurveID: up to 3 load curves (0: none)
  std::vector<Vec3> area;                   // p.area: face area of each of those curves
};

}  // namespace anode
