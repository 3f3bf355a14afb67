// The paper's 1-D diffusion verification (§2.2, StandAlone/Studies/DiffusionSlab1D.h) at the quick
// resolutions of `diffusion_1d_study --quick` (h = 1/20, 1/40, 1/80), for both SD-Type Dirichlet
// treatments. Uintah's nodal treatment overshoots [0, 1] (docs/verification.md, "1-D diffusion"),
// so the accuracy runs use the "-wide" variants, whose input declares the range [-1, 2]; with
// [0, 1] the nodal run is checked to stop on the code's range check and the particle run to
// complete. Bounds are the measured values (quoted) plus a margin; orders are asserted below the
// measured ones.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "StandAlone/Studies/DiffusionSlab1D.h"

namespace {

using anode::DiffusionSlabCase;
using anode::DiffusionSlabResult;

double order(const DiffusionSlabResult& coarse, const DiffusionSlabResult& fine,
             double DiffusionSlabResult::*metric) {
  return std::log(coarse.*metric / fine.*metric) / std::log(coarse.h / fine.h);
}

DiffusionSlabCase slab(const std::string& interpolator, const std::string& variant, int cells) {
  DiffusionSlabCase c;
  c.cells = cells;
  c.interpolator = interpolator;
  anode::setDiffusionSlabVariant(c, variant);
  return c;
}

std::vector<DiffusionSlabResult> run(const std::string& interpolator, const std::string& variant) {
  std::vector<DiffusionSlabResult> results;
  for (int cells : anode::diffusionSlabQuickCells())
    results.push_back(anode::runDiffusionSlab(slab(interpolator, variant, cells)));
  return results;
}

TEST(DiffusionSlab1D, ExactSolution) {
  // Eq. 13: boundary values, the steady profile as t grows, and a value from an erfc-image sum
  // (c = sum_k [erfc((2k + x)/s) - erfc((2k + 2 - x)/s)], s = 2 sqrt(Dt)).
  EXPECT_NEAR(anode::diffusionSlabExact(0.0, 0.25, 0.1), 1.0, 1e-12);
  EXPECT_NEAR(anode::diffusionSlabExact(1.0, 0.25, 0.1), 0.0, 1e-12);
  EXPECT_NEAR(anode::diffusionSlabExact(0.3, 1e3, 0.1), 0.7, 1e-12);
  const double x = 0.2, s = 2 * std::sqrt(0.1 * 0.25);
  double images = 0;
  for (int k = 0; k < 20; ++k)
    images += std::erfc((2 * k + x) / s) - std::erfc((2 * k + 2 - x) / s);
  EXPECT_NEAR(anode::diffusionSlabExact(x, 0.25, 0.1), images, 1e-12);
}

class DiffusionSlab : public ::testing::TestWithParam<std::string> {};

TEST_P(DiffusionSlab, NodalTreatmentConvergesButLeavesTheUnitInterval) {
  const std::vector<DiffusionSlabResult> r = run(GetParam(), "nodal-wide");
  ASSERT_EQ(r.size(), 3u);
  const DiffusionSlabCase base;
  for (const DiffusionSlabResult& x : r) {
    SCOPED_TRACE(GetParam() + ", h = " + std::to_string(x.h));
    ASSERT_TRUE(x.completed) << x.stopMessage;
    EXPECT_EQ(x.particles, 2u * x.cells);
    // The diffusion limit sets dt (mechanics is far slower), and the run ends on t = 0.25.
    EXPECT_NEAR(x.firstDt, base.timestepMultiplier * x.h * x.h / (2 * base.diffusivity), 1e-15);
    EXPECT_EQ(x.steps, std::lround(std::ceil(base.endTime / x.firstDt - 1e-9)));
    EXPECT_NEAR(x.finalTime, base.endTime, 1e-12);
    EXPECT_LT(x.maxDisplacement, 1e-12);
    // Uintah's nodal rate drives the projection on the wall node to c_BC, so the particle next
    // to the c = 1 wall rises above 1 (measured 1.1605 at every h) and the one next to the c = 0
    // wall dips below 0 (-4.0e-6, -2.1e-6, -1.0e-6).
    EXPECT_GT(x.maxConcentration, 1.15);
    EXPECT_LT(x.maxConcentration, 1.17);
    EXPECT_LT(x.minConcentration, 0.0);
    EXPECT_GT(x.minConcentration, -1e-5);
  }
  for (size_t i = 1; i < r.size(); ++i) {
    SCOPED_TRACE(GetParam() + ", h = " + std::to_string(r[i - 1].h) + " -> " +
                 std::to_string(r[i].h));
    // Measured 1.46, 1.14 (the paper's slope is 1).
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::paperNorm), 1.0);
    // Measured 1.58, 1.52: O(h) errors on the O(1) particles next to the walls.
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::rmsAbsolute), 1.35);
    // Measured 2.24, 2.00 away from the walls (0.1 <= x <= 0.9).
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::interiorRmsAbsolute), 1.8);
    // Measured 1.05, 1.01.
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::maxAbsolute), 0.9);
  }
  // h = 1/80, measured: Eq. 15 1.280e-2, RMS abs 1.882e-3, interior 1.525e-4, max 2.235e-2.
  const DiffusionSlabResult& finest = r.back();
  EXPECT_LT(finest.paperNorm, 1.4e-2);
  EXPECT_LT(finest.rmsAbsolute, 2.1e-3);
  EXPECT_LT(finest.interiorRmsAbsolute, 1.7e-4);
  EXPECT_LT(finest.maxAbsolute, 2.5e-2);
}

