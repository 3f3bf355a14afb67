#include "Components/MPM/Materials/ConstitutiveModels/CompNeoHookean.h"

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"

namespace anode {

std::unique_ptr<CompNeoHookean> CompNeoHookean::fromInput(const PSNode& node, bool diffusion) {
  const ElasticConstants elastic = ElasticConstants::fromInput(node, diffusion);
  // UCNH's options beyond plain hyperelasticity: accepted when off, unsupported when on.
  for (const char* option : {"useModifiedEOS", "usePlasticity", "useDamage"})
    if (const PSNode flag = node.child(option))
      if (flag.value<bool>())
        flag.unsupported(std::string("<") + option + ">true in comp_neo_hook (elastic only here)");
  return std::make_unique<CompNeoHookean>(elastic.K, elastic.G, elastic.eta);
}

void CompNeoHookean::initializeState(ParticleSet& p) const {
  eachStateField([&](const auto& field) { p.declareModelArray(field); });
}

ConcreteModel CompNeoHookean::concrete() const {
  return {this};
}

}  // namespace anode
