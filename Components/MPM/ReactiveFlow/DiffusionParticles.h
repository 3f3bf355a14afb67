// The particle arrays of the diffusion subcomponent, which it declares on each material's
// particle set (declareDiffusionArrays) and reaches there through a view (DiffusionParticles).
// They exist only with <do_scalar_diffusion>true, the flux arrays only for materials whose
// particles a <scalar_flux> can reach (empty otherwise).
#pragma once

#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "Components/MPM/ParticleSet.h"
#include "Core/Math/Types.h"

namespace anode {

// The arrays' fields, in declaration order (the order of checkpoints and splitting).
struct DiffusionFields {
  static inline const ParticleField<double> concentration{"p.concentration", Physics::Diffusion,
                                                          0.0, OnSplit::Copy};
  static inline const ParticleField<Vec3> concentrationGradient{
      "p.concentrationGradient", Physics::Diffusion, Vec3::Zero(), OnSplit::Copy};
  static inline const ParticleField<double> diffusivity{"p.diffusivity", Physics::Diffusion, 0.0,
                                                        OnSplit::Copy};
  static inline const ParticleField<double> externalScalarFlux{"p.externalScalarFlux",
                                                               Physics::FluxBC, 0.0, OnSplit::Copy};
  static inline const ParticleField<Vec3i> loadCurveID{"p.loadCurveID", Physics::FluxBC,
                                                       Vec3i::Zero(), OnSplit::Own};
  static inline const ParticleField<Vec3> area{"p.area", Physics::FluxBC, Vec3::Zero(),
                                               OnSplit::Own};
  static inline const ParticleField<Vec3> stressPotentialGradient{
      "p.stressPotentialGradient", Physics::StressDrivenDiffusion, Vec3::Zero(), OnSplit::Copy};

  // Calls f(field) for each field above.
  template <class F>
  static void forEach(F&& f) {
    f(concentration);
    f(concentrationGradient);
    f(diffusivity);
    f(externalScalarFlux);
    f(loadCurveID);
    f(area);
    f(stressPotentialGradient);
  }
};

// Declares the arrays on `p` and creates those of Physics::Diffusion.
inline void declareDiffusionArrays(ParticleSet& p) {
  DiffusionFields::forEach([&p](const auto& field) { p.declareArray(field); });
  p.enable(Physics::Diffusion);
}

// The arrays of one particle set (`Set`: ParticleSet, or const ParticleSet to read them).
template <class Set>
struct DiffusionArrays {
  template <class T>
  using Array = std::conditional_t<std::is_const_v<Set>, const std::vector<T>, std::vector<T>>;

  explicit DiffusionArrays(Set& p)
      : concentration(of(p, DiffusionFields::concentration)),
        concentrationGradient(of(p, DiffusionFields::concentrationGradient)),
        diffusivity(of(p, DiffusionFields::diffusivity)),
        externalScalarFlux(of(p, DiffusionFields::externalScalarFlux)),
        loadCurveID(of(p, DiffusionFields::loadCurveID)),
        area(of(p, DiffusionFields::area)),
        stressPotentialGradient(of(p, DiffusionFields::stressPotentialGradient)) {}

  Array<double>& concentration;        // p.concentration, normalised
  Array<Vec3>& concentrationGradient;  // p.concentrationGradient, from the previous step
  Array<double>& diffusivity;          // p.diffusivity (Eq. 23 or 24)
  Array<double>& externalScalarFlux;   // p.externalScalarFlux: dc/dt from the flux BCs (Eq. 16)
  Array<Vec3i>& loadCurveID;           // p.loadCurveID: up to 3 load curves (0: none)
  Array<Vec3>& area;                   // p.area: face area of each of those curves
  // p.stressPotentialGradient: grad phi_0 + s_p grad c_0, phi = Omega tau_h / RT
  // (ChemicalPotential.h), of the diffusion pass's particles (chemical_potential only)
  Array<Vec3>& stressPotentialGradient;

 private:
  template <class T>
  static Array<T>& of(Set& p, const ParticleField<T>& field) {
    if (Array<T>* array = p.findArray(field)) return *array;
    throw std::logic_error(std::string("particles without the diffusion array ") + field.label);
  }
};
using DiffusionParticles = DiffusionArrays<ParticleSet>;
using ConstDiffusionParticles = DiffusionArrays<const ParticleSet>;

inline DiffusionParticles diffusionParticles(ParticleSet& p) {
  return DiffusionParticles(p);
}
inline ConstDiffusionParticles diffusionParticles(const ParticleSet& p) {
  return ConstDiffusionParticles(p);
}

// p.concentration, or null for particles without the diffusion arrays (a run without diffusion).
inline const std::vector<double>* concentrationOf(const ParticleSet& p) {
  return p.findArray(DiffusionFields::concentration);
}

}  // namespace anode
