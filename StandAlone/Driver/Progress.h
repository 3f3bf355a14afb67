// Progress of a long run: a rewritten status line on a terminal, plain periodic lines otherwise.
#pragma once

#include <chrono>
#include <cstdio>

namespace anode {

class ProgressReporter {
 public:
  ProgressReporter(double initTime, double maxTime, long maxSteps);
  // Called after every step; prints at most a few times per second (terminal) or every 10 s.
  void update(long step, double time, double dt, double particleSteps, bool force = false);
  void finish();

 private:
  double initTime_, maxTime_;
  long maxSteps_;
  bool terminal_;
  bool pending_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace anode
