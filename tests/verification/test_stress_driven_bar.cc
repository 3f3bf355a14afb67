// Stress-driven diffusion on the quasi-static path against its closed form and a 1-D solution of
// the same equation: the bar standing under gravity (StandAlone/Studies/StressDrivenBar.h) at 12
// and 24 cells, at equilibrium and in its transient.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "StandAlone/Studies/StressDrivenBar.h"

namespace anode {
namespace {

// The closed form holds the lithium and solves the equation: D dc/dX = D c (1 - c) dphi/dX (no
// flux) by central differences.
TEST(StressDrivenBarExact, EquilibriumHoldsTheLithiumWithoutFlux) {
  const StressDrivenBarCase c;
  const StressDrivenBarEquilibrium exact(c);
  const int n = 4000;
  double lithium = 0;
  for (int i = 0; i < n; ++i) lithium += exact.concentration((i + 0.5) / n) / n;
  EXPECT_NEAR(lithium, c.initialConcentration, 1e-6);
  const double d = 1e-5;
  for (double X : {0.05, 0.3, 0.5, 0.77, 0.95}) {
    const double dc = (exact.concentration(X + d) - exact.concentration(X - d)) / (2 * d);
    const double dphi = (c.stressPotential(X + d) - c.stressPotential(X - d)) / (2 * d);
    const double cx = exact.concentration(X);
    EXPECT_NEAR(dc, cx * (1 - cx) * dphi, 1e-8) << X;
  }
  EXPECT_GT(exact.concentration(1) - exact.concentration(0), 0.25);  // the stress moves lithium
}

// Measured (stress_driven_bar_study --quick): equilibrium largest 4.17e-3, 2.05e-3 (order 1.02),
// mean 5.46e-4, 1.37e-4 (1.99); transient at t = 0.05 largest 4.86e-3, 2.28e-3 (1.09), mean
// 6.49e-4, 1.63e-4 (1.99). 67 and 55 steps.
TEST(StressDrivenBar, ConvergesToTheClosedFormAndTheOneDimensionalSolution) {
  for (const bool equilibrium : {true, false}) {
    StressDrivenBarResult coarser;
    for (int cells : {12, 24}) {
      StressDrivenBarCase c;
      c.cells = cells;
      c.threads = 1;
      if (!equilibrium) c.endTime = 0.05, c.maxDt = 0.001;
      const StressDrivenBarResult r = runStressDrivenBar(c, equilibrium);
      std::printf("%s, %d cells: largest %.3e, mean %.3e, range %.3f, %ld steps\n",
                  equilibrium ? "equilibrium" : "transient", cells, r.largestError, r.meanError,
                  r.concentrationRange, r.steps);
      EXPECT_NEAR(r.finalTime, c.endTime, 1e-12);
      if (coarser.particles > 0) {
        EXPECT_GT(std::log2(coarser.largestError / r.largestError), 0.9);
        EXPECT_GT(std::log2(coarser.meanError / r.meanError), 1.8);
        EXPECT_LT(r.largestError, 2.5e-3);
      }
      coarser = r;
    }
  }
}

}  // namespace
}  // namespace anode
