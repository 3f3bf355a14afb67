// What a run prints once its setup is done (sus, rank 0's stderr): setup's time and peak memory
// (of the slowest and largest rank, and of the fastest and smallest), the particles and the grid,
// the ranks' boxes, the diffusion's notes and the forecast of the steps.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "Core/Parallel/Communicator.h"

namespace anode {

class MPM;

struct SetupFigures {
  size_t particles = 0;   // of every rank
  double imbalance = 1;   // particles per rank, largest over mean
  double seconds = 0;     // this rank's setup time
  double peakBytes = 0;   // and the peak memory it left
  std::string directory;  // the output's
};

// Prints the report; `forecast` (StepForecast.h) is needed on rank 0 only. One reduction of 4
// values on several ranks.
void printSetupReport(Collective, const MPM& mpm, const SetupFigures& figures,
                      const std::vector<std::string>& forecast);

}  // namespace anode
