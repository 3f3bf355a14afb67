// Constitutive model interface: one virtual call per material per step, never per particle.
#pragma once

#include <memory>
#include <vector>

#include "Components/MPM/ParticleSet.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

class ConstitutiveModel {
 public:
  virtual ~ConstitutiveModel() = default;
  // Creates the per-particle state this model needs (and nothing else).
  virtual void initializeState(ParticleSet& p) const = 0;
  // Stress at the end of the step from the velocity gradient L and the new F; p.F still holds
  // the old F on entry and the new one on exit. `concentrationIncrement` (c^{n+1} - c^n of the
  // step, per particle) is null without diffusion.
  virtual void computeStressTensor(ParticleSet& p, const std::vector<Mat3>& L, const std::vector<Mat3>& Fnew,
                                   const std::vector<double>* concentrationIncrement, double dt) const = 0;
  // True if the stress depends on the concentration (swelling).
  virtual bool swells() const = 0;
  // K + 4G/3: the modulus of the dilatational wave speed (paper Eq. 41).
  virtual double dilatationalModulus() const = 0;
  virtual bool canYield() const = 0;
};

// Factory keyed by <constitutive_model type="...">; `diffusion` tells whether concentration exists.
std::unique_ptr<ConstitutiveModel> createConstitutiveModel(const PSNode& node, bool diffusion);

}  // namespace anode
