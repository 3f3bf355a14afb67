// Pins rf_elastic_plastic: radial return against the closed-form uniaxial strain response
// (perfect plasticity and linear hardening), and objectivity under rotation.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"
#include "Core/Math/PolarDecomposition.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"
#include "tests/UniaxialStrain.h"

namespace anode {
namespace {

struct UniaxialResult {
  double sxx, syy, ep;
};

// Drives uniaxial strain to logarithmic strain e in n increments of 1e-3.
UniaxialResult uniaxialStrain(const RFElasticPlastic& model, double e, int n) {
  const UniaxialStrainEnd end = driveUniaxialStrain(model, e, n, 1e-3);
  return {end.stress(0, 0), end.stress(1, 1), end.state.ep};
}

const double K = 67e3, G = 31e3, sigmaY = 1.4e3, H = 1.15e3;  // the paper's values, MPa

TEST(RadialReturn, ElasticUniaxialStrain) {
  const RFElasticPlastic model(K, G, std::nullopt);
  const double e = 0.02;
  const UniaxialResult r = uniaxialStrain(model, e, 400);
  EXPECT_NEAR(r.sxx, (K + 4 * G / 3) * e, 1e-9 * K * e);
  EXPECT_NEAR(r.syy, (K - 2 * G / 3) * e, 1e-9 * K * e);
}

// Closed form in uniaxial strain: elastic until 2 G e = sigma_Y; then
// eps_p = (2 G e - sigma_Y) / (3 G + H), sigma_eq = sigma_Y + H eps_p,
// sigma_xx = K e + 2/3 sigma_eq, sigma_yy = K e - 1/3 sigma_eq.
void checkPlasticUniaxial(const RFElasticPlastic& model, double hardening) {
  for (double e : {0.03, 0.05, -0.04}) {
    const UniaxialResult r = uniaxialStrain(model, e, 500);
    const double ee = std::abs(e), sign = e > 0 ? 1 : -1;
    const double ep = (2 * G * ee - sigmaY) / (3 * G + hardening);
    ASSERT_GT(ep, 0) << "the test strain must exceed the yield strain";
    const double seq = sigmaY + hardening * ep;
    EXPECT_NEAR(r.ep, ep, 1e-9 * ep);
    EXPECT_NEAR(r.sxx, K * e + sign * 2.0 / 3.0 * seq, 1e-9 * K * ee);
    EXPECT_NEAR(r.syy, K * e - sign * 1.0 / 3.0 * seq, 1e-9 * K * ee);
  }
}

TEST(RadialReturn, PerfectPlasticityJohnsonCookAOnly) {
  FlowModel flow;
  flow.type = FlowModel::Type::JohnsonCook;
  flow.A = sigmaY;
  checkPlasticUniaxial(RFElasticPlastic(K, G, flow), 0.0);
}

TEST(FlowModel, JohnsonCookWithoutBOrNIsPerfectlyPlastic) {
  // sigma_y = A + B eps_p^n is constant when B = 0 or n = 0; its slope is 0 at every eps_p, also
  // where eps_p^(n - 1) overflows (a subnormal eps_p with n = 0 gave 0 x inf = NaN).
  FlowModel flow;
  flow.type = FlowModel::Type::JohnsonCook;
  flow.A = sigmaY;
  flow.B = 5;
  for (const double ep : {0.0, 1e-310, 0.3, 2.0}) {
    EXPECT_EQ(flow.flowStress(ep), sigmaY + 5) << ep;
    EXPECT_EQ(flow.hardeningModulus(ep), 0.0) << ep;
  }
  flow.B = 0;
  flow.n = 0.5;
  EXPECT_EQ(flow.flowStress(0.3), sigmaY);
  EXPECT_EQ(flow.hardeningModulus(1e-310), 0.0);
  flow.B = 5;
  EXPECT_EQ(flow.flowStress(0.25), sigmaY + 5 * 0.5);
  EXPECT_EQ(flow.hardeningModulus(0.25), 5 * 0.5 / 0.5);
}

// Reads <flow_model type="johnson_cook"> with A = 100, B = 50, n = 1, m = 0.5 and `extra` tags.
FlowModel johnsonCook(const std::string& extra) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification><flow_model type=\"johnson_cook\"><A>100</A><B>50</B><C>0</C>"
      "<n>1</n><m>0.5</m>" +
          extra + "</flow_model></Uintah_specification>",
      "flow.ups");
  return FlowModel::fromInput(spec->root().requireChild("flow_model"));
}

