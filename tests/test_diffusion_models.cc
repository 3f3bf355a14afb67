// Unit tests of the diffusion subcomponent against hand-computed values: the flux restriction
// (paper Eq. 17), the diffusivity laws jg / non_linear1 (Eq. 23, with and without pressure and
// diff_curve) / cubic (Eq. 24) / constant_rate, the factory's input errors, and the flux BC's
// surface-particle selection (ScalarFluxBC::flaggedArea, onSurface; UINTAH_UPS.md §3.1).
// Models are built through createDiffusionModel() from small XML texts.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/PhysicalBCs.h"
#include "Components/MPM/ReactiveFlow/FluxRestriction.h"
#include "Components/MPM/ReactiveFlow/ScalarDiffusionModel.h"
#include "Components/MPM/ReactiveFlow/ScalarFluxBC.h"
#include "Core/Geometry/GeometryPiece.h"
#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"

namespace anode {
namespace {

// ---------------------------------------------------------------------------------------------
// Flux restriction R(c) = max(0, 1 + ln(1 - c)/4), Eq. 17

TEST(FluxRestriction, HandComputedValues) {
  EXPECT_EQ(fluxRestriction(0.0), 1.0);
  // 1 + ln(0.5)/4 = 0.826713..., 1 + ln(0.1)/4 = 0.424353...
  EXPECT_NEAR(fluxRestriction(0.5), 0.8267, 5e-5);
  EXPECT_NEAR(fluxRestriction(0.9), 0.4244, 5e-5);
  EXPECT_NEAR(fluxRestriction(0.5), 1.0 - 0.25 * std::log(2.0), 1e-15);
  EXPECT_NEAR(fluxRestriction(0.9), 1.0 - 0.25 * std::log(10.0), 1e-15);
  // Small c: R = 1 - c/4 - c^2/8 - ...
  EXPECT_NEAR(fluxRestriction(1e-6), 1.0 - 0.25e-6 - 0.125e-12, 1e-15);
  EXPECT_NEAR(fluxRestriction(1e-3), 1.0 - 2.5e-4, 2e-7);
}

TEST(FluxRestriction, ZeroFromOneMinusExpMinusFourOn) {
  // R reaches 0 at c* = 1 - e^-4 = 0.98168436...; 0.98168 itself lies just below c*.
  const double cStar = 1.0 - std::exp(-4.0);
  EXPECT_NEAR(cStar, 0.98168436111, 1e-11);
  EXPECT_NEAR(fluxRestriction(0.98168), 0.25 * std::log(0.01832 / std::exp(-4.0)),
              1e-12);  // 5.95e-5
  EXPECT_GT(fluxRestriction(0.98168), 0.0);
  for (double c : {0.98169, 0.99, 0.999, 0.999999, 1.0 - 1e-15, 1.0, 1.5})
    EXPECT_EQ(fluxRestriction(c), 0.0) << "c = " << c;
  // The double nearest to 1 - e^-4 has 1 - c = e^-4 (1 + 2.2e-15): R is the round-off of that
  // representation (5.6e-16), never negative.
  EXPECT_GE(fluxRestriction(cStar), 0.0);
  EXPECT_LT(fluxRestriction(cStar), 1e-15);
  EXPECT_EQ(fluxRestriction(std::nextafter(cStar, 1.0)), 0.0);
  // Monotone decreasing on [0, c*].
  double previous = 2;
  for (int k = 0; k <= 1000; ++k) {
    const double c = cStar * k / 1000.0;
    const double r = fluxRestriction(c);
    EXPECT_LE(r, previous);
    previous = r;
  }
}

TEST(FluxRestriction, SlopeConstantIsEToTheFourOverFour) {
  EXPECT_NEAR(kRestrictionSlope, std::exp(4.0) / 4.0, 1e-14 * kRestrictionSlope);
  // It is |R'(c*)| = 1/(4 (1 - c*)): a central difference just below c*.
  const double cStar = 1.0 - std::exp(-4.0), h = 1e-7;
  const double slope = (fluxRestriction(cStar - 2 * h) - fluxRestriction(cStar - h)) / h;
  EXPECT_NEAR(slope, kRestrictionSlope, 1e-4 * kRestrictionSlope);
  // The tangent at c* bounds the concave R from above on [0, c*]: R(c) <= slope (c* - c).
  for (int k = 0; k < 100; ++k) {
    const double c = cStar * k / 100.0;
    EXPECT_LE(fluxRestriction(c), kRestrictionSlope * (cStar - c) + 1e-15);
  }
}

TEST(FluxRestriction, StepToTheRootFollowsTheConcentration) {
  EXPECT_NEAR(kRestrictionRoot, 1 - std::exp(-4.0), 1e-16);
  EXPECT_NEAR(fluxRestriction(kRestrictionRoot), 0.0, 1e-15);
  EXPECT_NEAR(fluxStepToRoot(0.0), kRestrictionRoot, 1e-15);  // R(0) = 1
  double previous = HUGE_VAL;
  for (int k = 0; k <= 1000; ++k) {
    const double c = kRestrictionRoot * k / 1000.0;
    const double g = fluxStepToRoot(c);
    // Falls as c rises, never below the bound at the root, never beyond 1/|R'(c)| (monotone).
    EXPECT_LE(g, previous);
    EXPECT_GE(g, 1 / kRestrictionSlope);
    EXPECT_LE(g, 4 * (1 - c) * (1 + 1e-12));
    previous = g;
    // One explicit step of dc/dt = k R(c) with dt = g(c)/k lands on the root, not past it.
    if (k < 1000) {
      EXPECT_NEAR(c + g * fluxRestriction(c), kRestrictionRoot, 1e-15);
    }
  }
  // Near the root the quotient holds its limit; past it nothing flows in.
  EXPECT_NEAR(fluxStepToRoot(kRestrictionRoot - 1e-13), 1 / kRestrictionSlope, 1e-6);
  EXPECT_EQ(fluxStepToRoot(0.999), 1 / kRestrictionSlope);
}

// ---------------------------------------------------------------------------------------------
// Diffusion models from XML text

// Wraps `model` (a <diffusion_model> element starting on line 2) in a document and builds it.
struct ModelFromText {
  std::unique_ptr<ProblemSpec> spec;
  std::unique_ptr<ScalarDiffusionModel> model;
  explicit ModelFromText(const std::string& model, double maxTime = 1.0,
                         double swellingCoefficient = 0, bool implicit = false) {
    spec = ProblemSpec::fromText("<Uintah_specification>\n" + model + "\n</Uintah_specification>\n",
                                 "diffusion.ups");
    this->model = createDiffusionModel(spec->root().requireChild("diffusion_model"),
                                       {maxTime, swellingCoefficient, 3.0, 2.0, implicit});
  }
};

ParticleSet particles(const std::vector<double>& c, const Mat3& stress = Mat3::Zero()) {
  ParticleSet p;
  p.resize(c.size());
  declareDiffusionArrays(p);
  const DiffusionParticles d(p);
  for (size_t i = 0; i < c.size(); ++i) {
    d.concentration[i] = c[i];
    p.stress[i] = stress;
    d.diffusivity[i] = -1.0;  // overwritten by the model
  }
  return p;
}

const std::vector<double> kConcentrations = {0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0};

TEST(DiffusionModel, JgGivesD0Everywhere) {
  ModelFromText m(
      "<diffusion_model type=\"jg\"><diffusivity>2.5e-3</diffusivity>"
      "<max_concentration>1.0</max_concentration></diffusion_model>");
  ASSERT_EQ(m.model->type, "jg");
  EXPECT_TRUE(m.model->diffuses());
  EXPECT_EQ(m.model->constantRate(), 0.0);
  ParticleSet p = particles(kConcentrations, -3e6 * Mat3::Identity());
  EXPECT_EQ(m.model->computeDiffusivity(p, 0.0), 2.5e-3);
  for (double d : diffusionParticles(p).diffusivity) EXPECT_EQ(d, 2.5e-3);
}

TEST(DiffusionModel, NonLinear1WithoutPressureIsD0ExpAlphaC) {
  // Stress must not matter when use_pressure is false (and tuning3..5 are then inert).
  ModelFromText m(
      "<diffusion_model type=\"non_linear1\"><diffusivity>1e-5</diffusivity>"
      "<max_concentration>1.0</max_concentration><use_pressure>false</use_pressure>"
      "<tuning1>6.0</tuning1><tuning2>0.5</tuning2><tuning3>0</tuning3><tuning4>3</tuning4>"
      "<tuning5>1e-6</tuning5></diffusion_model>");
  ParticleSet p = particles(kConcentrations, -2e6 * Mat3::Identity());
  const double dmax = m.model->computeDiffusivity(p, 0.0);
  for (size_t i = 0; i < p.count(); ++i)
    EXPECT_NEAR(diffusionParticles(p).diffusivity[i], 1e-5 * std::exp(6.0 * kConcentrations[i]),
                1e-14 * diffusionParticles(p).diffusivity[i]);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[3], 1e-5 * 20.085536923187668, 1e-18);  // e^3
  EXPECT_NEAR(dmax, 1e-5 * std::exp(6.0), 1e-14 * dmax);                                // at c = 1
}

std::string pressureModel(double floor = 0.0, double pmax = 3.0) {
  return "<diffusion_model type=\"non_linear1\"><diffusivity>1e-5</diffusivity>"
         "<max_concentration>1.0</max_concentration><use_pressure>true</use_pressure>"
         "<tuning1>6.0</tuning1><tuning2>0.5</tuning2><tuning3>" +
         std::to_string(floor) + "</tuning3><tuning4>" + std::to_string(pmax) +
         "</tuning4><tuning5>1e-6</tuning5></diffusion_model>";
}

TEST(DiffusionModel, NonLinear1WithPressure) {
  // sigma = diag(-2e6): p = -tr(sigma)/3 = 2e6, scaled by tuning5 = 1e-6 -> p' = 2 (inside
  // [tuning3, tuning4] = [0, 3]), D = D0 exp(alpha c - 2 beta).
  ModelFromText m(pressureModel());
  ParticleSet p = particles(kConcentrations, -2e6 * Mat3::Identity());
  m.model->computeDiffusivity(p, 0.0);
  for (size_t i = 0; i < p.count(); ++i)
    EXPECT_NEAR(diffusionParticles(p).diffusivity[i],
                1e-5 * std::exp(6.0 * kConcentrations[i] - 2 * 0.5),
                1e-14 * diffusionParticles(p).diffusivity[i]);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], 1e-5 * 0.36787944117144233, 1e-19);  // e^-1
  // Only the trace counts: a deviatoric part changes nothing.
  Mat3 s = -2e6 * Mat3::Identity();
  s(0, 1) = s(1, 0) = 5e6;
  s(0, 0) += 1e6;
  s(1, 1) -= 1e6;
  ParticleSet q = particles({0.5}, s);
  m.model->computeDiffusivity(q, 0.0);
  EXPECT_NEAR(diffusionParticles(q).diffusivity[0], 1e-5 * std::exp(3.0 - 1.0),
              1e-14 * diffusionParticles(q).diffusivity[0]);
}

