// Pins <Time> (StandAlone/Driver/TimeControl.h): the step's dt from the stable one, clamped in
// Uintah's order, and the tags it accepts, refuses or leaves to a restart.
#include <gtest/gtest.h>

#include <string>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"
#include "StandAlone/Driver/TimeControl.h"

namespace anode {
namespace {

TimeControl read(const std::string& extra) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification>\n<Time>\n<maxTime>1</maxTime><initTime>0</initTime>\n"
      "<delt_min>1e-6</delt_min><delt_max>0.1</delt_max>\n"
      "<timestep_multiplier>0.5</timestep_multiplier>\n" +
          extra + "\n</Time>\n</Uintah_specification>",
      "time.ups");
  return TimeControl::fromInput(spec->root().requireChild("Time"));
}

TEST(TimeControl, TheStableStepTimesTheMultiplierWithinDeltMinAndDeltMax) {
  const TimeControl tc = read("");
  EXPECT_EQ(tc.nextTimestep(0.02, 0, 0), 0.01);
  EXPECT_EQ(tc.nextTimestep(1.0, 0, 0), 0.1);    // delt_max
  EXPECT_EQ(tc.nextTimestep(1e-8, 0, 0), 1e-6);  // delt_min
}

TEST(TimeControl, ClampsInUintahsOrder) {
  const TimeControl tc = read(
      "<max_delt_increase>0.5</max_delt_increase><delt_init>0.004</delt_init>"
      "<initial_delt_range>0.2</initial_delt_range>"
      "<end_at_max_time_exactly>true</end_at_max_time_exactly>");
  EXPECT_DOUBLE_EQ(tc.nextTimestep(0.1, 0.002, 0.5), 0.003);  // at most 1.5 x the previous step
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 0.1), 0.004);             // delt_init within the initial range
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 0.99), 1 - 0.99);         // ends at maxTime
  // A round-off remainder joins the step before it.
  const double almost = 1 - 0.05 - 1e-15;
  EXPECT_EQ(tc.nextTimestep(0.1, 0, almost), 1 - almost);
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 1 - 0.05 - 1e-6), 0.05);
}

TEST(TimeControl, InitialRangeEndsAtAnAbsoluteTimeAndZeroDeltInitCapsNothing) {
  TimeControl tc = read("<delt_init>0.004</delt_init><initial_delt_range>0.2</initial_delt_range>");
  tc.initTime = 0.5;  // a run starting after the range: no cap (Uintah: t + dt <= range)
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 0.6), 0.05);
  tc.initTime = 0;
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 0.2), 0.004);
  EXPECT_EQ(tc.nextTimestep(0.1, 0, 0.21), 0.05);
  EXPECT_EQ(read("<delt_init>0</delt_init>").nextTimestep(0.02, 0, 0), 0.01);
  EXPECT_THROW(read("<delt_init>-1</delt_init>"), InputError);
}

TEST(TimeControl, OverrideRestartDeltOnlyAsZero) {
  EXPECT_NO_THROW(read("<override_restart_delt>0</override_restart_delt>"));
  try {
    read("<override_restart_delt>1e-5</override_restart_delt>");
    FAIL() << "a nonzero <override_restart_delt> was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 6);
    EXPECT_NE(std::string(e.what()).find("<override_restart_delt> other than 0"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace anode
