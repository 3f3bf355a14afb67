// RKL2 (Components/MPM/ReactiveFlow/RungeKuttaLegendre.h): second order in the step, and stable up
// to (s^2 + s - 2) / 4 forward-Euler limits with s stages, on y' = -A y for A's eigenvalues.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "Components/MPM/ReactiveFlow/RungeKuttaLegendre.h"

namespace anode {
namespace {

// y_k' = -lambda_k y_k over `steps` steps of tau with s stages each.
std::vector<double> decay(const std::vector<double>& lambda, double tau, int steps, int s) {
  std::vector<double> y(lambda.size(), 1.0);
  for (int n = 0; n < steps; ++n)
    stepRkl2(y, tau, s, [&](const std::vector<double>& at, std::vector<double>& f) {
      for (size_t k = 0; k < at.size(); ++k) f[k] = -lambda[k] * at[k];
    });
  return y;
}

TEST(RungeKuttaLegendre, StagesCoverTheRatioOfForwardEulerLimits) {
  for (double ratio : {0.1, 1.0, 2.5, 10.0, 92.0, 1000.0}) {
    const int s = rkl2Stages(ratio);
    EXPECT_GE((s * s + s - 2) / 4.0, ratio) << ratio;
    if (s > 2) {
      EXPECT_LT(((s - 1) * (s - 1) + s - 3) / 4.0, ratio) << ratio;
    }
  }
  EXPECT_EQ(rkl2Stages(0.0), 2);
}

TEST(RungeKuttaLegendre, AStepAtACountsReachTakesThatCount) {
  // dt = limit x (s^2 + s - 2)/4 as DiffusionPass bounds it, dt / limit rounded either way.
  for (double limit : {0.2, 1.0 / 3, 7.3e-5, 1234.567, 0.1 * 0.7})
    for (int s : {2, 3, 19, 200, 201}) {
      const double dt = limit * (s * s + s - 2.0) / 4;
      EXPECT_EQ(rkl2Stages(dt / limit), s) << limit << " " << s;
      EXPECT_EQ(rkl2Stages(std::nextafter(dt / limit, 1e300)), s) << limit << " " << s;
    }
}

TEST(RungeKuttaLegendre, SecondOrderInTheStep) {
  // y' = -y to t = 1 in 4, 8 and 16 steps of 5 stages: the error falls about 4 times when the
  // steps halve (measured 4.28 and 4.14).
  double errors[3];
  for (int level = 0; level < 3; ++level) {
    const int steps = 4 << level;
    errors[level] = std::abs(decay({1.0}, 1.0 / steps, steps, 5)[0] - std::exp(-1.0));
  }
  for (int level = 1; level < 3; ++level) {
    const double ratio = errors[level - 1] / errors[level];
    EXPECT_GT(ratio, 3.5) << level;  // first order: 2; third: 8
    EXPECT_LT(ratio, 4.5) << level;
  }
}

TEST(RungeKuttaLegendre, StableUpToItsBoundAndNotBeyond) {
  // Eigenvalues spread up to 1, forward Euler's limit 2: 0.99 of the bound keeps every mode
  // within 1 for 20 steps; 1.3 times it lets the stiffest grow.
  std::vector<double> lambda;
  for (int k = 1; k <= 50; ++k) lambda.push_back(k / 50.0);
  for (int s : {3, 7, 14}) {
    const double bound = 2.0 * (s * s + s - 2) / 4.0;
    for (double y : decay(lambda, 0.99 * bound, 20, s)) EXPECT_LE(std::abs(y), 1.0) << s;
    EXPECT_GT(std::abs(decay({1.0}, 1.3 * bound, 20, s)[0]), 1.0) << s;
  }
}

}  // namespace
}  // namespace anode
