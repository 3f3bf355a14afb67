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

ElasticConstants ElasticConstants::fromInput(const PSNode& node, bool diffusion) {
  ElasticConstants c{};
  c.K = node.require<double>("bulk_modulus");
  if (!(c.K > 0)) node.requireChild("bulk_modulus").fail("<bulk_modulus> must be positive");
  c.G = node.require<double>("shear_modulus");
  if (!(c.G > 0)) node.requireChild("shear_modulus").fail("<shear_modulus> must be positive");
  if (diffusion)
    c.eta = node.require<double>("volume_expansion_coeff");
  else
    node.acceptInert("volume_expansion_coeff");
  return c;
}

}  // namespace anode
