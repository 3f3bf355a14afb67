#include "StandAlone/Driver/Progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <string>

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

ProgressReporter::ProgressReporter(double startTime, double maxTime, long startStep, long maxSteps)
    : startTime_(startTime),
      maxTime_(maxTime),
      startStep_(startStep),
      maxSteps_(maxSteps),
      terminal_(::isatty(STDERR_FILENO) || std::getenv(kProgressOnTerminal)),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

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
  if (terminal_) {
    std::fprintf(stderr, "\r%-100s", line);
    pending_ = true;
  } else {
    std::fprintf(stderr, "%s\n", line);
  }
  std::fflush(stderr);
}

void ProgressReporter::finish() {
  if (pending_) std::fprintf(stderr, "\n");
  pending_ = false;
}

}  // namespace anode
