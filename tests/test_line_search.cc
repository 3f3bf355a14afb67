// Pins Newton's line search on the correction's energy (Components/MPM/Implicit/LineSearch.h)
// on slopes g(s) = du.r(u + s du) of known shape: it finds the energy's minimum along an
// overshooting correction, steps back from trials that left the tangent's region or are not a
// number, takes a whole correction along which the energy falls without a trial, and returns the
// best trial when none meets its criterion.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "Components/MPM/Implicit/LineSearch.h"

namespace anode {
namespace {

constexpr double kEnergy = 3.0;  // g(0)

struct Slope {
  std::vector<double> tried;
  std::function<double(double)> g;
  double operator()(double s) {
    tried.push_back(s);
    return g(s);
  }
};

LineSearchChoice search(Slope& slope) {
  return searchAlongCorrection(kEnergy, slope.g(1.0), [&slope](double s) { return slope(s); });
}

TEST(LineSearch, FindsTheEnergysMinimumAlongAnOvershootingCorrection) {
  // The energy's minimum at s = 0.1: the whole correction goes nine times past it.
  Slope slope{{}, [](double s) { return kEnergy * (1 - 10 * s); }};
  const LineSearchChoice choice = search(slope);
  EXPECT_NEAR(choice.fraction, 0.1, 1e-12);
  EXPECT_TRUE(choice.lastTried);
  EXPECT_EQ(slope.tried.size(), 1u);
}

TEST(LineSearch, StepsBackFromATrialBeyondTheTangentsRegion) {
  // As at a pillar's rim: beyond s = 0.2 the slope jumps far above g(0).
  Slope slope{{}, [](double s) { return s < 0.2 ? kEnergy * (1 - 10 * s) : 1e4 * kEnergy; }};
  const LineSearchChoice choice = search(slope);
  EXPECT_LT(choice.fraction, 0.2);
  EXPECT_LE(std::abs(slope.g(choice.fraction)), kEnergyReduction * kEnergy);
  EXPECT_TRUE(choice.lastTried);
}

TEST(LineSearch, BisectsAwayFromTrialsThatAreNotANumber) {
  // Beyond s = 0.3 a trial inverts a particle; the minimum is at 0.2.
  Slope slope{{}, [](double s) {
                return s > 0.3 ? std::numeric_limits<double>::quiet_NaN() : kEnergy * (1 - 5 * s);
              }};
  const LineSearchChoice choice = search(slope);
  ASSERT_TRUE(std::isfinite(slope.g(choice.fraction)));
  EXPECT_LE(std::abs(slope.g(choice.fraction)), kEnergyReduction * kEnergy);
  EXPECT_DOUBLE_EQ(slope.tried.front(), 0.5);  // the first trial bisects
}

TEST(LineSearch, TakesAWholeCorrectionAlongWhichTheEnergyFalls) {
  for (const double whole : {0.9 * kEnergy, 0.1 * kEnergy, -0.4 * kEnergy}) {
    Slope slope{{}, [whole](double) { return whole; }};
    const LineSearchChoice choice = search(slope);
    EXPECT_EQ(choice.fraction, 1.0) << whole;
    EXPECT_TRUE(choice.lastTried);
    EXPECT_TRUE(slope.tried.empty());
  }
}

TEST(LineSearch, ReturnsTheBestTrialWhenNoneMeetsTheCriterion) {
  // A slope that stays at 0.9 g(0) short of s = 1, where it is far past: no trial in (0, 1) has
  // |g| <= kEnergyReduction g(0); the first (lowest |g|, the others tie) is taken.
  Slope slope{{}, [](double s) { return s < 1 ? 0.9 * kEnergy : -10 * kEnergy; }};
  const LineSearchChoice choice = search(slope);
  ASSERT_EQ(slope.tried.size(), static_cast<size_t>(kLineSearchTrials - 1));
  EXPECT_EQ(choice.fraction, slope.tried.front());
  EXPECT_FALSE(choice.lastTried);
  for (size_t k = 1; k < slope.tried.size(); ++k)  // each trial moves towards the bracket's end
    EXPECT_GT(slope.tried[k], slope.tried[k - 1]);
}

}  // namespace
}  // namespace anode