TEST(DiffusionModel, NonLinear1TensionGoesToTheFloor) {
  // Tension: p < 0 -> p' = tuning3. Floor 0 gives the paper's p <= 0 branch D0 e^{alpha c}.
  ModelFromText m(pressureModel(0.0, 3.0));
  ParticleSet p = particles(kConcentrations, 4e6 * Mat3::Identity());
  m.model->computeDiffusivity(p, 0.0);
  for (size_t i = 0; i < p.count(); ++i)
    EXPECT_NEAR(diffusionParticles(p).diffusivity[i], 1e-5 * std::exp(6.0 * kConcentrations[i]),
                1e-14 * diffusionParticles(p).diffusivity[i]);
  // A negative floor: p' = max(-4, -0.5) = -0.5 -> D = D0 exp(alpha c + 0.25).
  ModelFromText n(pressureModel(-0.5, 3.0));
  ParticleSet q = particles({0.2}, 4e6 * Mat3::Identity());
  n.model->computeDiffusivity(q, 0.0);
  EXPECT_NEAR(diffusionParticles(q).diffusivity[0], 1e-5 * std::exp(1.2 + 0.25),
              1e-14 * diffusionParticles(q).diffusivity[0]);
  // Inside the range with a negative floor: p' = -0.3 is kept.
  ParticleSet r = particles({0.2}, 0.3e6 * Mat3::Identity());
  n.model->computeDiffusivity(r, 0.0);
  EXPECT_NEAR(diffusionParticles(r).diffusivity[0], 1e-5 * std::exp(1.2 + 0.15),
              1e-14 * diffusionParticles(r).diffusivity[0]);
}

