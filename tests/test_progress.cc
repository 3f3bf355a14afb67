// Pins the progress line's fraction done (StandAlone/Driver/Progress.h), which its ETA
// extrapolates: by simulated time or by steps, whichever limit ends the run first, counted from
// this run's start (a restart's checkpoint), not from the simulation's; and its pace, that of the
// last minutes rather than the run's average; a long step's own lines; long ETAs in days and
// years; and the setup's forecast of the steps (StepForecast.h) with its guess at a density typed
// in kg/m^3.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "Core/Util/StepActivity.h"
#include "StandAlone/Driver/Progress.h"
#include "StandAlone/Driver/StepForecast.h"

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

// A step running longer than the watch interval gets lines of its own, naming what it is doing
// (its phases' notes); none after finish() until the next step, and none for a short step.
TEST(Progress, ALongStepSaysWhatItIsDoing) {
  std::FILE* out = std::tmpfile();
  ASSERT_NE(out, nullptr);
  {
    ProgressReporter run(0, 100, 12, 0, 0.2, out);
    noteStepActivity(0, "Newton iteration", 4);
    noteStepActivity(1, "Krylov iteration", 230);
    std::this_thread::sleep_for(std::chrono::milliseconds(1000));
    run.finish();
    noteStepActivity(0, "diffusion sub-step", 7);  // idle: not shown
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
  }
  std::rewind(out);
  std::string text;
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, out)) text += buffer;
  std::fclose(out);
  EXPECT_NE(text.find("step 13 under way for 0s: Newton iteration 4, Krylov iteration 230\n"),
            std::string::npos)
      << text;
  const size_t lines = static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
  EXPECT_GE(lines, 2u) << text;  // one every 0.2 s from 0.2 s on, each up to 0.05 s late
  EXPECT_LE(lines, 5u) << text;
  EXPECT_EQ(text.find("diffusion sub-step"), std::string::npos) << text;
  // Level 0 clears level 1.
  noteStepActivity(1, "Krylov iteration", 3);
  noteStepActivity(0, "RKL2 stage", 2);
  EXPECT_EQ(describeStepActivity(), "RKL2 stage 2");
  clearStepActivity();
  EXPECT_EQ(describeStepActivity(), "");
}

// A run of 1e11 steps shows an ETA in years, not "?" (the ETA of a step that moves the run by
// 1e-11 of its time).
TEST(Progress, LongEtasAreShownInDaysAndYears) {
  EXPECT_EQ(durationText(-1), "?");
  EXPECT_EQ(durationText(42), "42s");
  EXPECT_EQ(durationText(185), "3m05s");
  EXPECT_EQ(durationText(5 * 3600 + 7 * 60), "5h07m");
  EXPECT_EQ(durationText(12 * 86400), "12 days");
  EXPECT_EQ(durationText(3.4e3 * 365.25 * 86400), "3.4e+03 years");
}

StepForecastInput sphere(double density, double dt) {
  StepForecastInput in;
  in.maxTime = 2e6;
  in.dt = dt;
  in.limit = "mechanics (Eq. 43)";
  in.mechanicsLimited = true;
  in.cellSize = 0.0025;  // um
  in.densities = {{"material 0 (silicon)", density}};
  return in;
}

// The silicon sphere with its density typed in kg/m^3 (2330): dt 2.3e-6 us, 8.6e11 steps; the
// note names the guess. At the raised density of the input, no note.
TEST(StepForecast, OutOfReachStepsNameTheDensityGuess) {
  const std::vector<std::string> typed = forecastSteps(sphere(2330, 2.319e-6));
  ASSERT_EQ(typed.size(), 2u);
  EXPECT_NE(typed[0].find("about 8.62e+11 steps to maxTime 2e+06"), std::string::npos) << typed[0];
  EXPECT_NE(typed[1].find("density 2330 of material 0 (silicon) looks like kg/m^3"),
            std::string::npos)
      << typed[1];
  EXPECT_NE(typed[1].find("2.33 pg/um^3"), std::string::npos) << typed[1];
  const std::vector<std::string> raised = forecastSteps(sphere(2.33e21, 370));
  ASSERT_EQ(raised.size(), 1u);
  EXPECT_NE(raised[0].find("about 5.41e+03 steps"), std::string::npos) << raised[0];
  // Out of reach at a density that is no kg/m^3 value: the note, without the guess.
  const std::vector<std::string> real = forecastSteps(sphere(2.33, 7e-8));
  ASSERT_EQ(real.size(), 2u);
  EXPECT_EQ(real[1].find("a guess"), std::string::npos) << real[1];
  // A step limit that ends the run first: no note.
  StepForecastInput limited = sphere(2330, 2.319e-6);
  limited.maxTimesteps = 100;
  const std::vector<std::string> stopped = forecastSteps(limited);
  ASSERT_EQ(stopped.size(), 1u);
  EXPECT_NE(stopped[0].find("the step limit 100 ends the run first"), std::string::npos);
}

// An implicit run's forecast says what its dt follows next: Newton's iterations, or under
// <error_tolerance> the error estimates.
TEST(StepForecast, ImplicitRunsSayWhatTheirDtFollows) {
  StepForecastInput in = sphere(2.33, 2e4);
  in.implicit = true;
  EXPECT_NE(forecastSteps(in)[0].find("(dt then follows Newton's iterations)"), std::string::npos);
  in.errorControlled = true;
  EXPECT_NE(forecastSteps(in)[0].find("(dt then follows the error estimates)"), std::string::npos);
}

}  // namespace
}  // namespace anode
