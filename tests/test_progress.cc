// Pins the progress line's fraction done (StandAlone/Driver/Progress.h), which its ETA
// extrapolates: by simulated time or by steps, whichever limit ends the run first, counted from
// this run's start (a restart's checkpoint), not from the simulation's; and its pace, that of the
// last minutes rather than the run's average.
#include <gtest/gtest.h>

#include "StandAlone/Driver/Progress.h"

namespace anode {
namespace {

TEST(Progress, FractionFollowsTheLimitThatEndsTheRun) {
  const ProgressReporter byTime(0, 10, 0, 0);
  EXPECT_DOUBLE_EQ(byTime.fractionDone(5, 2.5), 0.25);
  // --max-timesteps 200 long before maxTime: the steps say how far the run is.
  const ProgressReporter bySteps(0, 1e6, 0, 200);
  EXPECT_DOUBLE_EQ(bySteps.fractionDone(50, 1.0), 0.25);
  EXPECT_DOUBLE_EQ(bySteps.fractionDone(200, 4.0), 1.0);
}

TEST(Progress, ARestartCountsFromItsCheckpoint) {
  // Restarted at step 600 (t = 6) of a run limited to 1000 steps and t = 100: one step in, the
  // run is 1/400 done, not 601/1000 (which made the ETA near 0 s).
  const ProgressReporter restarted(6, 100, 600, 1000);
  EXPECT_DOUBLE_EQ(restarted.fractionDone(601, 6.01), 1.0 / 400);
  EXPECT_DOUBLE_EQ(restarted.fractionDone(800, 8), 0.5);
}

// A run that had the machine to itself only after ten minutes of sharing it: five minutes later
// the line gives the pace of the last minutes, not the whole run's average (200 particle-steps/s
// here, an ETA twice as long).
TEST(Progress, PaceIsThatOfTheLastMinutes) {
  ProgressReporter run(0, 100, 0, 0);
  ProgressReporter::Estimate pace{};
  double done = 0, particleSteps = 0;
  for (int second = 1; second <= 900; ++second) {
    const bool shared = second <= 600;
    done += shared ? 1e-4 : 4e-4;
    particleSteps += shared ? 100 : 400;
    pace = run.estimate(second, done, particleSteps);
  }
  EXPECT_NEAR(pace.particleStepsPerSecond, 400, 1e-9);
  EXPECT_NEAR(pace.secondsLeft, (1 - 0.18) / 4e-4, 1e-6);
}

TEST(Progress, FirstMinuteIsMeasuredFromTheStart) {
  ProgressReporter run(0, 100, 0, 0);
  EXPECT_LT(run.estimate(0, 0, 0).secondsLeft, 0);  // nothing done: not known yet
  run.estimate(10, 0.01, 1000);
  const ProgressReporter::Estimate pace = run.estimate(30, 0.05, 6000);
  EXPECT_DOUBLE_EQ(pace.particleStepsPerSecond, 200);
  EXPECT_NEAR(pace.secondsLeft, 30 * 0.95 / 0.05, 1e-9);
}

}  // namespace
}  // namespace anode
