#include <cmath>

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
  if (diffusion) {
    c.eta = node.require<double>("volume_expansion_coeff");
    // The swelling J = exp(3 eta c) of the stress-free particle (c = c / c_max in [0, 1]) within
    // 1/1000 and 1000 at c = 1: silicon's is about 4 (eta = 0.46), the paper's eta 0.56.
    if (!(std::abs(c.eta) <= std::log(1000.0) / 3))
      node.requireChild("volume_expansion_coeff")
          .fail(
              "<volume_expansion_coeff> must lie within -2.3 and 2.3: the swelling J = exp(3 "
              "eta c) at c = c_max within 1/1000 and 1000 (silicon's eta is about 0.46)");
  } else {
    node.acceptInert("volume_expansion_coeff");
  }
  return c;
}

}  // namespace anode
