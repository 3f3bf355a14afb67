#include "Components/MPM/Materials/ConstitutiveModels/ConstitutiveModel.h"
#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"

namespace anode {

std::unique_ptr<ConstitutiveModel> createConstitutiveModel(const PSNode& node, bool diffusion) {
  const std::string type = node.requireAttribute("type");
  if (type == "rf_elastic_plastic") return RFElasticPlastic::fromInput(node, diffusion);
  node.fail("constitutive_model type=\"" + type +
            "\" is not supported; accepted: rf_elastic_plastic");
}

}  // namespace anode