TEST(DiffusionModel, NonLinear1CompressionIsCappedAtTuning4) {
  // p' = 1e-6 * 7e6 = 7 > tuning4 = 3 -> D = D0 exp(alpha c - 3 beta), as at p' = 3 exactly.
  ModelFromText m(pressureModel(0.0, 3.0));
  ParticleSet p = particles(kConcentrations, -7e6 * Mat3::Identity());
  m.model->computeDiffusivity(p, 0.0);
  ParticleSet at = particles(kConcentrations, -3e6 * Mat3::Identity());
  m.model->computeDiffusivity(at, 0.0);
  for (size_t i = 0; i < p.count(); ++i) {
    EXPECT_NEAR(diffusionParticles(p).diffusivity[i],
                1e-5 * std::exp(6.0 * kConcentrations[i] - 1.5),
                1e-14 * diffusionParticles(p).diffusivity[i]);
    EXPECT_EQ(diffusionParticles(p).diffusivity[i], diffusionParticles(at).diffusivity[i]);
  }
}

TEST(DiffusionModel, FreeFunctionsMatchEquations23And24) {
  EXPECT_NEAR(nonLinear1Diffusivity(1e-17, 6.0, 0.5, 0.5, 3.0), 1e-17 * std::exp(1.5), 1e-31);
  EXPECT_NEAR(cubicDiffusivity(1e-17, 1e-15, 0.5), 1e-17 * 0.125 + 1e-15 * 0.125, 1e-31);
}

TEST(DiffusionModel, CubicIsD0OneMinusCCubedPlusDmaxCCubed) {
  ModelFromText m(
      "<diffusion_model type=\"cubic\"><diffusivity>1e-17</diffusivity>"
      "<max_concentration>1.0</max_concentration><max_diffusivity>1e-15</max_diffusivity>"
      "</diffusion_model>");
  ParticleSet p = particles({0.0, 0.5, 1.0});
  const double dmax = m.model->computeDiffusivity(p, 0.0);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], 1e-17, 1e-31);                // D0
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], (1e-17 + 1e-15) / 8, 1e-31);  // 1.2625e-16
  EXPECT_NEAR(diffusionParticles(p).diffusivity[2], 1e-15, 1e-29);                // Dmax
  EXPECT_NEAR(dmax, 1e-15, 1e-29);
  EXPECT_TRUE(m.model->diffuses());
  // D0 = 0 still diffuses through Dmax.
  ModelFromText z(
      "<diffusion_model type=\"cubic\"><diffusivity>0</diffusivity>"
      "<max_concentration>1.0</max_concentration><max_diffusivity>1e-15</max_diffusivity>"
      "</diffusion_model>");
  EXPECT_TRUE(z.model->diffuses());
}

