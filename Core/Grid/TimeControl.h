// <Time> (UINTAH_UPS.md §2.2; Uintah reads it in Core/Grid/SimulationTime): when to stop, and
// the clamps on the step's dt (Components/MPM/TimestepController.h chooses it).
#pragma once

#include <optional>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct TimeControl {
  double initTime = 0, maxTime = 0;
  double deltMin = 0, deltMax = 0;
  double multiplier = 1;
  long maxTimesteps = 0;       // 0: no limit
  double maxDeltIncrease = 0;  // 0: no limit
  std::optional<double> deltInit;
  double initialDeltRange = 0;
  bool endAtMaxTimeExactly = false;
  bool clampTimeToOutput = false;  // a step that would pass an output time ends on it
  double maxWallTime = 0;          // seconds, 0: no limit

  static TimeControl fromInput(const PSNode& timeNode);

  // dt for the step starting at time t: `dt` clamped in Uintah's order (max increase, delt_min,
  // delt_max, initial cap, end time). previousDt <= 0 for the first.
  double clamp(double dt, double previousDt, double t) const;
};

}  // namespace anode
