// Flux boundary condition against Carslaw & Jaeger's slab solution (StandAlone/Studies/FluxSlab.h),
// at the quick resolutions of `flux_slab_study --quick`, and the lithium balance of the flux BC.
// Bounds are the values measured with timestep_multiplier 0.2 (docs/verification.md, "Flux
// boundary condition (Carslaw & Jaeger slab)") plus a margin of ~10 %; orders are asserted below
// the measured ones. Measured with the flux source G/m in the nodal c*
// (MPM::integrateConcentration; Uintah leaves it out), which halved the errors at the flux face.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "StandAlone/Studies/FluxSlab.h"

namespace {

using anode::FluxSlabCase;
using anode::FluxSlabResult;

double order(const FluxSlabResult& coarse, const FluxSlabResult& fine,
             double FluxSlabResult::*metric) {
  return std::log(coarse.*metric / fine.*metric) / std::log(double(fine.cells) / coarse.cells);
}

std::vector<FluxSlabResult> runQuick(const std::string& interpolator) {
  std::vector<FluxSlabResult> results;
  for (int cells : anode::fluxSlabQuickCells()) {
    FluxSlabCase c;
    c.cells = cells;
    c.interpolator = interpolator;
    c.threads = 1;  // a few dozen particles: one thread is fastest
    results.push_back(anode::runFluxSlab(c));
  }
  return results;
}

TEST(FluxSlabAnalytic, SatisfiesTheProblem) {
  const double J = 2, L = 3, D = 0.5, t = 4;
  // Insulated at x = 0, flux J in at x = L: D dc/dx = 0 and J (central differences).
  const double e = 1e-5;
  EXPECT_NEAR(
      D * (anode::fluxSlabAnalytic(e, t, J, L, D) - anode::fluxSlabAnalytic(-e, t, J, L, D)) /
          (2 * e),
      0.0, 1e-8);
  EXPECT_NEAR(D *
                  (anode::fluxSlabAnalytic(L + e, t, J, L, D) -
                   anode::fluxSlabAnalytic(L - e, t, J, L, D)) /
                  (2 * e),
              J, 1e-8);
  // The mean is J t / L (all the lithium that came in), by the midpoint rule on 2000 points.
  double mean = 0;
  for (int k = 0; k < 2000; ++k)
    mean += anode::fluxSlabAnalytic(L * (k + 0.5) / 2000, t, J, L, D) / 2000;
  EXPECT_NEAR(mean, J * t / L, 1e-6 * J * t / L);
  // c = 0 at t = 0 (the series converges slowly there: loose tolerance).
  EXPECT_NEAR(anode::fluxSlabAnalytic(0.3 * L, 0.0, J, L, D), 0.0, 1e-8);
  // dc/dt = D d2c/dx2 inside.
  const double x = 1.1, dt = 1e-4, dx = 1e-3;
  const double dcdt =
      (anode::fluxSlabAnalytic(x, t + dt, J, L, D) - anode::fluxSlabAnalytic(x, t - dt, J, L, D)) /
      (2 * dt);
  const double d2c =
      (anode::fluxSlabAnalytic(x + dx, t, J, L, D) - 2 * anode::fluxSlabAnalytic(x, t, J, L, D) +
       anode::fluxSlabAnalytic(x - dx, t, J, L, D)) /
      (dx * dx);
  EXPECT_NEAR(dcdt, D * d2c, 1e-5 * std::abs(dcdt));
}

TEST(RobinSlabAnalytic, SatisfiesTheProblem) {
  const double cs = 0.7, k = 3, L = 2, D = 0.5, t = 0.6;
  const auto c = [&](double x, double time) {
    return anode::robinSlabAnalytic(x, time, cs, k, L, D);
  };
  const double e = 1e-5;
  EXPECT_NEAR(D * (c(e, t) - c(-e, t)) / (2 * e), 0.0, 1e-8);  // insulated at x = 0
  // D dc/dx = k (c_s - c) at x = L.
  EXPECT_NEAR(D * (c(L + e, t) - c(L - e, t)) / (2 * e), k * (cs - c(L, t)), 1e-7);
  EXPECT_NEAR(c(0.4 * L, 0.0), 0.0, 1e-6);  // empty at t = 0 (slow series there)
  EXPECT_NEAR(c(0.4 * L, 1e3), cs, 1e-12);  // held at c_s in the end
  const double x = 1.3, dt = 1e-4, dx = 1e-3;
  const double dcdt = (c(x, t + dt) - c(x, t - dt)) / (2 * dt);
  const double d2c = (c(x + dx, t) - 2 * c(x, t) + c(x - dx, t)) / (dx * dx);
  EXPECT_NEAR(dcdt, D * d2c, 1e-5 * std::abs(dcdt));
}

// <mode>potentiostatic: the x+ face held at c_s = 0.5 through J = k (c_s - c) against the plane
// wall's series, at Bi = k L / D = 10 and at k = 1e6 (the surface held). Measured with the
// particle's half thickness in series with k (ExternalScalarFlux.cc, surfaceConductance).
TEST(PotentiostaticSlab, ConvergesToThePlaneWallSeries) {
  for (const char* interpolator : {"linear", "cpdi"})
    for (double k : {10.0, 1e6}) {
      std::vector<FluxSlabResult> r;
      for (int cells : anode::fluxSlabQuickCells()) {
        FluxSlabCase c;
        c.cells = cells;
        c.interpolator = interpolator;
        c.threads = 1;
        c.surfaceRate = k;
        r.push_back(anode::runFluxSlab(c));
        SCOPED_TRACE(std::string(interpolator) + ", k " + std::to_string(k) + ", " +
                     std::to_string(cells) + " cells");
        // The relaxation step bound: no particle passes c_s, none falls below its initial 0
        // (holding the flagged particle at c_s instead sent the next one to -7e-4).
        EXPECT_LE(r.back().maxConcentration, c.heldConcentration);
        EXPECT_GE(r.back().minConcentration, 0.0);
        EXPECT_LT(r.back().balanceError(), 1e-13);  // measured <= 6e-15
      }
      SCOPED_TRACE(std::string(interpolator) + ", k " + std::to_string(k));
      // Measured: Bi 10: L2 order 0.96, 1.13, 5.833e-3 at 32 cells; k 1e6: 1.05, 1.33, 5.162e-3.
      for (size_t i = 1; i < r.size(); ++i)
        EXPECT_GT(order(r[i - 1], r[i], &FluxSlabResult::l2Error), 0.85);
      EXPECT_LT(r.back().l2Error, 6.4e-3);
    }
}

class FluxSlab : public ::testing::TestWithParam<std::string> {};

TEST_P(FluxSlab, ConvergesToCarslawAndJaeger) {
  const std::vector<FluxSlabResult> r = runQuick(GetParam());
  ASSERT_EQ(r.size(), 3u);
  const FluxSlabCase base;
  for (const FluxSlabResult& x : r) {
    SCOPED_TRACE(GetParam() + ", " + std::to_string(x.cells) + " cells");
    EXPECT_EQ(x.particles, 2u * x.cells);  // res [2,1,1] filling [0, L] exactly
    EXPECT_EQ(x.fluxParticles, 1u);        // the particle next to x = L
    EXPECT_NEAR(x.finalTime, base.endTime(), 1e-12 * base.endTime());
    // J = 1e-6 keeps c below 6e-7 (measured 5.54e-7..5.63e-7), so R(c) = 1 to 1.5e-7 (measured
    // 1.38e-7..1.41e-7).
    EXPECT_LT(x.maxConcentration, 6e-7);
    EXPECT_LT(x.maxRestrictionDeviation, 1.5e-7);
    // The lithium that came in is J t A up to the restriction (measured -9.0e-8..-9.3e-8).
    EXPECT_LT(x.injectedVsExact, 0.0);
    EXPECT_GT(x.injectedVsExact, -x.maxRestrictionDeviation);
    EXPECT_GE(x.minConcentration, 0.0);  // no undershoot below the initial 0
    EXPECT_LT(x.balanceError(), 1e-13);  // round-off: measured 1.1e-16..8.9e-16
  }
  for (size_t i = 1; i < r.size(); ++i) {
    SCOPED_TRACE(GetParam() + ", " + std::to_string(r[i - 1].cells) + " -> " +
                 std::to_string(r[i].cells) + " cells");
    // Measured 1.46, 1.48: an O(h) error on the particles next to the flux face gives O(h^1.5).
    EXPECT_GT(order(r[i - 1], r[i], &FluxSlabResult::l2Error), 1.35);
    // Measured 0.94, 0.98: the largest error sits on the particle next to x = L.
    EXPECT_GT(order(r[i - 1], r[i], &FluxSlabResult::maxError), 0.9);
    // Measured 2.15, 2.03 away from the flux face (x <= L/2).
    EXPECT_GT(order(r[i - 1], r[i], &FluxSlabResult::interiorMaxError), 1.8);
  }
  // 32 cells, measured: L2 2.393e-3, max 9.059e-3 (at x = L - h/4), x <= L/2 8.680e-5 (before
  // G/m entered c*: 4.976e-3, 1.943e-2, 2.609e-4).
  const FluxSlabResult& finest = r.back();
  EXPECT_LT(finest.l2Error, 2.65e-3);
  EXPECT_LT(finest.maxError, 1.0e-2);
  EXPECT_LT(finest.interiorMaxError, 9.6e-5);
  EXPECT_NEAR(finest.maxErrorAt, 1.0 - 0.25 / 32, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(Interpolators, FluxSlab, ::testing::Values("linear", "gimp", "cpdi"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

TEST(FluxSlabInterpolators, AgreeForAlignedParticlesAtRest) {
  // Two particles per cell, aligned with the cells and never moving: each particle's domain lies
  // inside one cell, where the GIMP and (undeformed) CPDI weights reduce to the linear ones.
  FluxSlabCase c;
  c.cells = 16;
  c.threads = 1;
  const FluxSlabResult linear = anode::runFluxSlab(c);
  for (const char* interpolator : {"gimp", "cpdi"}) {
    c.interpolator = interpolator;
    const FluxSlabResult r = anode::runFluxSlab(c);
    ASSERT_EQ(r.c.size(), linear.c.size());
    for (size_t i = 0; i < r.c.size(); ++i)
      EXPECT_NEAR(r.c[i], linear.c[i], 1e-12 * linear.maxConcentration);
  }
}

TEST(FluxSlabThickness, ThreeDimensionalSlabMatchesTheOneCellThickOne) {
  // 2 x 2 cells in y and z (ndim 3): four particles carry the flux; same profile.
  for (const char* interpolator : {"linear", "cpdi"}) {
    SCOPED_TRACE(interpolator);
    FluxSlabCase c;
    c.cells = 16;
    c.interpolator = interpolator;
    c.threads = 1;
    const FluxSlabResult thin = anode::runFluxSlab(c);
    c.thickness = 2;
    const FluxSlabResult thick = anode::runFluxSlab(c);
    EXPECT_EQ(thick.particles, 4 * thin.particles);
    EXPECT_EQ(thick.fluxParticles, 4u);
    EXPECT_NEAR(thick.l2Error, thin.l2Error, 1e-9 * thin.l2Error);
    EXPECT_NEAR(thick.maxError, thin.maxError, 1e-9 * thin.maxError);
    EXPECT_NEAR(thick.injectedVsExact, thin.injectedVsExact, 1e-12);
  }
}

// Lithium balance of the flux BC without Dirichlet conditions: the P2G/G2P transfer and the
// divergence conserve sum m c, so sum_p m_p c_p(t) - sum m c(0) = sum over steps of
// dt sum_p m_p rate_p, rate_p = p.externalScalarFlux at the start of the step. Here the flux is
// large (c up to 0.47, so the restriction acts: 1 - R(c) up to 0.16), varies in time and enters
// through both x faces. The 3-D slab runs on 2 threads, for the threaded scatter (per-thread
// grid buffers summed in thread order). Measured 6.5e-16 (3-D) and 8.6e-16 (one cell thick).
class LithiumBalance : public ::testing::TestWithParam<std::string> {};

TEST_P(LithiumBalance, HoldsToRoundOff) {
  for (int thickness : {1, 2}) {
    SCOPED_TRACE(GetParam() + ", thickness " + std::to_string(thickness));
    FluxSlabCase c;
    c.cells = 16;
    c.thickness = thickness;
    c.interpolator = GetParam();
    c.loadCurve = {{0.0, 0.2}, {0.1, 1.2}, {0.25, 0.8}};
    c.fluxAtZero = 0.3;
    c.threads = thickness;
    const FluxSlabResult r = anode::runFluxSlab(c);
    EXPECT_EQ(r.fluxParticles, 2u * thickness * thickness);  // both faces
    EXPECT_GT(r.maxRestrictionDeviation, 0.1) << "the restriction must act";
    EXPECT_GT(r.injected, 0.0);
    EXPECT_GT(r.lithium - r.lithium0, 0.0);
    EXPECT_LT(r.balanceError(), 1e-12)
        << "sum m c gained " << r.lithium - r.lithium0 << ", injected " << r.injected;
  }
}

INSTANTIATE_TEST_SUITE_P(Interpolators, LithiumBalance, ::testing::Values("linear", "cpdi"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param;
                         });

}  // namespace