std::string curveModel(double lastTime) {
  // in [0, 1], out (1, 2], in (2, last]
  return "<diffusion_model type=\"non_linear1\"><diffusivity>1e-2</diffusivity>"
         "<max_concentration>1.0</max_concentration><use_pressure>false</use_pressure>"
         "<tuning1>2.0</tuning1><tuning2>0</tuning2>\n"
         "<diff_curve>\n"
         "<time_point><time>0</time><flux_direction>in</flux_direction></time_point>\n"
         "<time_point><time>1</time><flux_direction>out</flux_direction></time_point>\n"
         "<time_point><time>2</time><flux_direction>in</flux_direction></time_point>\n"
         "<time_point><time>" +
         std::to_string(lastTime) +
         "</time><flux_direction>transition</flux_direction></time_point>\n"
         "</diff_curve></diffusion_model>";
}

double d(double c) {
  return 1e-2 * std::exp(2.0 * c);
}

TEST(DiffusionModel, DiffCurveFreezesDDuringOut) {
  ModelFromText m(curveModel(10.0), 5.0);
  ParticleSet p = particles({0.1, 0.3});
  m.model->computeDiffusivity(p, 0.0);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.1), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], d(0.3), 1e-16);
  // "in": recomputed from the new concentrations (t = 1 still belongs to the first interval).
  diffusionParticles(p).concentration = {0.2, 0.4};
  m.model->computeDiffusivity(p, 1.0);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.2), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], d(0.4), 1e-16);
  // "out": each particle keeps its previous D whatever its concentration; the maximum returned
  // is that of the frozen values.
  diffusionParticles(p).concentration = {0.9, 0.0};
  EXPECT_NEAR(m.model->computeDiffusivity(p, 1.5), d(0.4), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.2), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], d(0.4), 1e-16);
  diffusionParticles(p).concentration = {0.95, 0.05};
  m.model->computeDiffusivity(p, 2.0);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.2), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], d(0.4), 1e-16);
  // "in" again: recomputed.
  m.model->computeDiffusivity(p, 2.5);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.95), 1e-16);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[1], d(0.05), 1e-16);
  // "transition" (the last interval is never entered before maxTime; stays "in").
  diffusionParticles(p).concentration = {0.5, 0.5};
  m.model->computeDiffusivity(p, 4.9);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.5), 1e-16);
}

TEST(DiffusionModel, DiffCurveAdvancesAtMostOneIntervalPerCall) {
  ModelFromText m(curveModel(10.0), 5.0);
  ParticleSet p = particles({0.1});
  m.model->computeDiffusivity(p, 0.0);
  // Jumping from t = 0 to t = 2.5 (in the third interval) advances only to "out": frozen.
  diffusionParticles(p).concentration = {0.6};
  m.model->computeDiffusivity(p, 2.5);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.1), 1e-16);
  // The next call advances to the third interval ("in"): recomputed.
  m.model->computeDiffusivity(p, 2.5);
  EXPECT_NEAR(diffusionParticles(p).diffusivity[0], d(0.6), 1e-16);
}

TEST(DiffusionModel, ConstantRateReportsItsRateAndDoesNotDiffuse) {
  ModelFromText m(
      "<diffusion_model type=\"constant_rate\"><diffusivity>1e-3</diffusivity>"
      "<max_concentration>1.0</max_concentration><constant_rate>2.5e-4</constant_rate>"
      "</diffusion_model>");
  EXPECT_EQ(m.model->type, "constant_rate");
  EXPECT_EQ(m.model->constantRate(), 2.5e-4);
  EXPECT_FALSE(m.model->diffuses());
  ParticleSet p = particles({0.1, 0.7});
  EXPECT_EQ(m.model->computeDiffusivity(p, 0.0), 0.0);
  for (double x : diffusionParticles(p).diffusivity) EXPECT_EQ(x, 0.0);
  // jg with D0 = 0 does not diffuse either.
  ModelFromText z(
      "<diffusion_model type=\"jg\"><diffusivity>0</diffusivity>"
      "<max_concentration>1.0</max_concentration></diffusion_model>");
  EXPECT_FALSE(z.model->diffuses());
}

TEST(DiffusionModel, BaseTags) {
  ModelFromText m(
      "<diffusion_model type=\"jg\"><diffusivity>1</diffusivity>"
      "<max_concentration>2.0</max_concentration><min_concentration>0.5</min_concentration>"
      "<conc_tolerance>1e-10</conc_tolerance><initial_concentration>0.7</initial_concentration>"
      "</diffusion_model>");
  EXPECT_EQ(m.model->D0, 1.0);
  EXPECT_EQ(m.model->maxConcentration, 2.0);
  EXPECT_EQ(m.model->minConcentration, 0.5);
}

std::string chemicalPotentialModel(const std::string& more) {
  return "<diffusion_model type=\"chemical_potential\"><diffusivity>3</diffusivity>"
         "<max_concentration>1</max_concentration><cmax_RT>2</cmax_RT>" +
         more + "</diffusion_model>";
}

