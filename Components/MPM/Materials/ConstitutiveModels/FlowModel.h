// Flow stress sigma_y(eps_p) of rf_elastic_plastic's von Mises yield (paper Eqs. 34-35).
#pragma once

#include <cmath>
#include <limits>

#include "Core/Math/Simd.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct FlowModel {
  enum class Type { JohnsonCook, IsotropicHardening } type = Type::IsotropicHardening;
  // johnson_cook at zero rate and 298 K: sigma_y = (A + B*eps_p^n) * (1 - T*^m); A and B hold
  // the temperature factor (1 with the default T_r = 298 K).
  double A = 0, B = 0, n = 0;
  // isotropic_hardening: sigma_y = sigma_Y + K*eps_p (paper Eq. 35 with K the hardening modulus).
  double sigmaY = 0, K = 0;
  // isotropic_hardening's <sigma_Y_lithiated> (ours): sigma_Y at c = c_max, linear in c between
  // (the lithium-dependent laws, docs/input-reference.md); NaN: sigma_Y at every c.
  double sigmaYLithiated = std::numeric_limits<double>::quiet_NaN();

  static FlowModel fromInput(const PSNode& flowNode);

  // For one particle (S = double) or a pack of them (Core/Math/Simd.h). With B = 0 or n = 0,
  // johnson_cook is perfectly plastic (sigma_y = A + B, as eps_p^0 = 1): no power to take.
  template <class S>
  S flowStress(const S& ep) const {
    if (type == Type::IsotropicHardening) return S(sigmaY) + S(K) * ep;
    if (perfectlyPlastic()) return S(A + B);
    return S(A) + S(B) * powOf(ep, n);
  }
  // isotropic_hardening's rate-dependent flow (ours, Bower, Guduru & Sethuraman 2011): with
  // <reference_strain_rate> e0 > 0 and <rate_exponent> m, the plastic strain rate above the flow
  // stress is e0 (sigma_e / sigma_y - 1)^m (0 below it); e0 = 0: rate-independent.
  double referenceRate = 0, rateExponent = 1;
  bool rateDependent() const { return referenceRate > 0; }
  // What sigma_y gains at c / c_max = `c` over its value at c = 0 (<sigma_Y_lithiated>).
  template <class S>
  S lithiumShift(const S& c) const {
    if (!lithiumDependent()) return S(0.0);
    return S(sigmaYLithiated - sigmaY) * c;
  }
  bool lithiumDependent() const { return !std::isnan(sigmaYLithiated); }
  // d sigma_y / d eps_p.
  template <class S>
  S hardeningModulus(const S& ep) const {
    if (type == Type::IsotropicHardening) return S(K);
    if (perfectlyPlastic()) return S(0.0);
    return select(ep > S(0.0), S(B * n) * powOf(ep, n - 1), S(0.0));
  }

 private:
  bool perfectlyPlastic() const { return B == 0 || n == 0; }
};

}  // namespace anode
