// The implicit step's algorithmic tangent (Components/MPM/Implicit/ParticleEquilibrium.h): A =
// dP/dH by central differences of each model's own stress update against the closed form derived
// by hand (TangentClosedForms.h), on elastic, plastic and mixed packs of particles; the
// difference's error against its step (the residual's Taylor remainder: test_residual_taylor.cc).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <vector>

#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "tests/TangentClosedForms.h"

namespace anode {
namespace {

// Particles at the trials' starts, each with three nodes of its own whose gradients are the unit
// vectors: node 3i + a carries column a of trial i's h, so that H = sum_a u_a (x) e_a = h.
struct TrialParticles {
  ParticleSet p;
  InterpolationWeights W;
  std::vector<Vec3> u;
  std::vector<double> dc;
};

template <class Model>
TrialParticles trialParticles(const Model& model, const std::vector<Trial>& trials) {
  TrialParticles s;
  const size_t n = trials.size();
  s.p.resize(n);
  s.W.layOut(std::vector<uint8_t>(n, 3));
  s.u.resize(3 * n);
  for (size_t i = 0; i < n; ++i) {
    s.p.F[i] = trials[i].F;
    s.p.stress[i] = trials[i].stress;
    s.p.mass[i] = s.p.volume[i] = 1;
    s.W.count[i] = 3;
    for (int a = 0; a < 3; ++a) {
      s.W.node[3 * i + a] = static_cast<int32_t>(3 * i + a);
      s.W.weight[3 * i + a] = 1.0 / 3;
      s.W.gradient[3 * i + a] = Vec3::Unit(a);
      s.u[3 * i + a] = trials[i].h.col(a);
    }
    s.dc.push_back(trials[i].dc);
  }
  model.initializeState(s.p);  // rf_elastic_plastic: R of F_n
  for (size_t i = 0; i < n; ++i) {
    if constexpr (std::is_same_v<Model, RFElasticPlastic>)
      s.p.template modelArray<double>(0)[i] = trials[i].plasticStrain;
    else
      s.p.template modelArray<double>(0)[i] = trials[i].swellingStrain;
  }
  return s;
}

// The code's tangents of the trials (evaluateTrialStress, as Newton's assembly takes them).
template <class Model>
std::vector<Mat9> codeTangents(const Model& model, const std::vector<Trial>& trials) {
  TrialParticles s = trialParticles(model, trials);
  std::vector<Mat3> P;
  std::vector<Mat9> A;
  evaluateTrialStress(s.p, s.W, model, s.u, s.dc.data(), kDt, P, &A);
  return A;
}

// max |A - T| over max |T|.
double relativeError(const Mat9& A, const Mat9& T) {
  return (A - T).cwiseAbs().maxCoeff() / T.cwiseAbs().maxCoeff();
}

std::mt19937 randomState(5489u);
Mat3 randomMatrix(double size) {
  std::uniform_real_distribution<double> u(-size, size);
  Mat3 m;
  for (int k = 0; k < 9; ++k) m(k) = u(randomState);
  return m;
}
// A start F_n: a rotation of about 0.5 rad times a stretch of a few percent, det > 0.
Mat3 randomStart() {
  const Eigen::AngleAxisd rotation(0.5, Vec3(1, 2, 3).normalized() + 0.2 * Vec3::Random());
  return rotation.toRotationMatrix() * (kIdentity + symmetricPart(randomMatrix(0.05)));
}

// A trial from a random start strained by a random h of about `strain` (dc 0.01, plastic strain
// 0.02 at the start); Rn is the start's rotation.
Trial strainedTrial(double strain, Mat3& Rn) {
  Trial t;
  t.F = randomStart();
  t.h = randomMatrix(strain);
  t.dc = 0.01;
  t.plasticStrain = 0.02;
  Mat3 Un;
  polar(t.F, Rn, Un);
  return t;
}

// An elastic trial: a start well inside the yield surface (30% of sqrt(2/3) sigma_y plus a
// pressure), strained by h of about 1e-3: |s*| stays below 45% of the surface.
Trial elasticTrial(const RadialReturnCase& c) {
  Mat3 Rn;
  Trial t = strainedTrial(1e-3, Rn);
  const Mat3 direction = deviator(symmetricPart(randomMatrix(1.0)));
  const Mat3 stressBar = 0.3 * std::sqrt(2.0 / 3.0) * c.hardening.flowStress(t.plasticStrain) *
                             direction.normalized() -
                         2e6 * kIdentity;
  t.stress = Rn * stressBar * Rn.transpose();
  return t;
}

// A plastic trial: a start on the yield surface, its deviator along the trial's deviatoric strain
// increment (h of about 5e-3): |s*| exceeds sqrt(2/3) sigma_y by 2 G |dev e|, about 1e5 Pa, 1e3
// times what a difference step of 1e-6 moves it (2 G 1e-6 = 62 Pa), so no difference straddles
// the yield surface.
Trial plasticTrial(const RadialReturnCase& c) {
  Mat3 Rn;
  Trial t = strainedTrial(5e-3, Rn);
  const Mat3 along = deviator(strainIncrement(c, t)).normalized();
  const Mat3 stressBar =
      std::sqrt(2.0 / 3.0) * c.hardening.flowStress(t.plasticStrain) * along - 2e6 * kIdentity;
  t.stress = Rn * stressBar * Rn.transpose();
  return t;
}

// The central difference's error at kTangentStep, relative to the largest entry of the tangent:
// truncation h^2/6 |P'''| is 1e-13 where elastic (the midpoint rule's and cof's curvature is O(1)
// in h), but the radial return curves on the scale of the yield strain (theta = 1 - 2 G dgamma /
// |s*|, |s*| / 2G about 0.02 here), so in a plastic state it is about (h / 0.02)^2 / 6, 4e-10;
// round-off, eps |P| / h, is 1e-11. Measured over the packs below: at most 2.2e-10
// (plastic; 1.4e-11 elastic), falling as h^2 (DifferenceErrorAgainstStep). The tolerance is 5 times
// that; a wrong term of the tangent (the rotation's, cof's, thetaBar's) is of the stress over the
// moduli, 1e-2 and more.
constexpr double kTangentTolerance = 1e-9;

TEST(AlgorithmicTangent, RadialReturnMatchesSimoTaylorOnElasticPlasticAndMixedPacks) {
  constexpr int lanes = static_cast<int>(Pack::size());
  for (const RadialReturnCase& c : {linearHardening(), powerHardening()}) {
    const RFElasticPlastic model(c.K, c.G, c.flow, c.eta);
    // Two blocks and a part: all elastic, all plastic, then lanes alternating in the mixed set.
    for (const char* set : {"elastic", "plastic", "mixed"}) {
      SCOPED_TRACE(set);
      std::vector<Trial> trials;
      std::vector<bool> plastic;
      double worst = 0;
      for (int i = 0; i < 2 * lanes + 1; ++i) {
        plastic.push_back(set[0] == 'p' || (set[0] == 'm' && i % 2 == 1));
        trials.push_back(plastic.back() ? plasticTrial(c) : elasticTrial(c));
      }
      const std::vector<Mat9> A = codeTangents(model, trials);
      for (size_t i = 0; i < trials.size(); ++i) {
        bool yields = false;
        const Mat9 T = radialReturnTangent(c, trials[i], yields);
        ASSERT_EQ(yields, plastic[i]) << "particle " << i;
        worst = std::max(worst, relativeError(A[i], T));
        EXPECT_LE(relativeError(A[i], T), kTangentTolerance) << "particle " << i;
      }
      std::printf("%s, %s: largest relative error %.2e\n", c.name, set, worst);
    }
  }
}

TEST(AlgorithmicTangent, NeoHookeanMatchesItsClosedForm) {
  const NeoHookeanCase c;
  const CompNeoHookean model(c.K, c.G, c.eta);
  std::vector<Trial> trials;
  for (int i = 0; i < static_cast<int>(Pack::size()) + 1; ++i) {
    Trial t;
    t.F = randomStart();
    t.h = randomMatrix(1e-2);
    t.swellingStrain = 0.03;
    t.dc = 0.02;
    trials.push_back(t);
  }
  const std::vector<Mat9> A = codeTangents(model, trials);
  for (size_t i = 0; i < trials.size(); ++i)
    EXPECT_LE(relativeError(A[i], neoHookeanTangent(c, trials[i])), kTangentTolerance)
        << "particle " << i;
}

// The central difference of one particle's P with step h (ParticleEquilibrium.h's, any h).
template <class Model>
Mat9 centralDifference(const Model& model, const Trial& trial, double h) {
  TrialParticles s = trialParticles(model, std::vector<Trial>{trial});
  const auto arrays = model.stateArrays(s.p);
  const TrialBlock<Model> t(s.p, arrays, s.W, s.u, s.dc.data(), 0);
  Mat9 A;
  for (int k = 0; k < 9; ++k) {
    Mat3Pack plus = t.H, minus = t.H;
    plus(k / 3, k % 3) += Pack(h);
    minus(k / 3, k % 3) -= Pack(h);
    const Mat3 dP =
        lane(Mat3Pack((t.piola(model, plus, kDt) - t.piola(model, minus, kDt)) / Pack(2 * h)), 0);
    for (int r = 0; r < 9; ++r) A(r, k) = dP(r / 3, r % 3);
  }
  return A;
}

// The difference's error (max |A_h - T| / max |T|) against its step h, measured:
//   h        rf elastic  rf plastic  neo-Hookean
//   1e-3     2.5e-7      1.9e-4      8.6e-7
//   1e-5     2.5e-11     1.9e-8      8.3e-11
//   3e-6     3.6e-12     1.7e-9      4.4e-11
//   1e-6     7.9e-12     1.9e-10     1.1e-10   (kTangentStep)
//   3e-7     2.4e-11     5.8e-11     4.5e-10
//   1e-7     1.1e-10     1.2e-10     1.2e-9
//   1e-8     1.0e-9      8.6e-10     8.3e-9
//   1e-10    5.7e-8      8.7e-8      9.6e-7
//   scaled   3.4e-7      6.1e-8      3.2e-7    (sqrt(eps) max(|H|, 1e-3))
// Truncation falls as h^2 down to about 3e-6 (elastic) and 3e-7 (plastic: the return curves on the
// scale of the yield strain), then round-off grows as 1/h. A central difference's best step is
// (3 eps |P| / |P'''|)^(1/3), a cube root of eps; the square root belongs to a one-sided
// difference. The step scaled to the strain, sqrt(eps) max(|H|, 1e-3), is 1.5e-11 to 1.5e-9 for
// the strains of a step, deep in the round-off branch: 10^2 to 10^4 times worse than 1e-6. The
// fixed step is within a factor 3.3 of the best of the table in every column, and the error does
// not scale with |H| (round-off scales with the stress, truncation with the yield strain), so the
// fixed step stays.
TEST(AlgorithmicTangent, DifferenceErrorAgainstStep) {
  const RadialReturnCase c = linearHardening();
  const RFElasticPlastic radialReturn(c.K, c.G, c.flow, c.eta);
  const NeoHookeanCase n;
  const CompNeoHookean neoHookean(n.K, n.G, n.eta);
  Trial stretched;
  stretched.F = randomStart();
  stretched.h = randomMatrix(1e-2);
  stretched.dc = 0.02;
  struct Row {
    const char* name;
    Trial trial;
    std::function<Mat9(double)> difference;
    Mat9 exact;
  };
  const Trial elastic = elasticTrial(c), plastic = plasticTrial(c);
  bool yields = false;
  std::vector<Row> rows = {
      {"rf elastic", elastic, [&](double h) { return centralDifference(radialReturn, elastic, h); },
       radialReturnTangent(c, elastic, yields)},
      {"rf plastic", plastic, [&](double h) { return centralDifference(radialReturn, plastic, h); },
       radialReturnTangent(c, plastic, yields)},
      {"neo-Hookean", stretched,
       [&](double h) { return centralDifference(neoHookean, stretched, h); },
       neoHookeanTangent(n, stretched)}};
  const std::vector<double> steps = {1e-3, 1e-4, 1e-5, 3e-6, 1e-6, 3e-7, 1e-7, 1e-8, 1e-9, 1e-10};
  std::printf("%-12s", "step");
  for (const Row& r : rows) std::printf(" %12s", r.name);
  std::printf("\n");
  std::vector<std::vector<double>> error(rows.size());
  for (const double h : steps) {
    std::printf("%-12.0e", h);
    for (size_t r = 0; r < rows.size(); ++r) {
      error[r].push_back(relativeError(rows[r].difference(h), rows[r].exact));
      std::printf(" %12.2e", error[r].back());
    }
    std::printf("\n");
  }
  // The step scaled to the strain, sqrt(eps) max(|H|, 1e-3).
  std::vector<double> scaled;
  std::printf("%-12s", "scaled");
  for (const Row& r : rows) {
    const double h =
        std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(r.trial.h.norm(), 1e-3);
    scaled.push_back(relativeError(r.difference(h), r.exact));
    std::printf(" %12.2e", scaled.back());
  }
  std::printf("\n");
  const size_t used = std::find(steps.begin(), steps.end(), kTangentStep) - steps.begin();
  ASSERT_LT(used, steps.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    SCOPED_TRACE(rows[r].name);
    EXPECT_LE(error[r][used], kTangentTolerance);
    // Both branches: truncation at the largest step, round-off at the smallest, each at least 100
    // times the error at kTangentStep, which is within 10 of the best step's.
    EXPECT_GE(error[r].front(), 100 * error[r][used]);
    EXPECT_GE(error[r].back(), 100 * error[r][used]);
    EXPECT_LE(error[r][used], 10 * *std::min_element(error[r].begin(), error[r].end()));
    // The scaled step is worse than the fixed one (the study's conclusion above).
    EXPECT_GE(scaled[r], 100 * error[r][used]);
  }
}

}  // namespace
}  // namespace anode
