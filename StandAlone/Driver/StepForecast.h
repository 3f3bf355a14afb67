// The setup's forecast of a run's length: how many steps its first dt would take to maxTime, and
// when mechanics sets that dt and the count is out of reach, a guess at why (a density typed in
// kg/m^3 in an input whose lengths are in um), stated as a guess, never an error.
#pragma once

#include <string>
#include <vector>

namespace anode {

struct StepForecastInput {
  double startTime = 0, maxTime = 0;
  long maxTimesteps = 0;  // <max_Timesteps> or --max-timesteps, 0: none
  double dt = 0;          // the first step's
  std::string limit;      // what set it (StableTimestep::name)
  bool mechanicsLimited = false;
  bool implicit = false;         // dt then follows Newton's iterations and the change of c
  bool errorControlled = false;  // <error_tolerance>: dt then follows the error estimates
  double cellSize = 0;           // the grid's smallest spacing
  std::vector<std::pair<std::string, double>> densities;  // per material: its name, rho0
};

// Steps beyond which a run is called out of reach (about a day at 1e6 steps an hour).
constexpr double kStepsOutOfReach = 3e7;

// The lines setup prints: the forecast, and a note when the steps are out of reach.
std::vector<std::string> forecastSteps(const StepForecastInput& in);

}  // namespace anode
