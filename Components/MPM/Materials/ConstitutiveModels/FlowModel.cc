#include "Components/MPM/Materials/ConstitutiveModels/FlowModel.h"

#include <cmath>
#include <optional>
#include <string>

namespace anode {

namespace {

double nonNegative(const PSNode& node, const char* tag) {
  const double v = node.require<double>(tag);
  if (v < 0) node.requireChild(tag).fail("<" + std::string(tag) + "> must be >= 0");
  return v;
}

// Johnson-Cook's temperature factor at the fixed 298 K of Uintah's rf_elastic_plastic:
// T* = (298 - T_r) / (T_m - T_r); 1 - T*^m for T* >= 0, 1 - T* below (room temperature T_r
// above 298 hardens). The defaults T_r = 298, T_m = 1793 give T* = 0 and a factor of 1.
double temperatureFactor(const PSNode& flow, double m, double roomT, double meltT) {
  const double T = 298.0;
  if (!(m > 0))
    flow.requireChild("m").fail("<m> must be positive (m = 0 gives zero yield stress in Uintah)");
  if (!(meltT > T))
    flow.requireChild("T_m").fail(
        "<T_m> must be above 298 K, the temperature of rf_elastic_plastic (at or below it "
        "Uintah's material has melted: zero yield stress)");
  if (!(roomT < meltT)) flow.requireChild("T_r").fail("<T_r> must be below <T_m>");
  const double Tstar = (T - roomT) / (meltT - roomT);
  return Tstar < 0 ? 1 - Tstar : 1 - std::pow(Tstar, m);
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
    // Uintah divides the (zero) strain rate by epdot_0; 0 makes the yield stress NaN there.
    if (const PSNode rate = flow.child("epdot_0"))
      if (rate.value<double>() == 0) rate.fail("<epdot_0> must not be 0 (Uintah divides by it)");
    const double theta =
        temperatureFactor(flow, flow.require<double>("m"), flow.get<double>("T_r", 298.0),
                          flow.get<double>("T_m", 1793.0));
    f.A *= theta;
    f.B *= theta;
  } else if (type == "isotropic_hardening") {
    f.type = Type::IsotropicHardening;
    f.sigmaY = flow.require<double>("sigma_Y");
    if (!(f.sigmaY > 0)) flow.requireChild("sigma_Y").fail("<sigma_Y> must be positive");
    f.K = nonNegative(flow, "K");
    if (const PSNode rate = flow.child("reference_strain_rate")) {
      f.referenceRate = rate.value<double>();
      if (!(f.referenceRate > 0)) rate.fail("<reference_strain_rate> must be positive");
      f.rateExponent = flow.require<double>("rate_exponent");
      if (!(f.rateExponent > 0))
        flow.requireChild("rate_exponent").fail("<rate_exponent> must be positive");
    } else if (const PSNode exponent = flow.child("rate_exponent")) {
      exponent.fail("<rate_exponent> needs <reference_strain_rate>");
    }
    if (const std::optional<double> lithiated = flow.find<double>("sigma_Y_lithiated")) {
      f.sigmaYLithiated = *lithiated;
      if (!(f.sigmaYLithiated > 0))
        flow.requireChild("sigma_Y_lithiated").fail("<sigma_Y_lithiated> must be positive");
    }
  } else {
    flow.fail("unknown flow_model type=\"" + type +
              "\"; accepted: johnson_cook, isotropic_hardening");
  }
  return f;
}

}  // namespace anode