TEST(FlowModel, JohnsonCookTemperatureFactorAtUintahsFixed298K) {
  // Defaults T_r = 298, T_m = 1793: T* = 0, factor 1, exactly.
  EXPECT_EQ(johnsonCook("").flowStress(0.2), 100 + 50 * 0.2);
  // T_r = 294, T_m = 1794: T* = 4 / 1500, factor 1 - sqrt(T*) (m = 0.5), on A and B alike.
  const double soft = 1 - std::sqrt(4.0 / 1500.0);
  const FlowModel cooled = johnsonCook("<T_r>294</T_r><T_m>1794</T_m>");
  EXPECT_NEAR(cooled.flowStress(0.2), (100 + 50 * 0.2) * soft, 1e-12 * 110);
  EXPECT_NEAR(cooled.hardeningModulus(0.2), 50 * soft, 1e-12 * 50);
  // T_r = 300 > 298: T* = -2 / 1494 < 0, factor 1 - T*.
  EXPECT_NEAR(johnsonCook("<T_r>300</T_r><T_m>1794</T_m>").flowStress(0.0),
              100 * (1 + 2.0 / 1494.0), 1e-12 * 100);
  // A nonzero epdot_0 changes nothing (zero strain rate); 0 is Uintah's 0/0.
  EXPECT_EQ(johnsonCook("<epdot_0>1e-3</epdot_0>").flowStress(0.2), 100 + 50 * 0.2);
  EXPECT_THROW(johnsonCook("<epdot_0>0</epdot_0>"), InputError);
  // Melted at 298 K (zero yield stress in Uintah), or T_r not below T_m: errors.
  EXPECT_THROW(johnsonCook("<T_m>298</T_m>"), InputError);
  EXPECT_THROW(johnsonCook("<T_r>1800</T_r><T_m>1700</T_m>"), InputError);
}

TEST(RadialReturn, LinearHardening) {
  FlowModel flow;
  flow.type = FlowModel::Type::IsotropicHardening;
  flow.sigmaY = sigmaY;
  flow.K = H;
  checkPlasticUniaxial(RFElasticPlastic(K, G, flow), H);
}

TEST(RadialReturn, JohnsonCookWithLinearExponentEqualsLinearHardening) {
  FlowModel flow;
  flow.type = FlowModel::Type::JohnsonCook;
  flow.A = sigmaY;
  flow.B = H;
  flow.n = 1;
  checkPlasticUniaxial(RFElasticPlastic(K, G, flow), H);
}

TEST(Objectivity, RigidRotationRotatesTheStressAndKeepsItsInvariants) {
  FlowModel flow;
  flow.type = FlowModel::Type::JohnsonCook;
  flow.A = sigmaY;
  const RFElasticPlastic model(K, G, flow);
  Mat3 stress;
  stress << 300, 50, -20, 50, -100, 10, -20, 10, 80;
  Mat3 F = Mat3::Identity();
  const Vec3 axis = Vec3(1, 1, 0.3).normalized();
  const double omega = 2.0, dt = 1e-3;
  const Mat3 start = stress;
  RFElasticPlastic::State<double> state{Mat3::Identity(), 0, 0, 0};
  for (int i = 1; i <= 500; ++i) {
    const Mat3 Fnew = Eigen::AngleAxisd(omega * dt * i, axis).toRotationMatrix();
    const Mat3 W = Fnew * F.inverse();              // incremental rotation
    const Mat3 L = (W - W.transpose()) / (2 * dt);  // spin only: no rate of deformation
    stress = model.updateStress(stress, Fnew, L, 0.0, dt, state);
    F = Fnew;
  }
  const Mat3 expected = F * start * F.transpose();
  EXPECT_LT((stress - expected).norm(), 1e-10 * start.norm());
  EXPECT_NEAR(stress.trace(), start.trace(), 1e-10 * start.norm());
  EXPECT_EQ(state.ep, 0.0);
}

}  // namespace
}  // namespace anode