// k = Omega c_max / (c_max R T): 3 eta / <cmax_RT> unless <stress_coupling> gives Omega c_max,
// which is warned of when it differs; s = k eta 12 K G / (3K + 4G) (K = 3, G = 2 here), and the
// pass's diffusivity D0 (1 + s c (1 - c)), whatever the stress.
TEST(DiffusionModel, ChemicalPotentialTakesItsStressTermFromTheSwelling) {
  ModelFromText fromSwelling(chemicalPotentialModel(""), 1.0, 0.2, true);
  const double k = 0.6 / 2, s = k * 0.2 * 12 * 3 * 2 / (9 + 8);
  EXPECT_DOUBLE_EQ(fromSwelling.model->stressPotentialPerStress(), k);
  EXPECT_DOUBLE_EQ(fromSwelling.model->stressPotentialStabilization(), s);
  EXPECT_TRUE(fromSwelling.spec->warnings().empty());
  ParticleSet p = particles(kConcentrations, -2e6 * Mat3::Identity());
  EXPECT_DOUBLE_EQ(fromSwelling.model->computeDiffusivity(p, 0.0), 3.0 * (1 + s / 4));
  for (size_t i = 0; i < p.count(); ++i)
    EXPECT_DOUBLE_EQ(diffusionParticles(p).diffusivity[i],
                     3.0 * (1 + s * kConcentrations[i] * (1 - kConcentrations[i])));

  ModelFromText given(chemicalPotentialModel("<stress_coupling>0.5</stress_coupling>"), 1.0, 0.2,
                      true);
  EXPECT_DOUBLE_EQ(given.model->stressPotentialPerStress(), 0.25);
  ASSERT_EQ(given.spec->warnings().size(), 1u);
  EXPECT_NE(given.spec->warnings()[0].find("stress_coupling"), std::string::npos);
  // The swelling's own value: no warning; 0: a Fickian flux.
  ModelFromText same(chemicalPotentialModel("<stress_coupling>0.6</stress_coupling>"), 1.0, 0.2,
                     true);
  EXPECT_TRUE(same.spec->warnings().empty());
  ModelFromText fick(chemicalPotentialModel(""), 1.0, 0.0, true);
  EXPECT_EQ(fick.model->stressPotentialPerStress(), 0.0);
  EXPECT_EQ(fick.model->stressPotentialStabilization(), 0.0);
}

// The model text below starts on line 2 of the document; `line` is the line of the offending
// element within the whole text.
void expectInputError(const std::string& model, int line, const std::string& fragment,
                      double maxTime = 1.0, bool implicit = false) {
  try {
    ModelFromText m(model, maxTime, 0.1, implicit);
    ADD_FAILURE() << "no InputError for:\n" << model;
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), "diffusion.ups");
    EXPECT_EQ(e.line(), line) << what;
    EXPECT_EQ(what.rfind("diffusion.ups:" + std::to_string(line) + ": ", 0), 0u) << what;
    EXPECT_NE(what.find(fragment), std::string::npos) << what;
  }
}

TEST(DiffusionModelFactory, UnknownAndUnsupportedTypes) {
  expectInputError(
      "<diffusion_model type=\"fickian\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "unknown diffusion_model type=\"fickian\"");
  expectInputError(
      "<diffusion_model type=\"rf1\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "not supported");
  expectInputError(
      "<diffusion_model type=\"non_linear2\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "not supported");
  expectInputError("<diffusion_model><diffusivity>1</diffusivity></diffusion_model>", 2, "type");
}

TEST(DiffusionModelFactory, ChemicalPotentialBadValues) {
  expectInputError(chemicalPotentialModel(""), 2, "explicit path");
  expectInputError(
      "<diffusion_model type=\"chemical_potential\"><diffusivity>3</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "cmax_RT", 1.0, true);
  expectInputError(
      "<diffusion_model type=\"chemical_potential\"><diffusivity>3</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<cmax_RT>0</cmax_RT></diffusion_model>",
      4, "<cmax_RT> must be positive", 1.0, true);
  expectInputError(
      "<diffusion_model type=\"chemical_potential\"><diffusivity>3</diffusivity>\n"
      "<max_concentration>1</max_concentration><cmax_RT>1</cmax_RT>\n"
      "<stress_coupling>-1</stress_coupling></diffusion_model>",
      4, "<stress_coupling> must be >= 0", 1.0, true);
}

TEST(DiffusionModelFactory, MissingRequiredTags) {
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<tuning1>6</tuning1><tuning2>0.5</tuning2>\n"
      "</diffusion_model>",
      2, "use_pressure");
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<use_pressure>false</use_pressure>\n"
      "<tuning2>0.5</tuning2>\n</diffusion_model>",
      2, "tuning1");
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<use_pressure>false</use_pressure>\n"
      "<tuning1>6</tuning1>\n</diffusion_model>",
      2, "tuning2");
  // use_pressure true requires tuning3..5.
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<use_pressure>true</use_pressure>\n"
      "<tuning1>6</tuning1><tuning2>0.5</tuning2><tuning4>3</tuning4><tuning5>1e-6</tuning5>\n"
      "</diffusion_model>",
      2, "tuning3");
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<use_pressure>true</use_pressure>\n"
      "<tuning1>6</tuning1><tuning2>0.5</tuning2><tuning3>0</tuning3><tuning4>3</tuning4>\n"
      "</diffusion_model>",
      2, "tuning5");
  // p_max below the floor, on the <tuning4> line.
  expectInputError(
      "<diffusion_model type=\"non_linear1\">\n<diffusivity>1</diffusivity>\n"
      "<max_concentration>1</max_concentration>\n<use_pressure>true</use_pressure>\n"
      "<tuning1>6</tuning1><tuning2>0.5</tuning2><tuning3>1</tuning3>\n<tuning4>0.5</tuning4>\n"
      "<tuning5>1e-6</tuning5></diffusion_model>",
      7, "tuning4");
  expectInputError(
      "<diffusion_model type=\"jg\"><max_concentration>1</max_concentration></diffusion_model>", 2,
      "diffusivity");
  expectInputError("<diffusion_model type=\"jg\"><diffusivity>1</diffusivity></diffusion_model>", 2,
                   "max_concentration");
  expectInputError(
      "<diffusion_model type=\"constant_rate\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "constant_rate");
  expectInputError(
      "<diffusion_model type=\"cubic\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration></diffusion_model>",
      2, "max_diffusivity");
  // Values out of range, on the offending tag's line.
  expectInputError(
      "<diffusion_model type=\"jg\">\n<diffusivity>-1</diffusivity>\n"
      "<max_concentration>1</max_concentration></diffusion_model>",
      3, "must be >= 0");
  expectInputError(
      "<diffusion_model type=\"jg\"><diffusivity>1</diffusivity>\n"
      "<max_concentration>0</max_concentration></diffusion_model>",
      3, "must be positive");
}

