#include "StandAlone/Driver/RunTimings.h"

#include <sys/resource.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"
#include "Core/Util/InstructionSet.h"

namespace anode {

void printTimings(Collective every, const RunCounts& run, const MPM& mpm,
                  const Integrator& integrator) {
  // Per task the slowest rank's time (the others wait for it at the next exchange).
  const TaskTimers& timers = mpm.timers();
  std::vector<double> seconds = timers.seconds();
  collective::maximum(every, seconds.data(), static_cast<int>(seconds.size()));
  const size_t particles = static_cast<size_t>(
      collective::sum(every, static_cast<int64_t>(countParticles(mpm.materials()))));
  const double imbalance = mpm.layout().imbalance(every);
  const long collectiveCalls = Communicator::collectiveCalls();  // before this summary's own
  double communication[2] = {Communicator::bytesSent(), Communicator::communicationSeconds()};
  collective::sum(every, communication, 1);
  collective::maximum(every, communication + 1, 1);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double ownPeak = usage.ru_maxrss * 1024.0;  // Linux: kilobytes
  const double peakBytes = collective::maximum(every, ownPeak),
               allPeaks = collective::sum(every, ownPeak);
  if (!Communicator::isRoot()) return;
  double total = 0;
  for (double v : seconds) total += v;
  std::fprintf(stderr, "sus: %ld steps, t = %.6e, %zu particles, wall %.3f s", run.step, run.t,
               particles, run.wallSeconds);
  if (run.restarted)
    std::fprintf(stderr, " (after the restart: %ld steps, from step %ld)",
                 run.step - run.firstStepOfThisProcess, run.firstStepOfThisProcess);
  std::fprintf(stderr, "\n");
  std::fprintf(stderr, "  %-34s %10s %7s\n", "task", "seconds", "share");
  for (size_t i = 0; i < timers.names().size(); ++i)
    std::fprintf(stderr, "  %-34s %10.3f %6.1f%%\n", timers.names()[i].c_str(), seconds[i],
                 total > 0 ? 100 * seconds[i] / total : 0.0);
  std::string limits;
  for (int rule = 0; rule < kDtRules; ++rule)
    if (run.stepsByRule[rule] > 0)
      limits += (limits.empty() ? "" : ", ") + std::string(dtRuleName(rule)) + " " +
                std::to_string(run.stepsByRule[rule]);
  if (!limits.empty()) std::fprintf(stderr, "  steps whose dt the limit set: %s\n", limits.c_str());
  const std::string solver = integrator.summary(run.step - run.firstStepOfThisProcess);
  if (!solver.empty()) std::fprintf(stderr, "  %s\n", solver.c_str());
  std::fprintf(stderr, "  instruction set: %s\n", instructionSet().c_str());
  // This process's steps over its wall time; after a restart also the whole run's (the time
  // of each earlier process up to its last checkpoint, as the steps).
  std::fprintf(stderr, "  particle-steps per second: %.4e\n",
               run.wallSeconds > 0 ? run.particleStepsOfThisProcess / run.wallSeconds : 0.0);
  if (run.restarted) {
    const double wholeWall = run.earlierWallSeconds + run.wallSeconds;
    std::fprintf(stderr,
                 "  since step 0, with the runs before the restart: %.4e particle-steps in "
                 "%.3f s, %.4e per second\n",
                 run.particleSteps, wholeWall, wholeWall > 0 ? run.particleSteps / wholeWall : 0.0);
  }
  if (Communicator::size() > 1)
    std::fprintf(stderr,
                 "  %d ranks: particles per rank max/mean %.3f; sent %.4g bytes in all, %.4g per "
                 "step; communication at most %.3f s on a rank; %ld collective calls, %.1f per "
                 "step\n",
                 Communicator::size(), imbalance, communication[0],
                 run.step > run.firstStepOfThisProcess
                     ? communication[0] / (run.step - run.firstStepOfThisProcess)
                     : 0.0,
                 communication[1], collectiveCalls,
                 run.step > run.firstStepOfThisProcess ? static_cast<double>(collectiveCalls) /
                                                             (run.step - run.firstStepOfThisProcess)
                                                       : 0.0);
  std::fprintf(
      stderr, "  peak memory: %.1f MB, %.0f bytes per particle%s\n", peakBytes / 1e6,
      allPeaks / std::max<size_t>(particles, 1),
      Communicator::size() > 1
          ? " (the largest rank's peak; per particle: every rank's peak over all particles)"
          : "");
}

}  // namespace anode
