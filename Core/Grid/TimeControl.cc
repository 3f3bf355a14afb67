#include "Core/Grid/TimeControl.h"

#include <algorithm>
#include <cstdio>
#include <string>

namespace anode {

TimeControl TimeControl::fromInput(const PSNode& time) {
  TimeControl tc;
  tc.initTime = time.require<double>("initTime");
  tc.maxTime = time.require<double>("maxTime");
  if (!(tc.maxTime > tc.initTime))
    time.requireChild("maxTime").fail("<maxTime> must exceed <initTime>");
  tc.deltMin = time.require<double>("delt_min");
  tc.deltMax = time.require<double>("delt_max");
  if (tc.deltMin < 0) time.requireChild("delt_min").fail("<delt_min> must be >= 0");
  if (!(tc.deltMax > 0)) time.requireChild("delt_max").fail("<delt_max> must be positive");
  if (tc.deltMin > tc.deltMax) time.requireChild("delt_min").fail("<delt_min> exceeds <delt_max>");
  tc.multiplier = time.require<double>("timestep_multiplier");
  if (!(tc.multiplier > 0 && tc.multiplier <= 1)) {
    char found[32];
    std::snprintf(found, sizeof found, "%g", tc.multiplier);
    time.requireChild("timestep_multiplier")
        .fail(
            "<timestep_multiplier> must be in (0, 1]: found " + std::string(found) +
            "; dt = multiplier x the stable time step (Eqs. 43-44), and a dt beyond the stable one "
            "makes the explicit update unstable (in 2-D and 3-D already above about 0.75, "
            "docs/stability.md)");
  }
  tc.maxTimesteps = time.get<int>("max_Timesteps", 0);
  if (tc.maxTimesteps < 0) time.requireChild("max_Timesteps").fail("<max_Timesteps> must be >= 0");
  tc.maxDeltIncrease = time.get<double>("max_delt_increase", 0.0);
  if (tc.maxDeltIncrease < 0)
    time.requireChild("max_delt_increase").fail("<max_delt_increase> must be >= 0");
  // delt_init 0 (Uintah's default) caps nothing.
  if (const PSNode init = time.child("delt_init")) {
    const double cap = init.value<double>();
    if (cap < 0) init.fail("<delt_init> must be >= 0");
    if (cap > 0) tc.deltInit = cap;
  }
  tc.initialDeltRange = time.get<double>("initial_delt_range", 0.0);
  tc.endAtMaxTimeExactly = time.get<bool>("end_at_max_time_exactly", false);
  tc.maxWallTime = time.get<double>("max_wall_time", 0.0);
  tc.clampTimeToOutput = time.get<bool>("clamp_time_to_output", false);
  // A restart goes on with the checkpoint's dt; 0, Uintah's default, asks for nothing else.
  if (const PSNode restartDelt = time.child("override_restart_delt"))
    if (restartDelt.value<double>() != 0)
      restartDelt.unsupported("<override_restart_delt> other than 0 (a restart keeps its dt)");
  return tc;
}

double TimeControl::clamp(double dt, double previousDt, double t) const {
  if (maxDeltIncrease > 0 && previousDt > 0) dt = std::min(dt, (1 + maxDeltIncrease) * previousDt);
  dt = std::max(dt, deltMin);
  dt = std::min(dt, deltMax);
  // The initial range ends at an absolute time, not initTime + range (Uintah).
  if (deltInit && t <= initialDeltRange) dt = std::min(dt, *deltInit);
  // A remainder below 1e-9 of the step (round-off in the sum of earlier steps) joins it: alone
  // it would be a step of round-off size, in which an implicit step's Newton has nothing to solve
  // but the last step's residual and fails.
  if (endAtMaxTimeExactly && t + dt * (1 + 1e-9) > maxTime) dt = maxTime - t;
  return dt;
}

}  // namespace anode
