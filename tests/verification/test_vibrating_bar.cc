// Axial vibrating bar against its small-amplitude analytic solution
// (StandAlone/Studies/VibratingBar.h), at the quick resolutions of `vibrating_bar_study --quick`.
// Bounds are the values measured with timestep_multiplier 0.2 (docs/verification.md, "Axial
// vibrating bar") plus a modest margin; orders are asserted below the measured ones.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "StandAlone/Studies/VibratingBar.h"

namespace {

using anode::VibratingBarResult;

double order(const VibratingBarResult& coarse, const VibratingBarResult& fine,
             double VibratingBarResult::*metric) {
  return std::log(coarse.*metric / fine.*metric) / std::log(double(fine.cells) / coarse.cells);
}

class VibratingBar : public ::testing::TestWithParam<std::string> {
 protected:
  static std::vector<VibratingBarResult> run(const std::string& interpolator) {
    std::vector<VibratingBarResult> results;
    for (int cells : anode::vibratingBarQuickCells()) {
      anode::VibratingBarCase c;
      c.cells = cells;
      c.interpolator = interpolator;
      results.push_back(anode::runVibratingBar(c));
    }
    return results;
  }
};

TEST_P(VibratingBar, ConvergesToTheAnalyticSolutionAndConservesEnergy) {
  const std::vector<VibratingBarResult> r = run(GetParam());
  ASSERT_EQ(r.size(), 3u);
  const anode::VibratingBarCase base;
  for (const VibratingBarResult& x : r) {
    SCOPED_TRACE(GetParam() + ", " + std::to_string(x.cells) + " cells");
    EXPECT_EQ(x.particles, 2u * x.cells);  // res [2,1,1] over the bar only
    EXPECT_NEAR(x.finalTime, base.period(), 1e-12 * base.period());
    EXPECT_LT(x.transverseVelocity, 1e-12);  // Symmetric y and z faces: uniaxial strain
  }
  for (size_t i = 1; i < r.size(); ++i) {
    SCOPED_TRACE(GetParam() + ", " + std::to_string(r[i - 1].cells) + " -> " +
                 std::to_string(r[i].cells) + " cells");
    // Measured 1.35-1.59: O(h^2) space plus the O(dt) = O(h) half-step lag of the velocity.
    EXPECT_GT(order(r[i - 1], r[i], &VibratingBarResult::centreOfMassError), 1.0);
    // Measured 2.01-2.12 once the lag is taken out.
    EXPECT_GT(order(r[i - 1], r[i], &VibratingBarResult::centreOfMassErrorStaggered), 1.8);
    // Measured 1.47-1.50 (O(h) error on the particles next to the fixed end).
    EXPECT_GT(order(r[i - 1], r[i], &VibratingBarResult::velocityL2Error), 1.3);
    // Measured 1.04-1.28: the kinetic + strain energy oscillates by O(w dt).
    EXPECT_GT(order(r[i - 1], r[i], &VibratingBarResult::energyDrift), 0.8);
    EXPECT_LT(r[i].leapfrogEnergyDrift, r[i - 1].leapfrogEnergyDrift);
  }
  // 32 cells, measured: vcm 6.50e-3..6.58e-3, staggered 1.71e-3..1.82e-3, L2 4.61e-3,
  // energy 4.95e-3..4.96e-3, leapfrog energy 6.8e-5..8.1e-5.
  const VibratingBarResult& finest = r.back();
  EXPECT_LT(finest.centreOfMassError, 8e-3);
  EXPECT_LT(finest.centreOfMassErrorStaggered, 2.2e-3);
  EXPECT_LT(finest.velocityL2Error, 5.5e-3);
  EXPECT_LT(finest.energyDrift, 6e-3);
  EXPECT_LT(finest.leapfrogEnergyDrift, 1.2e-4);
}

// Implicit dynamics (<dynamic>true: Newmark's trapezoidal rule, Implicit/Newmark.h) on the same
// bar, linear interpolation. Measured (vibrating_bar_study --quick --implicit 200 / 50): 200 steps
// a period, 16 -> 32 cells: vcm 6.65e-3 -> 1.95e-3 (order 1.77), energy drift 9.96e-5 and 4.49e-5;
// 32 cells with 50 steps a period: vcm 7.88e-3.
TEST(VibratingBarImplicit, NewmarkConvergesKeepsTheEnergyAndLagsAsTheTrapezoidalRule) {
  std::vector<VibratingBarResult> r;
  for (int cells : {16, 32}) {
    anode::VibratingBarCase c;
    c.cells = cells;
    c.implicitStepsPerPeriod = 200;
    r.push_back(anode::runVibratingBar(c));
  }
  const anode::VibratingBarCase base;
  for (const VibratingBarResult& x : r) {
    SCOPED_TRACE(std::to_string(x.cells) + " cells");
    EXPECT_EQ(x.steps, 200);
    EXPECT_NEAR(x.finalTime, base.period(), 1e-12 * base.period());
    EXPECT_LT(x.transverseVelocity, 1e-12);
    // The trapezoidal rule keeps a linear system's energy: what drifts is space's and the
    // geometric nonlinearity's (the explicit step's kinetic + strain energy drifts 5e-3 here).
    EXPECT_LT(x.energyDrift, 2e-4);
  }
  EXPECT_GT(order(r[0], r[1], &VibratingBarResult::centreOfMassError), 1.5);
  EXPECT_LT(r[1].velocityL2Error, 3e-5);
  // With few steps the error is Newmark's period elongation (Hughes): T'/T - 1 = (w dt)^2 / 12,
  // so after one period the phase lags by 2 pi (w dt)^2 / 12, and v_cm's largest relative error
  // is that lag (plus the spatial error, 2e-3 at 32 cells).
  anode::VibratingBarCase c;
  c.cells = 32;
  c.implicitStepsPerPeriod = 50;
  const VibratingBarResult coarse = anode::runVibratingBar(c);
  const double wdt = c.omega() * c.period() / c.implicitStepsPerPeriod;
  const double lag = 2 * M_PI * wdt * wdt / 12;
  EXPECT_NEAR(coarse.centreOfMassError, lag, 0.25 * lag);
}

INSTANTIATE_TEST_SUITE_P(Interpolators, VibratingBar, ::testing::Values("linear", "gimp", "cpdi"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
