// The quasi-static step against a non-uniform closed form: the swelling sphere
// (StandAlone/Studies/SwellingSphere.h, Timoshenko & Goodier's thermoelastic sphere) at 4, 8
// and 16 cells per radius, and the explicit path damped to rest on the same input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "StandAlone/Studies/SwellingSphere.h"

namespace anode {
namespace {

// The closed form solves the problem: equilibrium d sigma_rr/dr + 2 (sigma_rr - sigma_tt)/r = 0,
// a free surface, and Hooke's law with the swelling strain beta (r/b)^2 on each axis, the strains
// du/dr and u/r taken by central differences.
TEST(SwellingSphereExact, SolvesTheThermoelasticSphere) {
  const SwellingSphereCase c;
  const double b = c.radius, E = c.youngsModulus(), nu = c.poissonsRatio(), d = 1e-4 * b;
  const double scale = c.surfaceStrain * E;
  EXPECT_NEAR(swellingSphereExact(c, b).radialStress, 0.0, 1e-15 * scale);
  for (double r : {0.1 * b, 0.37 * b, 0.5 * b, 0.81 * b, 0.99 * b}) {
    const SwellingSphereExact x = swellingSphereExact(c, r), minus = swellingSphereExact(c, r - d),
                              plus = swellingSphereExact(c, r + d);
    const double dsrr = (plus.radialStress - minus.radialStress) / (2 * d);
    EXPECT_NEAR(dsrr + 2 * (x.radialStress - x.hoopStress) / r, 0.0, 1e-9 * scale / b) << r;
    const double err = (plus.radialDisplacement - minus.radialDisplacement) / (2 * d);
    const double ett = x.radialDisplacement / r, swelling = c.surfaceStrain * r * r / (b * b);
    const double lame = E / ((1 + nu) * (1 - 2 * nu));
    EXPECT_NEAR(lame * ((1 - nu) * err + 2 * nu * ett - (1 + nu) * swelling), x.radialStress,
                1e-8 * scale)
        << r;
    EXPECT_NEAR(lame * (ett + nu * err - (1 + nu) * swelling), x.hoopStress, 1e-8 * scale) << r;
  }
}

// Measured (swelling_sphere_study --quick): u_r 1.523e-2, 4.783e-3, 1.491e-3 (orders 1.67,
// 1.67); sigma_rr 0.399, 0.218, 0.120 (0.87, 0.86); sigma_tt 0.234, 0.153, 0.0953 (0.62, 0.68);
// 4 Newton iterations each. A 1% error in the swelling strain or 5% in K or G (through Poisson's
// ratio) puts the 16-cell u_r error above 5e-3.
TEST(SwellingSphere, ImplicitConvergesToTheClosedForm) {
  SwellingSphereResult coarser;
  for (int cells : swellingSphereQuickCells()) {
    SwellingSphereCase c;
    c.cells = cells;
    c.threads = 1;  // the machine is shared: OpenMP's waiting threads would compete
    const SwellingSphereResult r = runSwellingSphere(c);
    std::printf(
        "%2d cells, %5zu particles: u_r %.3e, sigma_rr %.3e, sigma_tt %.3e, Newton %ld, "
        "Krylov %ld, %.2f s\n",
        cells, r.particles, r.radialDisplacementError, r.radialStressError, r.hoopStressError,
        r.newtonIterations, r.krylovIterations, r.wallSeconds);
    EXPECT_EQ(r.steps, 1);
    EXPECT_LE(r.newtonIterations, 6) << cells;
    if (coarser.particles > 0) {
      const double ratio = std::log(coarser.h / r.h);
      EXPECT_GT(std::log(coarser.radialDisplacementError / r.radialDisplacementError) / ratio, 1.5)
          << cells;
      EXPECT_GT(std::log(coarser.radialStressError / r.radialStressError) / ratio, 0.75) << cells;
      EXPECT_GT(std::log(coarser.hoopStressError / r.hoopStressError) / ratio, 0.5) << cells;
    }
    coarser = r;
  }
  EXPECT_EQ(coarser.cells, 16);
  EXPECT_LT(coarser.radialDisplacementError, 1.65e-3);
  EXPECT_LT(coarser.radialStressError, 0.13);
  EXPECT_LT(coarser.hoopStressError, 0.105);
  EXPECT_LT(coarser.tangentialDisplacement, 0.03);  // 0.022
}

// Without the hourglass stabilization (which only the implicit step has) both paths solve the
// same discrete equilibrium. The explicit run, damped at 5 c/b, reaches it in 20 b/c (321 steps).
// Measured differences: u_r 8.6e-6, sigma_rr 4.4e-4, sigma_tt 2.7e-4.
TEST(SwellingSphere, ExplicitDampedToRestMatchesTheImplicitStep) {
  SwellingSphereCase c;
  c.cells = 8;
  c.threads = 1;
  c.hourglassStabilization = 0;
  const SwellingSphereResult implicitRun = runSwellingSphere(c);
  c.integrator = "explicit";
  const double bOverC = c.radius / c.waveSpeed();
  c.damping = 5 / bOverC;
  c.endTime = 20 * bOverC;
  const SwellingSphereResult explicitRun = runSwellingSphere(c);
  EXPECT_EQ(explicitRun.steps, 321);
  EXPECT_LT(relativeDifference(explicitRun.ur, implicitRun.ur), 2e-5);
  EXPECT_LT(relativeDifference(explicitRun.srr, implicitRun.srr), 1e-3);
  EXPECT_LT(relativeDifference(explicitRun.stt, implicitRun.stt), 6e-4);
}

}  // namespace
}  // namespace anode