TEST(DiffusionModelFactory, DiffCurveMustReachBeyondMaxTime) {
  // The curve element is on line 3 (curveModel breaks the line before <diff_curve>).
  expectInputError(curveModel(5.0), 3, "beyond <maxTime>", 5.0);  // last time == maxTime
  expectInputError(curveModel(4.0), 3, "beyond <maxTime>", 5.0);  // last time < maxTime
  EXPECT_NO_THROW(ModelFromText(curveModel(5.0), 4.999));
  // Other curve errors: fewer than two points, times not increasing, a bad direction.
  expectInputError(
      "<diffusion_model type=\"non_linear1\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration><use_pressure>false</use_pressure>"
      "<tuning1>6</tuning1><tuning2>0</tuning2>\n<diff_curve>"
      "<time_point><time>10</time><flux_direction>in</flux_direction></time_point>"
      "</diff_curve></diffusion_model>",
      3, "at least two");
  expectInputError(
      "<diffusion_model type=\"non_linear1\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration><use_pressure>false</use_pressure>"
      "<tuning1>6</tuning1><tuning2>0</tuning2><diff_curve>\n"
      "<time_point><time>0</time><flux_direction>in</flux_direction></time_point>\n"
      "<time_point><time>0</time><flux_direction>out</flux_direction></time_point>\n"
      "</diff_curve></diffusion_model>",
      4, "strictly increasing");
  expectInputError(
      "<diffusion_model type=\"non_linear1\"><diffusivity>1</diffusivity>"
      "<max_concentration>1</max_concentration><use_pressure>false</use_pressure>"
      "<tuning1>6</tuning1><tuning2>0</tuning2><diff_curve>\n"
      "<time_point><time>0</time><flux_direction>in</flux_direction></time_point>\n"
      "<time_point><time>10</time><flux_direction>sideways</flux_direction></time_point>\n"
      "</diff_curve></diffusion_model>",
      4, "in, out or transition");
}

// ---------------------------------------------------------------------------------------------
// Flux BC selection of surface particles

ScalarFluxBC boxBC(const Vec3& lo, const Vec3& hi) {
  ScalarFluxBC bc;
  bc.face = ScalarFluxBC::Face::Box;
  bc.boxMin = lo;
  bc.boxMax = hi;
  return bc;
}

TEST(ScalarFluxBCArea, AreaStretchIsNanson) {
  // a / A = J |F^-T N| for the x+ face (N = x): a stretch along the normal leaves the face as it
  // is, a stretch across it grows it, a shear that slides the face within its plane leaves it.
  const ScalarFluxBC bc = boxBC(Vec3(1, 0, 0), Vec3(1, 0.5, 0.5));
  const Vec3 X(1, 0.2, 0.2);
  EXPECT_NEAR(bc.areaStretch(Vec3(2, 1, 1).asDiagonal().toDenseMatrix(), X), 1.0, 1e-15);
  EXPECT_NEAR(bc.areaStretch(Vec3(1, 2, 3).asDiagonal().toDenseMatrix(), X), 6.0, 1e-14);
  Mat3 shear = Mat3::Identity();
  shear(1, 0) = 0.5;  // y += 0.5 X: the face X = 1 slides within its plane
  EXPECT_NEAR(bc.areaStretch(shear, X), 1.0, 1e-15);
  shear = Mat3::Identity();
  shear(0, 1) = 0.5;  // x += 0.5 Y: the face tilts, its edge along Y becomes (0.5, 1, 0)
  EXPECT_NEAR(bc.areaStretch(shear, X), std::sqrt(1.25), 1e-15);
  // A rotation changes no area.
  const Mat3 R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  EXPECT_NEAR(bc.areaStretch(R * Vec3(1, 2, 3).asDiagonal().toDenseMatrix(), X), 6.0, 1e-13);
}

