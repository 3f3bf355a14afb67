#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"

namespace anode {

std::unique_ptr<ConstitutiveModel> createConstitutiveModel(const PSNode& node, bool diffusion) {
  const std::string type = node.requireAttribute("type");
  if (type == "rf_elastic_plastic") return RFElasticPlastic::fromInput(node, diffusion);
  if (type == "comp_neo_hook") return CompNeoHookean::fromInput(node, diffusion);
  node.fail("constitutive_model type=\"" + type +
            "\" is not supported; accepted: rf_elastic_plastic, comp_neo_hook");
}

}  // namespace anode
