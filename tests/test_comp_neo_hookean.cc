// Pins comp_neo_hook (CompNeoHookean.h) at a material point: Uintah's UCNH stress in uniaxial
// strain by hand, linear elasticity in the small-strain limit, objectivity, free swelling
// stress-free at finite stretch, the swelling strain it carries, one particle and a pack alike;
// and its input: UCNH's options off accepted, on refused at their line.
#include <gtest/gtest.h>

#include <cmath>

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"

namespace anode {
namespace {

const double K = 60e6, G = 6e6, eta = 0.56;  // the moduli of Uintah's const_test_cnh_implicit

Mat3 stressOf(const CompNeoHookean& model, const Mat3& F, double dc = 0) {
  CompNeoHookean::State<double> state{0.0};
  return model.updateStress<double>(Mat3::Zero(), F, Mat3::Zero(), dc, 1.0, state);
}

TEST(CompNeoHookean, UniaxialStrainByHand) {
  // F = diag(l, 1, 1): J = l, dev(b)_xx = 2/3 (l^2 - 1), dev(b)_yy = -1/3 (l^2 - 1).
  const CompNeoHookean model(K, G);
  for (const double l : {0.7, 1.0, 1.3, 2.0}) {
    const Mat3 s = stressOf(model, Vec3(l, 1, 1).asDiagonal());
    const double p = 0.5 * K * (l - 1 / l), shear = G * std::pow(l, -5.0 / 3.0) * (l * l - 1);
    EXPECT_NEAR(s(0, 0), p + 2.0 / 3.0 * shear, 1e-12 * K) << l;
    EXPECT_NEAR(s(1, 1), p - 1.0 / 3.0 * shear, 1e-12 * K) << l;
    EXPECT_NEAR(s(2, 2), s(1, 1), 1e-12 * K) << l;
    EXPECT_EQ(s(0, 1), 0.0);
  }
}

TEST(CompNeoHookean, SmallStrainIsLinearElasticity) {
  const CompNeoHookean model(K, G);
  const double e = 1e-6;
  Mat3 F = Mat3::Identity();
  F(0, 0) += e;
  F(0, 1) = e;  // a shear besides the stretch
  const Mat3 s = stressOf(model, F);
  EXPECT_NEAR(s(0, 0), (K + 4 * G / 3) * e, 1e-5 * K * e);
  EXPECT_NEAR(s(1, 1), (K - 2 * G / 3) * e, 1e-5 * K * e);
  EXPECT_NEAR(s(0, 1), G * e, 1e-5 * G * e);
}

TEST(CompNeoHookean, RotatingTheBodyRotatesTheStress) {
  const CompNeoHookean model(K, G);
  Mat3 F;
  F << 1.2, 0.3, 0, -0.1, 0.9, 0.2, 0.05, 0, 1.1;
  const Mat3 Q = Eigen::AngleAxisd(0.8, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  const Mat3 s = stressOf(model, F);
  EXPECT_LT((stressOf(model, Q * F) - Q * s * Q.transpose()).norm(), 1e-12 * s.norm());
}

TEST(CompNeoHookean, FreeSwellingIsStressFreeAtFiniteStretch) {
  // dc = 0.9 with eta = 0.56: each axis stretched by exp(0.504) ~ 1.66, J ~ 4.5.
  const CompNeoHookean model(K, G, eta);
  const double dc = 0.9;
  CompNeoHookean::State<double> state{0.0};
  const Mat3 F = std::exp(eta * dc) * Mat3::Identity();
  const Mat3 s = model.updateStress<double>(Mat3::Zero(), F, Mat3::Zero(), dc, 1.0, state);
  EXPECT_NEAR(state.swellingStrain, eta * dc, 1e-15);
  EXPECT_LT(s.norm(), 1e-9 * K);
  // Held at F = I instead, the same dc gives the confined pressure -K sinh(3 eta dc).
  const Mat3 confined = stressOf(model, Mat3::Identity(), dc);
  EXPECT_NEAR(confined(0, 0), -K * std::sinh(3 * eta * dc), 1e-12 * K);
  EXPECT_NEAR(confined(0, 0), confined(2, 2), 1e-12 * K);
}

TEST(CompNeoHookean, APackGivesEachParticleItsOwnStress) {
  const CompNeoHookean model(K, G, eta);
  CompNeoHookean::State<Pack> packState{Pack(0.0)};
  Mat3Pack F;
  Pack dc;
  std::vector<Mat3> Fs;
  for (size_t l = 0; l < Pack::size(); ++l) {
    Mat3 f = Mat3::Identity();
    f(0, 0) = 1 + 0.1 * l;
    f(1, 2) = 0.05 * l;
    Fs.push_back(f);
    setLane(F, static_cast<int>(l), f);
    dc[l] = 0.01 * l;
  }
  const Mat3Pack s =
      model.updateStress<Pack>(Mat3Pack::Zero(), F, Mat3Pack::Zero(), dc, 1.0, packState);
  for (size_t l = 0; l < Pack::size(); ++l) {
    CompNeoHookean::State<double> one{0.0};
    const Mat3 expected =
        model.updateStress<double>(Mat3::Zero(), Fs[l], Mat3::Zero(), dc[l], 1.0, one);
    EXPECT_LT((lane(s, static_cast<int>(l)) - expected).norm(), 1e-12 * K) << l;
    EXPECT_EQ(packState.swellingStrain[l], one.swellingStrain);
  }
}

std::unique_ptr<ConstitutiveModel> readModel(const std::string& tags, bool diffusion) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification><constitutive_model type=\"comp_neo_hook\">\n<bulk_modulus>60e6"
      "</bulk_modulus><shear_modulus>6e6</shear_modulus>\n" +
          tags + "</constitutive_model></Uintah_specification>",
      "cnh.ups");
  return createConstitutiveModel(spec->root().requireChild("constitutive_model"), diffusion);
}

TEST(CompNeoHookean, ReadsUintahsTagsAndRefusesWhatItLacks) {
  const auto model = readModel("<useModifiedEOS>false</useModifiedEOS>", false);
  EXPECT_FALSE(model->swells());
  EXPECT_DOUBLE_EQ(model->dilatationalModulus(), K + 4 * G / 3);
  EXPECT_TRUE(readModel("<volume_expansion_coeff>0.56</volume_expansion_coeff>", true)->swells());
  for (const char* on : {"useModifiedEOS", "usePlasticity", "useDamage"}) {
    try {
      readModel(std::string("<") + on + ">true</" + on + ">", false);
      ADD_FAILURE() << on << " on was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cnh.ups:3"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("not supported"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(readModel("", true), InputError);  // swelling needs volume_expansion_coeff
}

}  // namespace
}  // namespace anode