TEST(ScalarFluxBCArea, BoxFlagsWithinTheBoxEnlargedByDxp) {
  // The x+ face of a body [0,1] x [0,0.5] x [0,0.5]; particles dxp = (0.05, 0.1, 0.2).
  const ScalarFluxBC bc = boxBC(Vec3(1, 0, 0), Vec3(1, 0.5, 0.5));
  const Vec3 dxp(0.05, 0.1, 0.2);
  const double area = 0.1 * 0.2;  // the face normal to x (the box's thinnest axis)
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.975, 0.25, 0.25), dxp), area);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.951, 0.05, 0.45), dxp), area);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(1.049, 0.25, 0.25), dxp), area);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.975, -0.099, 0.25), dxp), area);  // y > 0 - dyp
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.975, 0.25, 0.699), dxp), area);   // z < 0.5 + dzp
  EXPECT_EQ(bc.flaggedArea(Vec3(0.925, 0.25, 0.25), dxp), 0.0);            // the second layer
  EXPECT_EQ(bc.flaggedArea(Vec3(1.051, 0.25, 0.25), dxp), 0.0);
  EXPECT_EQ(bc.flaggedArea(Vec3(0.975, -0.101, 0.25), dxp), 0.0);
  EXPECT_EQ(bc.flaggedArea(Vec3(0.975, 0.25, 0.701), dxp), 0.0);
  // Thinnest axis y (a y+ face) and z (a z- face).
  const Vec3 dxq(0.1, 0.2, 0.3);
  EXPECT_DOUBLE_EQ(boxBC(Vec3(0, 1, 0), Vec3(2, 1.01, 3)).flaggedArea(Vec3(1, 0.95, 1), dxq),
                   0.1 * 0.3);
  EXPECT_DOUBLE_EQ(boxBC(Vec3(0, 0, 0), Vec3(2, 3, 0)).flaggedArea(Vec3(1, 1, 0.15), dxq),
                   0.1 * 0.2);
}

ScalarFluxBC cylinderBC(bool end) {
  ScalarFluxBC bc;
  bc.face = end ? ScalarFluxBC::Face::CylinderEnd : ScalarFluxBC::Face::CylinderSide;
  bc.bottom = Vec3(0, 0, 0);
  bc.top = Vec3(0, 0, 1);
  bc.radius = 1;
  return bc;
}

TEST(ScalarFluxBCArea, CylinderSideUsesTheRadialToleranceAndTheRadialProjection) {
  const ScalarFluxBC bc = cylinderBC(false);
  const Vec3 dxp(0.1, 0.1, 0.2);  // tol = 0.9 * 0.1 = 0.09; faces (0.02, 0.02, 0.01)
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.95, 0, 0.5), dxp), 0.02);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.911, 0, 0.5), dxp), 0.02);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0, -1.089, 0.5), dxp), 0.02);
  EXPECT_EQ(bc.flaggedArea(Vec3(0.909, 0, 0.5), dxp), 0.0);   // r < R - tol
  EXPECT_EQ(bc.flaggedArea(Vec3(1.091, 0, 0.5), dxp), 0.0);   // r > R + tol
  EXPECT_EQ(bc.flaggedArea(Vec3(0.95, 0, -0.01), dxp), 0.0);  // below the bottom
  EXPECT_EQ(bc.flaggedArea(Vec3(0.95, 0, 1.01), dxp), 0.0);   // above the top
  // At 45 degrees with equal x, y faces the projected area is that face's.
  const double s = std::sqrt(0.5);
  EXPECT_NEAR(bc.flaggedArea(Vec3(0.95 * s, 0.95 * s, 0.5), dxp), 0.02, 1e-16);
  // Anisotropic particle: |(A_x n_x, A_y n_y, 0)| with A = (0.06, 0.03, 0.02), n = (0.6, 0.8).
  const Vec3 dxq(0.1, 0.2, 0.3);  // tol = 0.09
  EXPECT_NEAR(bc.flaggedArea(Vec3(0.6, 0.8, 0.5), dxq), std::hypot(0.036, 0.024), 1e-16);
  // The tolerance is 0.9 min(dxp): with dxq the smallest edge is 0.1 again.
  EXPECT_EQ(bc.flaggedArea(Vec3(0.909, 0, 0.5), dxq), 0.0);
  EXPECT_GT(bc.flaggedArea(Vec3(0.911, 0, 0.5), dxq), 0.0);
}

TEST(ScalarFluxBCArea, CylinderEndFlagsTheCylinderExtendedAxially) {
  const ScalarFluxBC bc = cylinderBC(true);
  const Vec3 dxp(0.1, 0.2, 0.05);  // tol = 0.045; end area dxp.x * dxp.y = 0.02
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0.5, 0, 1.04), dxp), 0.02);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0, 0.99, -0.044), dxp), 0.02);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(0, 0, 0.5), dxp), 0.02);  // interior: Uintah's rule
  EXPECT_EQ(bc.flaggedArea(Vec3(0.5, 0, 1.046), dxp), 0.0);
  EXPECT_EQ(bc.flaggedArea(Vec3(0.5, 0, -0.046), dxp), 0.0);
  EXPECT_EQ(bc.flaggedArea(Vec3(1.01, 0, 0.5), dxp), 0.0);  // outside the radius
  // An axis along x: the area is the face normal to x.
  ScalarFluxBC x = bc;
  x.top = Vec3(2, 0, 0);
  EXPECT_DOUBLE_EQ(x.flaggedArea(Vec3(2.04, 0.5, 0), dxp), 0.2 * 0.05);
}

