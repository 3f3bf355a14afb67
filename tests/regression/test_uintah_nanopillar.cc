// Pins the comparison with today's Uintah on its nightly NanoPillar test (NanoPillar2D_FBC_Sym,
// unmodified): at t = 9.90e5 us (its step 818) Uintah has 1036 particles (12 split into 4), mean
// c 0.132 over particles and max c 0.741; it reaches maxTime in 832 steps.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "StandAlone/Driver/Simulation.h"

namespace anode {
namespace {

TEST(UintahNanoPillar2D, MatchesUintahAtTheLastReportedTime) {
  const std::string input =
      std::string(ANODE_SOURCE_DIR) + "/../shared/inputs/uintah/NanoPillar2D_FBC_Sym.ups";
  if (!std::filesystem::exists(input)) GTEST_SKIP() << "shared inputs not present: " << input;
  RunOptions options;
  options.input = input;
  options.progress = false;
  Simulation sim(options);
  while (sim.time() < 9.90e5) sim.advance();
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  double sum = 0, cmax = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    sum += diffusionParticles(p).concentration[i];
    cmax = std::max(cmax, diffusionParticles(p).concentration[i]);
  }
  std::printf("t = %.4e us, step %ld: %zu particles, mean c %.4f, max c %.4f\n", sim.time(),
              sim.step(), p.count(), sum / p.count(), cmax);
  EXPECT_NEAR(static_cast<double>(p.count()), 1036.0, 3 * 3.0);  // within 3 splits
  EXPECT_NEAR(sum / p.count(), 0.132, 0.03 * 0.132);
  EXPECT_NEAR(cmax, 0.741, 0.02 * 0.741);
  while (sim.time() < sim.timeControl().maxTime) sim.advance();
  // dt is diffusion-limited, dt ~ exp(-7.9 c_max): 1% in c_max moves the step count by ~8%.
  std::printf("maxTime reached at step %ld\n", sim.step());
  EXPECT_NEAR(static_cast<double>(sim.step()), 832.0, 0.12 * 832);
}

}  // namespace
}  // namespace anode
