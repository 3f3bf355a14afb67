// Pins LoadCurve (Core/Util/LoadCurve.h, UINTAH_UPS.md §2.9): linear between points, extrapolated
// before the first time from the first interval, the last load after the last time, and the
// input checks of <load_curve>.
#include <gtest/gtest.h>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/Errors.h"
#include "Core/Util/LoadCurve.h"

namespace anode {
namespace {

TEST(LoadCurve, InterpolatesLinearlyBetweenPoints) {
  const LoadCurve c({0, 2, 6}, {1, 5, -3});
  EXPECT_EQ(c.at(0), 1.0);
  EXPECT_EQ(c.at(1), 3.0);  // halfway from 1 to 5
  EXPECT_EQ(c.at(2), 5.0);
  EXPECT_EQ(c.at(5), -1.0);  // three quarters from 5 to -3
}

TEST(LoadCurve, HoldsTheLastLoadAndExtrapolatesBeforeTheFirstTime) {
  const LoadCurve c({1, 3}, {2, 6});
  EXPECT_EQ(c.at(3), 6.0);
  EXPECT_EQ(c.at(100), 6.0);
  EXPECT_EQ(c.at(0), 0.0);  // the first interval's line, slope 2, continued back to t = 0
  const LoadCurve single({0}, {7});
  EXPECT_EQ(single.at(-1), 7.0);
  EXPECT_EQ(single.at(5), 7.0);
}

TEST(LoadCurve, AStepIsTwoCloseTimePoints) {
  // A sign change over a short interval: before and after it the loads hold exactly.
  const LoadCurve c({0, 10, 10.001, 100}, {1, 1, -1, -1});
  EXPECT_EQ(c.at(5), 1.0);
  EXPECT_EQ(c.at(10), 1.0);
  EXPECT_NEAR(c.at(10.0005), 0.0, 1e-9);
  EXPECT_EQ(c.at(50), -1.0);
}

TEST(LoadCurve, SegmentsStartAtTheTimePoints) {
  // A cycle: charge to 10, a ramp to the discharge, discharge to 100.
  const LoadCurve c({0, 10, 10.001, 100}, {1, 1, -1, -1});
  EXPECT_EQ(c.segmentAt(0), 1u);
  EXPECT_EQ(c.segmentAt(9.99), 1u);
  EXPECT_EQ(c.segmentAt(10), 2u);  // a step ending on a time point is in the next segment
  EXPECT_EQ(c.segmentAt(10 * (1 - 1e-13)), 2u);
  EXPECT_EQ(c.segmentAt(10.0005), 2u);
  EXPECT_EQ(c.segmentAt(50), 3u);
  EXPECT_EQ(c.segmentAt(100), 4u);
  EXPECT_EQ(LoadCurve({1, 3}, {2, 6}).segmentAt(0.5), 0u);
}

TEST(LoadCurve, ReadFromInputWithItsChecks) {
  const auto read = [](const std::string& points) {
    auto spec = ProblemSpec::fromText(
        "<Uintah_specification>\n<load_curve>" + points + "</load_curve>\n</Uintah_specification>",
        "curve.ups");
    return LoadCurve::fromInput(spec->root().requireChild("load_curve"));
  };
  const LoadCurve c = read(
      "<time_point><time>0</time><load>2</load></time_point>"
      "<time_point><time>4</time><load>10</load></time_point>");
  EXPECT_EQ(c.at(1), 4.0);
  ASSERT_EQ(c.times().size(), 2u);
  EXPECT_THROW(read(""), InputError);
  EXPECT_THROW(read("<time_point><time>-1</time><load>2</load></time_point>"), InputError);
  EXPECT_THROW(read("<time_point><time>1</time><load>2</load></time_point>"
                    "<time_point><time>1</time><load>3</load></time_point>"),
               InputError);
  EXPECT_THROW(LoadCurve({0, 1}, {1}), std::invalid_argument);
}

}  // namespace
}  // namespace anode