TEST(ScalarFluxBCArea, SphereShell) {
  ScalarFluxBC bc;
  bc.face = ScalarFluxBC::Face::Sphere;
  bc.center = Vec3(1, 1, 1);
  bc.radius = 0.5;
  const Vec3 dxp(0.03, 0.04, 0.12);  // |dxp| = 0.13; area = the x face, 0.04 * 0.12
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(1, 1.62, 1), dxp), 0.04 * 0.12);
  EXPECT_DOUBLE_EQ(bc.flaggedArea(Vec3(1.38, 1, 1), dxp), 0.04 * 0.12);
  EXPECT_EQ(bc.flaggedArea(Vec3(1, 1.64, 1), dxp), 0.0);
  EXPECT_EQ(bc.flaggedArea(Vec3(1, 1, 1.36), dxp), 0.0);
}

TEST(ScalarFluxBCArea, ReadFromInput) {
  auto spec = ProblemSpec::fromText(
      "<Uintah_specification><PhysicalBC><MPM>\n"
      "<scalar_flux><geom_object><box><min>[1,0,0]</min><max>[1,0.5,0.5]</max></box></geom_object>"
      "<load_curve><id>1</id><time_point><time>0</time><load>2</load></time_point>"
      "<time_point><time>1</time><load>4</load></time_point></load_curve></scalar_flux>\n"
      "<scalar_flux><geom_object><cylinder><bottom>[0,0,0]</bottom><top>[0,0,1]</top>"
      "<radius>1</radius><cylinder_end>true</cylinder_end></cylinder></geom_object>"
      "<load_curve><id>2</id><time_point><time>0</time><load>-1</load></time_point></load_curve>"
      "</scalar_flux>\n</MPM></PhysicalBC></Uintah_specification>",
      "flux.ups");
  const auto bcs = ScalarFluxBC::fromInput(readPhysicalBCs(spec->root()).scalarFlux);
  ASSERT_EQ(bcs.size(), 2u);
  EXPECT_EQ(bcs[0].face, ScalarFluxBC::Face::Box);
  EXPECT_EQ(bcs[0].line, 2);
  EXPECT_EQ(bcs[0].load.at(0.5), 3.0);
  EXPECT_EQ(bcs[1].face, ScalarFluxBC::Face::CylinderEnd);
  EXPECT_EQ(bcs[1].load.at(7.0), -1.0);
  // Load-curve ids must number the blocks 1..N in file order.
  auto bad = ProblemSpec::fromText(
      "<Uintah_specification><PhysicalBC><MPM>\n"
      "<scalar_flux><geom_object><box><min>[1,0,0]</min><max>[1,0.5,0.5]</max></box></geom_object>"
      "<load_curve>\n<id>2</id><time_point><time>0</time><load>2</load></time_point></load_curve>"
      "</scalar_flux>\n</MPM></PhysicalBC></Uintah_specification>",
      "flux.ups");
  try {
    ScalarFluxBC::fromInput(readPhysicalBCs(bad->root()).scalarFlux);
    ADD_FAILURE() << "no InputError for load curve id 2 on the first block";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
  }
}

TEST(SurfaceDetection, OnSurfaceTestsXPlusMinusDxpPerAxis) {
  BoxPiece box;
  box.lo = Vec3(0, 0, 0);
  box.hi = Vec3(1, 1, 1);
  const Vec3 dxp(0.1, 0.1, 0.1);
  EXPECT_FALSE(onSurface(box, Vec3(0.5, 0.5, 0.5), dxp, 3));
  EXPECT_TRUE(onSurface(box, Vec3(0.05, 0.5, 0.5), dxp, 3));    // x - dxp outside
  EXPECT_TRUE(onSurface(box, Vec3(0.5, 0.95, 0.5), dxp, 3));    // y + dyp outside
  EXPECT_TRUE(onSurface(box, Vec3(0.5, 0.5, 0.95), dxp, 3));    // z + dzp outside
  EXPECT_FALSE(onSurface(box, Vec3(0.15, 0.85, 0.5), dxp, 3));  // second layer: closed box
  // ndim 2: z is not tested; ndim 1 still tests x and y (Uintah's checkForSurface).
  EXPECT_FALSE(onSurface(box, Vec3(0.5, 0.5, 0.95), dxp, 2));
  EXPECT_TRUE(onSurface(box, Vec3(0.5, 0.95, 0.5), dxp, 2));
  EXPECT_TRUE(onSurface(box, Vec3(0.5, 0.95, 0.5), dxp, 1));
  EXPECT_FALSE(onSurface(box, Vec3(0.5, 0.5, 0.95), dxp, 1));
  // Anisotropic dxp: each axis uses its own edge.
  const Vec3 dxq(0.02, 0.3, 0.1);
  EXPECT_FALSE(onSurface(box, Vec3(0.05, 0.5, 0.5), dxq, 3));
  EXPECT_TRUE(onSurface(box, Vec3(0.5, 0.25, 0.5), dxq, 3));
}

}  // namespace
}  // namespace anode
