#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"

namespace anode {

namespace {

double nonNegative(const PSNode& node, const char* tag) {
  const double v = node.require<double>(tag);
  if (v < 0) node.requireChild(tag).fail("<" + std::string(tag) + "> must be >= 0");
  return v;
}

}  // namespace

FlowModel FlowModel::fromInput(const PSNode& flow) {
  FlowModel f;
  const std::string type = flow.requireAttribute("type");
  if (type == "johnson_cook") {
    f.type = Type::JohnsonCook;
    f.A = flow.require<double>("A");
    if (!(f.A > 0)) flow.requireChild("A").fail("<A> (initial yield stress) must be positive");
    f.B = nonNegative(flow, "B");
    f.n = nonNegative(flow, "n");
    const double C = flow.require<double>("C");
    if (C != 0)
      flow.requireChild("C").unsupported(
          "strain-rate hardening <C> != 0 (Uintah's rf_elastic_plastic also evaluates it at zero "
          "rate, so it changes nothing there)");
    // The temperature factor 1 - T*^m is 1 at room temperature, which this model keeps, provided
    // m > 0 (Uintah evaluates 0^0 = 1 and gets a zero yield stress).
    const double m = flow.require<double>("m");
    if (!(m > 0))
      flow.requireChild("m").fail("<m> must be positive (m = 0 gives zero yield stress in Uintah)");
    flow.acceptInert("epdot_0");
    flow.acceptInert("T_r");
    flow.acceptInert("T_m");
  } else if (type == "isotropic_hardening") {
    f.type = Type::IsotropicHardening;
    f.sigmaY = flow.require<double>("sigma_Y");
    if (!(f.sigmaY > 0)) flow.requireChild("sigma_Y").fail("<sigma_Y> must be positive");
    f.K = nonNegative(flow, "K");
  } else {
    flow.fail("unknown flow_model type=\"" + type +
              "\"; accepted: johnson_cook, isotropic_hardening");
  }
  return f;
}

}  // namespace anode
