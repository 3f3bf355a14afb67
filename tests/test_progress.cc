// Pins the progress line's fraction done (StandAlone/Driver/Progress.h), which its ETA
// extrapolates: by simulated time or by steps, whichever limit ends the run first, counted from
// this run's start (a restart's checkpoint), not from the simulation's.
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

}  // namespace
}  // namespace anode
