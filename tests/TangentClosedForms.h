// The closed forms the algorithmic tangent is checked against (tests/test_tangent.cc,
// tests/test_residual_taylor.cc): each constitutive model's dP/dH derived by hand, with the
// materials and trial states they are taken at.
#pragma once

#include <Eigen/SVD>
#include <cmath>
#include <functional>

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Core/Math/Types.h"

namespace anode {

inline const Mat3 kIdentity = Mat3::Identity();
constexpr double kDt = 0.5;  // the updates see L dt and dc, not dt alone

inline Mat3 unit(int k) {
  Mat3 e = Mat3::Zero();
  e(k / 3, k % 3) = 1;
  return e;
}
inline Mat3 symmetricPart(const Mat3& m) {
  return 0.5 * (m + m.transpose());
}
inline Mat3 deviator(const Mat3& m) {
  return m - m.trace() / 3 * kIdentity;
}
inline double contract(const Mat3& a, const Mat3& b) {
  return (a.array() * b.array()).sum();
}

// F = R U by the singular values (independent of Core/Math/PolarDecomposition.h).
inline void polar(const Mat3& F, Mat3& R, Mat3& U) {
  const Eigen::JacobiSVD<Mat3> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  R = svd.matrixU() * svd.matrixV().transpose();
  U = svd.matrixV() * svd.singularValues().asDiagonal() * svd.matrixV().transpose();
}

// dR of F = R U along dF: R^T dR = W, skew, with axial vector w = (tr(U) I - U)^-1 2 axial(skew(R^T
// dF)), since skew(R^T dF) = (W U + U W) / 2 and W U + U W = [(tr(U) I - U) w]x.
inline Mat3 rotationDerivative(const Mat3& R, const Mat3& U, const Mat3& dF) {
  const Mat3 a = R.transpose() * dF;
  const Vec3 twiceAxial(a(2, 1) - a(1, 2), a(0, 2) - a(2, 0), a(1, 0) - a(0, 1));
  const Vec3 w = (U.trace() * kIdentity - U).inverse() * twiceAxial;
  Mat3 W;
  W << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return R * W;
}

// P = sigma cof(A), A = I + h, cof(A) = det(A) A^-T: dP = dsigma cof(A) + sigma dcof(A), dcof(A) =
// det(A) (tr(A^-1 dh) A^-T - A^-T dh^T A^-T). The tangent's column k is dP along dh = unit(k).
inline Mat9 piolaTangent(const Mat3& h, const Mat3& sigma,
                         const std::function<Mat3(const Mat3&)>& dSigma) {
  const Mat3 A = kIdentity + h, inverse = A.inverse(), inverseT = inverse.transpose();
  const double J = A.determinant();
  Mat9 T;
  for (int k = 0; k < 9; ++k) {
    const Mat3 dh = unit(k);
    const Mat3 dCofactor =
        J * ((inverse * dh).trace() * inverseT - inverseT * dh.transpose() * inverseT);
    const Mat3 dP = dSigma(dh) * J * inverseT + sigma * dCofactor;
    for (int r = 0; r < 9; ++r) T(r, k) = dP(r / 3, r % 3);
  }
  return T;
}

// A particle at its start of step, and its trial displacement gradient h.
struct Trial {
  Mat3 F = kIdentity, stress = Mat3::Zero(), h = Mat3::Zero();
  double plasticStrain = 0, swellingStrain = 0, dc = 0;
};

// The hardening law as stated here, apart from FlowModel: sigma_y(eps_p) and its slope.
struct Hardening {
  std::function<double(double)> flowStress, slope;
};

struct RadialReturnCase {
  const char* name = "";
  double K = 6.7e7, G = 3.1e7, eta = 0.56;  // inputs/Paper/QuasiStatic_Fig4.ups, Pa
  FlowModel flow;
  Hardening hardening;
};

inline RadialReturnCase linearHardening() {
  RadialReturnCase c;
  c.name = "linear hardening";
  c.flow.sigmaY = 1.4e6;
  c.flow.K = 1.15e6;
  c.hardening = {[](double e) { return 1.4e6 + 1.15e6 * e; }, [](double) { return 1.15e6; }};
  return c;
}

// Johnson-Cook's power law, a slope that changes along the return.
inline RadialReturnCase powerHardening() {
  RadialReturnCase c;
  c.name = "power hardening";
  c.flow.type = FlowModel::Type::JohnsonCook;
  c.flow.A = 1.4e6;
  c.flow.B = 4e6;
  c.flow.n = 0.4;
  c.hardening = {[](double e) { return 1.4e6 + 4e6 * std::pow(e, 0.4); },
                 [](double e) { return 4e6 * 0.4 * std::pow(e, -0.6); }};
  return c;
}

// The unrotated strain increment rf_elastic_plastic sees (Eqs. 26-29, 25): R_n^T sym(L dt) R_n -
// eta dc I, L dt = 2 h (2 I + h)^-1 (the midpoint rule of ParticleEquilibrium.h).
inline Mat3 strainIncrement(const RadialReturnCase& c, const Trial& t) {
  Mat3 Rn, Un;
  polar(t.F, Rn, Un);
  return Rn.transpose() * symmetricPart(2 * t.h * (2 * kIdentity + t.h).inverse()) * Rn -
         c.eta * t.dc * kIdentity;
}

// Closed-form dP/dH of rf_elastic_plastic's update (RFElasticPlastic.h) at the trial, by the chain
// h -> e (strainIncrement) -> the unrotated stress -> sigma = R sigmaBar R^T, R of (I + h) F_n ->
// P = sigma cof(I + h). The unrotated stress is the hypoelastic trial s* = dev(sigmaBar_n) + 2 G
// dev(e) returned radially: |s*| - sqrt(2/3) sigma_y(eps_p,n + sqrt(2/3) dgamma) - 2 G dgamma = 0,
// s = theta s*, theta = 1 - 2 G dgamma / |s*|, plus the mean stress tr(sigmaBar_n)/3 + K tr(e).
// Its derivative is Simo and Taylor's consistent tangent (Simo and Hughes 1998, Eq. 3.3.10):
// dsigmaBar = K tr(de) I + 2 G theta dev(de) - 2 G thetaBar (n : de) n, n = s*/|s*|, thetaBar = 1 /
// (1 + H'/(3 G)) - (1 - theta), H' = dsigma_y/deps_p at eps_p,n+1 (the linearized return: d dgamma
// = 2 G n : de / (2 G + 2/3 H')); elastic: theta = 1, thetaBar = 0. `yields` says which.
inline Mat9 radialReturnTangent(const RadialReturnCase& c, const Trial& t, bool& yields) {
  Mat3 Rn, Un, R, U;
  polar(t.F, Rn, Un);
  polar((kIdentity + t.h) * t.F, R, U);
  const Mat3 M = (2 * kIdentity + t.h).inverse();
  const Mat3 e = strainIncrement(c, t);
  const Mat3 startStress = Rn.transpose() * t.stress * Rn;
  const Mat3 trial = deviator(startStress) + 2 * c.G * deviator(e);
  const double size = trial.norm(), sqrt23 = std::sqrt(2.0 / 3.0);
  yields = std::sqrt(1.5) * size > c.hardening.flowStress(t.plasticStrain);
  double dgamma = 0, thetaBar = 0;
  if (yields) {  // bisection: g(0) > 0 > g(|s*| / 2G)
    const auto g = [&](double x) {
      return size - sqrt23 * c.hardening.flowStress(t.plasticStrain + sqrt23 * x) - 2 * c.G * x;
    };
    double low = 0, high = size / (2 * c.G);
    for (int i = 0; i < 200 && high - low > 1e-17 * high; ++i)
      (g(0.5 * (low + high)) > 0 ? low : high) = 0.5 * (low + high);
    dgamma = 0.5 * (low + high);
  }
  const double theta = 1 - 2 * c.G * dgamma / size;
  if (yields)
    thetaBar =
        1 / (1 + c.hardening.slope(t.plasticStrain + sqrt23 * dgamma) / (3 * c.G)) - (1 - theta);
  const Mat3 n = yields ? Mat3(trial / size) : Mat3::Zero();
  const Mat3 stressBar = theta * trial + (startStress.trace() / 3 + c.K * e.trace()) * kIdentity;
  const auto dSigma = [&](const Mat3& dh) {
    const Mat3 de = Rn.transpose() * symmetricPart(4 * M * dh * M) * Rn;  // d(L dt) = 4 M dh M
    const Mat3 dStressBar = c.K * de.trace() * kIdentity + 2 * c.G * theta * deviator(de) -
                            2 * c.G * thetaBar * contract(n, de) * n;
    const Mat3 dR = rotationDerivative(R, U, dh * t.F);
    return Mat3(dR * stressBar * R.transpose() + R * dStressBar * R.transpose() +
                R * stressBar * dR.transpose());
  };
  return piolaTangent(t.h, R * stressBar * R.transpose(), dSigma);
}

struct NeoHookeanCase {
  double K = 6.7e7, G = 3.1e7, eta = 0.56;
};

// Closed-form dP/dH of comp_neo_hook (CompNeoHookean.h): sigma = K/2 (Je - 1/Je) I + G Je^(-5/3)
// dev(b), Fe = exp(-theta) (I + h) F_n, theta = theta_n + eta dc, b = Fe Fe^T; along dh: dFe =
// exp(-theta) dh F_n, dJe = Je tr((I + h)^-1 dh), db = dFe Fe^T + Fe dFe^T.
inline Mat9 neoHookeanTangent(const NeoHookeanCase& c, const Trial& t) {
  const double stretch = std::exp(-(t.swellingStrain + c.eta * t.dc));
  const Mat3 A = kIdentity + t.h, Fe = stretch * A * t.F, b = Fe * Fe.transpose();
  const double Je = Fe.determinant();
  const Mat3 sigma =
      0.5 * c.K * (Je - 1 / Je) * kIdentity + c.G * std::pow(Je, -5.0 / 3) * deviator(b);
  const auto dSigma = [&](const Mat3& dh) {
    const Mat3 dFe = stretch * dh * t.F, db = dFe * Fe.transpose() + Fe * dFe.transpose();
    const double dJe = Je * (A.inverse() * dh).trace();
    return Mat3(0.5 * c.K * (1 + 1 / (Je * Je)) * dJe * kIdentity -
                5.0 / 3 * c.G * std::pow(Je, -8.0 / 3) * dJe * deviator(b) +
                c.G * std::pow(Je, -5.0 / 3) * deviator(db));
  };
  return piolaTangent(t.h, sigma, dSigma);
}

// Particles at the trials' starts, each with three nodes of its own whose gradients are the unit

}  // namespace anode
