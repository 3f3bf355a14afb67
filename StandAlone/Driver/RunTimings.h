// The timings a run prints at its end (sus): per task the slowest rank's seconds, the steps per
// rule that set dt, the solver's counts, particle-steps per second, communication and peak memory.
#pragma once

#include <array>

#include "Core/Parallel/Communicator.h"
#include "StandAlone/Driver/DataArchiver.h"

namespace anode {

class Integrator;
class MPM;

// The run's counts the timings are of.
struct RunCounts {
  long step = 0;
  double t = 0;
  bool restarted = false;                    // this process continued a run from a checkpoint
  long firstStepOfThisProcess = 0;           // the step it started from (a restart's)
  std::array<long, kDtRules> stepsByRule{};  // steps of this process's run per DtRule
  // Particle-steps of every rank: since step 0, restarts included, and of this process's steps.
  double particleSteps = 0, particleStepsOfThisProcess = 0;
  double wallSeconds = 0;         // of this process's time loop
  double earlierWallSeconds = 0;  // of the runs before a restart
};

// Prints the timings on rank 0's stderr (each task's time that of the slowest rank).
void printTimings(Collective, const RunCounts& run, const MPM& mpm, const Integrator& integrator);

}  // namespace anode