TEST_P(DiffusionSlab, ParticleTreatmentConverges) {
  const std::vector<DiffusionSlabResult> r = run(GetParam(), "particle-wide");
  ASSERT_EQ(r.size(), 3u);
  for (const DiffusionSlabResult& x : r) {
    SCOPED_TRACE(GetParam() + ", h = " + std::to_string(x.h));
    ASSERT_TRUE(x.completed) << x.stopMessage;
    EXPECT_NEAR(x.finalTime, 0.25, 1e-12);
    // Particles touching a wall node take the grid solution (a convex combination of nodal
    // values), so c stays in [0, 1]: min c = 0 (the initial state), max c = 0.955066, 0.977689,
    // 0.988848 (the particle at h/4, at t = 0.25). See also
    // ParticleTreatmentKeepsCInTheUnitInterval.
    EXPECT_GE(x.minConcentration, 0.0);
    EXPECT_LE(x.maxConcentration, 1.0);
  }
  for (size_t i = 1; i < r.size(); ++i) {
    SCOPED_TRACE(GetParam() + ", h = " + std::to_string(r[i - 1].h) + " -> " +
                 std::to_string(r[i].h));
    // Second order everywhere, walls included (the nodal treatment: 1.5 in RMS, 1 in max).
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::paperNorm), 2.25);           // 2.52, 2.52
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::rmsAbsolute), 1.8);          // 2.20, 2.04
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::interiorRmsAbsolute), 1.8);  // 2.09, 2.03
    EXPECT_GT(order(r[i - 1], r[i], &DiffusionSlabResult::maxAbsolute), 1.8);          // 2.38, 2.04
  }
  // h = 1/80, measured: Eq. 15 2.224e-3, RMS abs 1.454e-4, interior 1.516e-4, max 3.298e-4.
  const DiffusionSlabResult& finest = r.back();
  EXPECT_LT(finest.paperNorm, 2.45e-3);
  EXPECT_LT(finest.rmsAbsolute, 1.6e-4);
  EXPECT_LT(finest.interiorRmsAbsolute, 1.7e-4);
  EXPECT_LT(finest.maxAbsolute, 3.65e-4);
}

TEST_P(DiffusionSlab, UnitRangeStopsTheNodalTreatmentOnly) {
  // With the physical range [0, 1] (1e-6 tolerance) Uintah's nodal treatment is stopped by the
  // range check (1.08125 at step 2); the particle treatment completes.
  const DiffusionSlabResult nodal = anode::runDiffusionSlab(slab(GetParam(), "nodal", 40));
  EXPECT_FALSE(nodal.completed);
  EXPECT_EQ(nodal.steps, 2);
  EXPECT_NEAR(nodal.maxConcentration, 1.08125, 1e-5);
  EXPECT_NE(nodal.stopMessage.find("stopped: c = 1.08"), std::string::npos) << nodal.stopMessage;
  const DiffusionSlabResult particle = anode::runDiffusionSlab(slab(GetParam(), "particle", 40));
  EXPECT_TRUE(particle.completed) << particle.stopMessage;
}

// The particle treatment (docs/diffusion.md) keeps c in [0, 1]: particles touching a Dirichlet
// node take a convex combination of nodal values.
TEST_P(DiffusionSlab, ParticleTreatmentKeepsCInTheUnitInterval) {
  for (int cells : anode::diffusionSlabQuickCells()) {
    const DiffusionSlabResult r = anode::runDiffusionSlab(slab(GetParam(), "particle", cells));
    EXPECT_TRUE(r.completed) << r.stopMessage;
    EXPECT_GE(r.minConcentration, -1e-12);
    EXPECT_LE(r.maxConcentration, 1 + 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Interpolators, DiffusionSlab, ::testing::Values("linear", "gimp", "cpdi"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

TEST(DiffusionSlab1D, GimpAndCpdiEqualLinearHere) {
  // Two particles per cell that never move: no particle domain straddles a node, so uGIMP and
  // undeformed CPDI weights and gradients are the linear ones (up to round-off).
  for (const char* variant : {"particle-wide", "nodal-wide"}) {
    const DiffusionSlabResult linear = anode::runDiffusionSlab(slab("linear", variant, 40));
    for (const char* other : {"gimp", "cpdi"}) {
      SCOPED_TRACE(std::string(other) + ", " + variant);
      const DiffusionSlabResult r = anode::runDiffusionSlab(slab(other, variant, 40));
      EXPECT_EQ(r.steps, linear.steps);
      EXPECT_NEAR(r.rmsAbsolute, linear.rmsAbsolute, 1e-10 * linear.rmsAbsolute);
      EXPECT_NEAR(r.paperNorm, linear.paperNorm, 1e-10 * linear.paperNorm);
      EXPECT_NEAR(r.maxConcentration, linear.maxConcentration, 1e-12);
    }
  }
}

}  // namespace
