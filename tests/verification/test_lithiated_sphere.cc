// The quasi-static path's diffusion and swelling together against closed forms: the lithiated
// sphere (StandAlone/Studies/LithiatedSphere.h, Crank's constant-flux sphere and Timoshenko &
// Goodier's stresses) at 4 and 8 cells per radius, with each <swelling_strain>.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "StandAlone/Studies/LithiatedSphere.h"

namespace anode {
namespace {

// The closed forms solve the problem: the surface flux D dc/dr = J, the mean c = 3 J t / b (the
// lithium taken up), equilibrium d sigma_rr/dr + 2 (sigma_rr - sigma_tt)/r = 0 and a free
// surface, by central differences.
TEST(LithiatedSphereExact, SolvesTheConstantFluxSphere) {
  const LithiatedSphereCase c;
  const LithiatedSphereSolution exact(c);
  const double b = c.radius, d = 1e-4 * b, t = c.endTime;
  const double gradient = (exact.concentration(b) - exact.concentration(b - d)) / d;
  EXPECT_NEAR(c.diffusivity * gradient / c.flux, 1.0, 1e-3);
  double lithium = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * b / n;
    lithium += exact.concentration(r) * 3 * r * r / (b * b * b) * (b / n);
  }
  EXPECT_NEAR(lithium / (3 * c.flux * t / b), 1.0, 1e-6);
  const double scale = std::abs(exact.at(b).hoopStress);
  EXPECT_NEAR(exact.at(b).radialStress, 0.0, 1e-12 * scale);
  for (double r : {0.1 * b, 0.37 * b, 0.5 * b, 0.81 * b, 0.99 * b}) {
    const double dsrr = (exact.at(r + d).radialStress - exact.at(r - d).radialStress) / (2 * d);
    const LithiatedSphereExact x = exact.at(r);
    EXPECT_NEAR(dsrr + 2 * (x.radialStress - x.hoopStress) / r, 0.0, 1e-5 * scale / b) << r;
  }
}

// Measured (lithiated_sphere_study --quick): c 3.37e-2, 1.40e-2 (order 1.27) with either
// swelling; particle dc: sigma_rr 0.615, 0.279 (1.14), sigma_tt 0.420, 0.210 (1.00); cell means:
// sigma_rr 0.426, 0.233 (0.87), sigma_tt 0.505, 0.275 (0.88). 7 steps, 32-34 Newton iterations.
TEST(LithiatedSphere, DiffusionAndSwellingConvergeToTheClosedForms) {
  for (const char* swelling : {"particle", "cell_mean"}) {
    LithiatedSphereResult coarser;
    for (int cells : {4, 8}) {
      LithiatedSphereCase c;
      c.cells = cells;
      c.swellingStrain = swelling;
      c.threads = 1;  // the machine is shared: OpenMP's waiting threads would compete
      const LithiatedSphereResult r = runLithiatedSphere(c);
      std::printf("%s, %d cells, %zu particles: c %.3e, sigma_rr %.3e, sigma_tt %.3e, %ld steps\n",
                  swelling, cells, r.particles, r.concentrationError, r.radialStressError,
                  r.hoopStressError, r.steps);
      EXPECT_NEAR(r.finalTime, c.endTime, 1e-12) << swelling;
      if (coarser.particles > 0) {
        const double ratio = std::log(coarser.h / r.h);
        EXPECT_GT(std::log(coarser.concentrationError / r.concentrationError) / ratio, 1.1);
        EXPECT_GT(std::log(coarser.radialStressError / r.radialStressError) / ratio, 0.75);
        EXPECT_GT(std::log(coarser.hoopStressError / r.hoopStressError) / ratio, 0.75);
        EXPECT_LT(r.concentrationError, 0.015) << swelling;
        EXPECT_LT(r.radialStressError, 0.3) << swelling;
        EXPECT_LT(r.hoopStressError, 0.3) << swelling;
      }
      coarser = r;
    }
  }
}

}  // namespace
}  // namespace anode
