// Progress of a long run: a rewritten status line on a terminal, plain periodic lines otherwise.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

namespace anode {

// Set in the environment of the ranks of the one-command mode (OwnRanks.h) when its stderr is a
// terminal: mpirun passes their stderr on to it, a line rewritten included.
constexpr const char* kProgressOnTerminal = "ANODE_PROGRESS_ON_TERMINAL";

// Seconds as the ETA shows them: 42s, 3m05s, 5h07m, 12 days, 3.4e+03 years; "?" if negative.
std::string durationText(double seconds);

class ProgressReporter {
 public:
  // The run starts here at (startTime, startStep) (a restart: the checkpoint's) and ends at
  // maxTime or maxSteps (0: no step limit), whichever comes first. A step running longer than
  // `watchSeconds` gets a line of its own every `watchSeconds` ("step 13 under way for 40s:
  // Newton iteration 4, Krylov iteration 230", StepActivity.h), from a thread that only reads.
  ProgressReporter(double startTime, double maxTime, long startStep, long maxSteps,
                   double watchSeconds = 10, std::FILE* out = stderr);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;
  // Called after every step; prints at most a few times per second (terminal) or every 10 s.
  // `limit` names what set dt.
  void update(long step, double time, double dt, const char* limit, double particleSteps,
              bool force = false);
  // Ends the status line (before other messages); the step watch waits for the next update.
  void finish();
  // The fraction of the run done at (step, time), which the ETA extrapolates.
  double fractionDone(long step, double time) const;

  // The speed of the last one to two minutes (of the whole run in its first minute), so that the
  // line follows a machine whose load changes: particle-steps per second, and the seconds left
  // at the pace the fraction done has moved meanwhile (negative: not known yet).
  struct Estimate {
    double particleStepsPerSecond, secondsLeft;
  };
  // At `seconds` after the start, with the fraction `done` and `particleSteps` of this process.
  Estimate estimate(double seconds, double done, double particleSteps);

 private:
  struct Sample {
    double seconds, done, particleSteps;
  };
  static constexpr double kWindowSeconds = 60;

  // Writes `line` as the status line (terminal) or a line of its own; mutex_ held.
  void show(const char* line);
  // The step watch's thread: a line about the step under way when it runs long.
  void watchSteps();

  double startTime_, maxTime_;
  long startStep_, maxSteps_;
  std::chrono::duration<double> watchInterval_;
  std::FILE* out_;
  bool terminal_;
  bool pending_ = false;
  std::chrono::steady_clock::time_point start_, last_;
  // The step watch: the step under way (lastStep_ + 1) started at stepStart_; no line while
  // idle_ (after finish()) and not before lastWatchLine_ + watchInterval_.
  std::mutex mutex_;
  std::condition_variable wake_;
  bool ending_ = false, idle_ = false;
  long lastStep_;
  std::chrono::steady_clock::time_point stepStart_, lastWatchLine_;
  std::thread watcher_;
  // The window's start (older_) and the sample that becomes it a minute later (newer_).
  Sample older_{0, 0, 0}, newer_{0, 0, 0};
};

}  // namespace anode
