#include "StandAlone/Driver/Progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string>

#include "Core/Util/StepActivity.h"

namespace anode {

std::string durationText(double s) {
  char buf[64];
  if (!(s >= 0)) return "?";
  if (s < 60)
    std::snprintf(buf, sizeof buf, "%.0fs", s);
  else if (s < 3600)
    std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  else if (s < 48 * 3600)
    std::snprintf(buf, sizeof buf, "%dh%02dm", int(s) / 3600, (int(s) % 3600) / 60);
  else if (s < 365.25 * 86400)
    std::snprintf(buf, sizeof buf, "%.0f days", s / 86400);
  else
    std::snprintf(buf, sizeof buf, "%.2g years", s / (365.25 * 86400));
  return buf;
}

ProgressReporter::ProgressReporter(double startTime, double maxTime, long startStep, long maxSteps,
                                   double watchSeconds, std::FILE* out)
    : startTime_(startTime),
      maxTime_(maxTime),
      startStep_(startStep),
      maxSteps_(maxSteps),
      watchInterval_(watchSeconds),
      out_(out),
      terminal_((out == stderr && ::isatty(STDERR_FILENO)) || std::getenv(kProgressOnTerminal)),
      start_(std::chrono::steady_clock::now()),
      last_(start_),
      lastStep_(startStep),
      stepStart_(start_),
      lastWatchLine_(start_) {
  clearStepActivity();
  watcher_ = std::thread([this] { watchSteps(); });
}

ProgressReporter::~ProgressReporter() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ending_ = true;
  }
  wake_.notify_one();
  watcher_.join();
}

void ProgressReporter::watchSteps() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!ending_) {
    wake_.wait_for(lock, std::min(watchInterval_ / 4, std::chrono::duration<double>(1.0)));
    const auto now = std::chrono::steady_clock::now();
    if (ending_ || idle_ || now - stepStart_ < watchInterval_ ||
        now - lastWatchLine_ < watchInterval_)
      continue;
    lastWatchLine_ = now;
    const std::string activity = describeStepActivity();
    const std::string line = "step " + std::to_string(lastStep_ + 1) + " under way for " +
                             durationText(std::chrono::duration<double>(now - stepStart_).count()) +
                             (activity.empty() ? "" : ": " + activity);
    show(line.c_str());
  }
}

void ProgressReporter::show(const char* line) {
  if (terminal_) {
    std::fprintf(out_, "\r%-100s", line);
    pending_ = true;
  } else {
    std::fprintf(out_, "%s\n", line);
  }
  std::fflush(out_);
}

double ProgressReporter::fractionDone(long step, double time) const {
  // Since this run's start (which a restart moves): by simulated time, or by steps when the
  // step limit comes first.
  double done = maxTime_ > startTime_ ? (time - startTime_) / (maxTime_ - startTime_) : 1.0;
  if (maxSteps_ > startStep_)
    done = std::max(done, double(step - startStep_) / double(maxSteps_ - startStep_));
  return std::min(done, 1.0);
}

ProgressReporter::Estimate ProgressReporter::estimate(double seconds, double done,
                                                      double particleSteps) {
  const Sample now{seconds, done, particleSteps};
  if (seconds - newer_.seconds >= kWindowSeconds) {
    older_ = newer_;
    newer_ = now;
  }
  const double span = seconds - older_.seconds;
  const double progressed = done - older_.done;
  return {span > 0 ? (particleSteps - older_.particleSteps) / span : 0.0,
          progressed > 0 ? span * (1 - done) / progressed : -1.0};
}

void ProgressReporter::update(long step, double time, double dt, const char* limit,
                              double particleSteps, bool force) {
  const auto now = std::chrono::steady_clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  clearStepActivity();
  lastStep_ = step;
  stepStart_ = lastWatchLine_ = now;
  idle_ = false;
  const double sinceLast = std::chrono::duration<double>(now - last_).count();
  if (!force && sinceLast < (terminal_ ? 0.25 : 10.0)) return;
  last_ = now;
  const Estimate pace = estimate(std::chrono::duration<double>(now - start_).count(),
                                 fractionDone(step, time), particleSteps);
  char line[256];
  std::snprintf(line, sizeof line,
                "step %ld  t = %.4e / %.4e  dt = %.3e (%s)  %.3e particle-steps/s  ETA %s", step,
                time, maxTime_, dt, limit, pace.particleStepsPerSecond,
                durationText(pace.secondsLeft).c_str());
  show(line);
}

void ProgressReporter::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (pending_) std::fprintf(out_, "\n");
  pending_ = false;
  idle_ = true;
}

}  // namespace anode
