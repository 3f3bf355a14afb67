#include "Components/MPM/Materials/ConstitutiveModels/CompNeoHookean.h"

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"

namespace anode {

std::unique_ptr<CompNeoHookean> CompNeoHookean::fromInput(const PSNode& node, bool diffusion) {
  const double K = node.require<double>("bulk_modulus");
  if (!(K > 0)) node.requireChild("bulk_modulus").fail("<bulk_modulus> must be positive");
  const double G = node.require<double>("shear_modulus");
  if (!(G > 0)) node.requireChild("shear_modulus").fail("<shear_modulus> must be positive");
  double eta = 0;
  if (diffusion)
    eta = node.require<double>("volume_expansion_coeff");
  else
    node.acceptInert("volume_expansion_coeff");
  // UCNH's options beyond plain hyperelasticity: accepted when off, unsupported when on.
  for (const char* option : {"useModifiedEOS", "usePlasticity", "useDamage"})
    if (const PSNode flag = node.child(option))
      if (flag.value<bool>())
        flag.fail(std::string("<") + option +
                  ">true is not supported for comp_neo_hook (elastic only)");
  return std::make_unique<CompNeoHookean>(K, G, eta);
}

void CompNeoHookean::initializeState(ParticleSet& p) const {
  eachStateField([&](const auto& field) { p.declareModelArray(field); });
}

ConcreteModel CompNeoHookean::concrete() const {
  return {this};
}

}  // namespace anode
