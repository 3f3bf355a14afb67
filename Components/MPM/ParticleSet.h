// Particle state of one material, stored as structure-of-arrays. Plasticity arrays exist only for
// materials that can yield.
#pragma once

#include <cstdint>
#include <vector>

#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/Math/Types.h"

namespace anode {

// The diffusion subcomponent declares its own arrays (ReactiveFlow/DiffusionParticles.h).
struct ParticleSet : DiffusionParticles {
  std::vector<int64_t> id;           // p.particleID, stable for the run
  std::vector<Vec3> x;               // p.x
  std::vector<Vec3> velocity;        // p.velocity
  std::vector<Vec3> displacement;    // p.displacement
  std::vector<double> mass;          // p.mass (constant)
  std::vector<double> volume;        // p.volume = mass/rho0 * det F
  std::vector<Mat3> F;               // p.deformationMeasure
  std::vector<Mat3> stress;          // p.stress (Cauchy, lab frame)
  std::vector<Mat3> size;            // p.size: reference domain edge vectors in grid-cell units
  std::vector<Mat3> rotation;        // R of F = R U: the stress update's frame, kept so a step computes one
  std::vector<double> plasticStrain;      // p.plasticStrain (yielding materials only)
  std::vector<double> plasticStrainRate;  // p.plasticStrainRate (yielding materials only)

  // Particle splitting (only with <refine_particles>true): 1 once a particle or its parent split.
  std::vector<uint8_t> refined;

  size_t count() const { return x.size(); }

  // Calls f(array) for every array above, in declaration order (the one list of them).
  template <class F>
  void forEachArray(F&& f) { eachArray(*this, f); }
  template <class F>
  void forEachArray(F&& f) const { eachArray(*this, f); }

  // Appends a copy of particle i (every array that exists) and returns its index.
  size_t duplicate(size_t i) {
    forEachArray([i](auto& v) {
      if (!v.empty()) v.push_back(v[i]);
    });
    return count() - 1;
  }

  // Frees the spare capacity of every array (growth by appending leaves up to half unused).
  void shrinkToFit() {
    forEachArray([](auto& v) { v.shrink_to_fit(); });
  }

 private:
  template <class Self, class F>
  static void eachArray(Self& s, F& f) {
    f(s.id), f(s.x), f(s.velocity), f(s.displacement), f(s.mass), f(s.volume), f(s.F), f(s.stress), f(s.size);
    f(s.rotation);
    f(s.plasticStrain), f(s.plasticStrainRate), f(s.concentration), f(s.concentrationGradient), f(s.diffusivity);
    f(s.externalScalarFlux), f(s.loadCurveID), f(s.area), f(s.refined);
  }
};

}  // namespace anode
