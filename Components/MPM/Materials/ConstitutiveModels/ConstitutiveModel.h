// What the step needs to know of a constitutive model; the stress update itself is called on the
// concrete model inside the particle loop (MPM dispatches once per material, never per particle).
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
  // True if the stress depends on the concentration (swelling).
  virtual bool swells() const = 0;
  // K + 4G/3: the modulus of the dilatational wave speed (paper Eq. 41).
  virtual double dilatationalModulus() const = 0;
  virtual bool canYield() const = 0;
};

// Factory keyed by <constitutive_model type="...">; `diffusion` tells whether concentration exists.
std::unique_ptr<ConstitutiveModel> createConstitutiveModel(const PSNode& node, bool diffusion);

}  // namespace anode
