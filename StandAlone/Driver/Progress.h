// Progress of a long run: a rewritten status line on a terminal, plain periodic lines otherwise.
#pragma once

#include <chrono>
#include <cstdio>

namespace anode {

class ProgressReporter {
 public:
  // The run starts here at (startTime, startStep) (a restart: the checkpoint's) and ends at
  // maxTime or maxSteps (0: no step limit), whichever comes first.
  ProgressReporter(double startTime, double maxTime, long startStep, long maxSteps);
  // Called after every step; prints at most a few times per second (terminal) or every 10 s.
  // `limit` names what set dt.
  void update(long step, double time, double dt, const char* limit, double particleSteps,
              bool force = false);
  void finish();
  // The fraction of the run done at (step, time), which the ETA extrapolates.
  double fractionDone(long step, double time) const;

 private:
  double startTime_, maxTime_;
  long startStep_, maxSteps_;
  bool terminal_;
  bool pending_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace anode
