// The particle arrays of the diffusion subcomponent. They exist only with
// <do_scalar_diffusion>true, the flux arrays only for materials whose particles a <scalar_flux>
// can reach; ParticleSet holds them with the mechanics arrays, in its one list of arrays.
#pragma once

#include <vector>

#include "Components/MPM/ParticleField.h"
#include "Core/Math/Types.h"

namespace anode {

struct DiffusionParticles {
  std::vector<double> concentration;        // p.concentration, normalised
  std::vector<Vec3> concentrationGradient;  // p.concentrationGradient, from the previous step
  std::vector<double> diffusivity;          // p.diffusivity (Eq. 23 or 24)
  std::vector<double> externalScalarFlux;  // p.externalScalarFlux: dc/dt from the flux BCs (Eq. 16)
  std::vector<Vec3i> loadCurveID;          // p.loadCurveID: up to 3 load curves (0: none)
  std::vector<Vec3> area;                  // p.area: face area of each of those curves

 protected:
  // Calls f(array, field) for each array above (part of ParticleSet::eachArray).
  template <class Self, class F>
  static void eachDiffusionArray(Self& s, F& f) {
    using P = Physics;
    using S = OnSplit;
    f(s.concentration, ParticleField<double>{"p.concentration", P::Diffusion, 0.0, S::Copy});
    f(s.concentrationGradient,
      ParticleField<Vec3>{"p.concentrationGradient", P::Diffusion, Vec3::Zero(), S::Copy});
    f(s.diffusivity, ParticleField<double>{"p.diffusivity", P::Diffusion, 0.0, S::Copy});
    f(s.externalScalarFlux, ParticleField<double>{"p.externalScalarFlux", P::FluxBC, 0.0, S::Copy});
    f(s.loadCurveID, ParticleField<Vec3i>{"p.loadCurveID", P::FluxBC, Vec3i::Zero(), S::Own});
    f(s.area, ParticleField<Vec3>{"p.area", P::FluxBC, Vec3::Zero(), S::Own});
  }
};

}  // namespace anode
