// Wall-clock time per named task of the step, for the end-of-run report.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace anode {

class TaskTimers {
 public:
  // Returns the index of the named task, adding it on first use.
  int task(const std::string& name);
  void add(int task, double seconds) { seconds_[task] += seconds; }
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<double>& seconds() const { return seconds_; }

 private:
  std::vector<std::string> names_;
  std::vector<double> seconds_;
};

// Adds the lifetime of the scope to one task.
class ScopedTimer {
 public:
  ScopedTimer(TaskTimers& timers, int task)
      : timers_(timers), task_(task), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    timers_.add(task_,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }

 private:
  TaskTimers& timers_;
  int task_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace anode
