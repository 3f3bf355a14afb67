// Flow stress sigma_y(eps_p) of rf_elastic_plastic's von Mises yield (paper Eqs. 34-35).
#pragma once

#include <cmath>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct FlowModel {
  enum class Type { JohnsonCook, IsotropicHardening } type = Type::IsotropicHardening;
  // johnson_cook at room temperature and zero rate: sigma_y = A + B*eps_p^n.
  double A = 0, B = 0, n = 0;
  // isotropic_hardening: sigma_y = sigma_Y + K*eps_p (paper Eq. 35 with K the hardening modulus).
  double sigmaY = 0, K = 0;

  static FlowModel fromInput(const PSNode& flowNode);

  double flowStress(double ep) const {
    if (type == Type::IsotropicHardening) return sigmaY + K * ep;
    return A + B * std::pow(ep, n);
  }
  // d sigma_y / d eps_p.
  double hardeningModulus(double ep) const {
    if (type == Type::IsotropicHardening) return K;
    return ep > 0 ? B * n * std::pow(ep, n - 1) : 0.0;
  }
};

}  // namespace anode
