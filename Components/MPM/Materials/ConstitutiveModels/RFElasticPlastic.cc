#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"

#include <cmath>
#include <string>

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/Math/PolarDecomposition.h"

namespace anode {

std::unique_ptr<RFElasticPlastic> RFElasticPlastic::fromInput(const PSNode& node, bool diffusion) {
  const ElasticConstants elastic = ElasticConstants::fromInput(node, diffusion);
  for (const char* inert :
       {"initial_material_temperature", "taylor_quinney_coeff", "coeff_thermal_expansion",
        "critical_stress", "tolerance", "useModifiedEOS", "check_TEPLA_failure_criterion",
        "do_melting", "check_max_stress_failure", "compute_specific_heat",
        "plastic_convergence_algo"})
    node.acceptInert(inert);

  if (const PSNode shear = node.child("shear_modulus_model")) {
    if (shear.requireAttribute("type") != "constant_shear")
      shear.fail("shear_modulus_model type=\"" + *shear.attribute("type") +
                 "\" is not supported; accepted: constant_shear");
    shear.markSubtreeUsed();
  }
  if (const PSNode dev = node.child("deviatoric_stress_model")) {
    if (dev.requireAttribute("type") != "hypoElastic")
      dev.fail("deviatoric_stress_model type=\"" + *dev.attribute("type") +
               "\" is not supported; accepted: hypoElastic");
    dev.markSubtreeUsed();
  }
  // default_hypo is this code's default (UINTAH_UPS.md P2: Uintah builds default_hyper when the
  // tag is absent; see docs/differences-from-uintah.md).
  if (const PSNode eos = node.child("equation_of_state")) {
    const std::string type = eos.requireAttribute("type");
    if (type == "default_hyper")
      eos.fail("equation_of_state type=\"default_hyper\" is not supported; use default_hypo");
    if (type != "default_hypo")
      eos.fail("equation_of_state type=\"" + type + "\" is not supported; accepted: default_hypo");
    eos.markSubtreeUsed();
  }

  std::optional<FlowModel> flow;
  const PSNode flowNode = node.child("flow_model");
  const PSNode yield = node.child("yield_condition");
  if (flowNode) {
    flow = FlowModel::fromInput(flowNode);
    if (!yield) node.fail("<flow_model> requires <yield_condition type=\"vonMises\">");
  }
  if (yield) {
    if (yield.requireAttribute("type") != "vonMises")
      yield.fail("yield_condition type=\"" + *yield.attribute("type") +
                 "\" is not supported; accepted: vonMises");
    if (!flowNode) yield.fail("<yield_condition> requires a <flow_model>");
    yield.markSubtreeUsed();
  }
  // The lithium-dependent laws (ours): K and G at c = c_max.
  bool lithiumDependent = false;
  const char* tags[] = {"bulk_modulus_lithiated", "shear_modulus_lithiated"};
  double moduli[] = {elastic.K, elastic.G};
  for (int k = 0; k < 2; ++k)
    if (const PSNode given = node.child(tags[k])) {
      if (!diffusion)
        given.fail("<" + std::string(tags[k]) +
                   "> needs <do_scalar_diffusion>true: without lithium it has no c to act at");
      moduli[k] = given.value<double>();
      if (!(moduli[k] > 0)) given.fail("<" + std::string(tags[k]) + "> must be positive");
      lithiumDependent = true;
    }
  std::optional<LithiatedModuli> lithiated;
  if (lithiumDependent) lithiated = LithiatedModuli{moduli[0], moduli[1]};
  if (flow && flow->lithiumDependent() && !diffusion)
    flowNode.requireChild("sigma_Y_lithiated")
        .fail(
            "<sigma_Y_lithiated> needs <do_scalar_diffusion>true: without lithium it has no c "
            "to act at");
  return std::make_unique<RFElasticPlastic>(elastic.K, elastic.G, flow, elastic.eta, lithiated);
}

void RFElasticPlastic::initializeState(ParticleSet& p) const {
  eachStateField([&](const auto& field) {
    if (field.physics != Physics::Plasticity || flow_) p.declareModelArray(field);
  });
  std::vector<Mat3>& rotation = p.modelArray<Mat3>(0);
  for (size_t i = 0; i < p.count(); ++i) rotation[i] = rotationOf(p.F[i]);
}

RFElasticPlastic::StateArrays::StateArrays(ParticleSet& p, bool yields, double maxConcentration)
    : rotation_(p.modelArray<Mat3>(0).data()) {
  if (maxConcentration > 0) {
    concentration_ = diffusionParticles(static_cast<const ParticleSet&>(p)).concentration.data();
    perMax_ = 1 / maxConcentration;
  }
  if (!yields) return;
  ep_ = p.modelArray<double>(0).data();
  epdot_ = p.modelArray<double>(1).data();
}

ConcreteModel RFElasticPlastic::concrete() const {
  return {this};
}

}  // namespace anode
