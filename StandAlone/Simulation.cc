#include "StandAlone/Simulation.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <sstream>

#include "StandAlone/Progress.h"

namespace anode {

Simulation::Simulation(const RunOptions& options)
    : options_(options), spec_(std::make_unique<ProblemSpec>(options.input, options.ignoreUnsupported)) {
  setup();
}

Simulation::Simulation(const std::string& text, const std::string& name, const RunOptions& options)
    : options_(options), spec_(ProblemSpec::fromText(text, name, options.ignoreUnsupported)) {
  setup();
}

void Simulation::setup() {
  PSNode root = spec_->root();
  time_ = TimeControl::fromInput(root.requireChild("Time"));
  mpm_.problemSetup(root, time_.initTime, time_.maxTime);
  archiver_ = DataArchiver::fromInput(root.requireChild("DataArchiver"), mpm_.flags().doScalarDiffusion);
  scenes_ = SceneOutput::fromInput(root, time_, mpm_);
  spec_->checkAllUsed();
  if (options_.maxTimesteps > 0 &&
      (time_.maxTimesteps == 0 || options_.maxTimesteps < time_.maxTimesteps))
    time_.maxTimesteps = options_.maxTimesteps;
  t_ = time_.initTime;
  dt_ = time_.nextTimestep(mpm_.computeStableTimestep(), 0.0, t_);
}

void Simulation::advance() {
  try {
    mpm_.timeAdvance(t_, dt_);
    ScopedTimer timer(mpm_.timers(), mpm_.timers().task("stateChecks"));
    checks_.afterStep(mpm_);
  } catch (const SimulationError& e) {
    std::ostringstream s;
    s << "step " << step_ + 1 << ", t = " << t_ + dt_ << ": " << e.what();
    throw SimulationError(s.str());
  }
  t_ += dt_;
  ++step_;
  particleSteps_ += static_cast<double>(mpm_.numParticles());
  dt_ = time_.nextTimestep(mpm_.computeStableTimestep(), dt_, t_);
}

void Simulation::run() {
  const auto start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  archiver_.open(chooseOutputDirectory(options_.outputDir, archiver_.filebase()), options_.input);
  const int outputTask = mpm_.timers().task("output");
  const int snapshotTask = mpm_.timers().task("lastGoodState");
  auto summaryRow = [&](double stepDt) {
    const StepSummary s = mpm_.summarize();
    archiver_.recordHistory({step_, s.particles, t_, stepDt, s.kineticEnergy, s.minJ, s.maxJ, wall(), s.diffusion,
                             s.totalLithium, s.minConcentration, s.maxConcentration});
  };
  auto output = [&] {
    ScopedTimer timer(mpm_.timers(), outputTask);
    if (archiver_.wantsGrid() && step_ == 0) mpm_.interpolateToGridForOutput();
    // Between steps the snapshot and the weights are not needed: the output's copy of the
    // particles takes their memory instead of adding to the peak.
    lastGood_.release();
    mpm_.releaseInterpolationWeights();
    archiver_.writeOutput(step_, t_, mpm_);
  };
  std::fprintf(stderr, "sus: %zu particles in %zu material(s), grid %dx%dx%d cells, output in %s\n",
               mpm_.numParticles(), mpm_.materials().size(), mpm_.grid().cells.x(),
               mpm_.grid().cells.y(), mpm_.grid().cells.z(), archiver_.directory().c_str());
  summaryRow(0.0);
  output();
  scenes_.renderDue(t_, mpm_, archiver_.directory());
  ProgressReporter progress(time_.initTime, time_.maxTime, time_.maxTimesteps);
  while (true) {
    const double stepDt = dt_;
    {
      ScopedTimer timer(mpm_.timers(), snapshotTask);
      lastGood_.save(mpm_);
    }
    try {
      advance();
    } catch (const SimulationError&) {
      archiver_.writeHistory();
      if (options_.progress) progress.finish();
      writeStateOnStop();
      throw;
    }
    summaryRow(stepDt);
    const bool done = t_ >= time_.maxTime || (time_.maxTimesteps > 0 && step_ >= time_.maxTimesteps) ||
                      (time_.maxWallTime > 0 && wall() >= time_.maxWallTime);
    if (done || archiver_.isOutputStep(step_, t_)) output();
    scenes_.renderDue(t_, mpm_, archiver_.directory());
    if (options_.progress) progress.update(step_, t_, stepDt, particleSteps_, done);
    if (done) break;
  }
  if (options_.progress) progress.finish();
  wallSeconds_ = wall();
}

void Simulation::writeStateOnStop() {
  // The failing step's particles outside the .pvd series, then the last good state (the end of
  // step_, saved before the failing step) as the series' last entry.
  const std::string failed = archiver_.writeFailedState(step_ + 1, mpm_);
  lastGood_.restore(mpm_);
  if (archiver_.lastOutputStep() != step_) {
    if (archiver_.wantsGrid()) mpm_.interpolateToGridForOutput();
    archiver_.writeOutput(step_, t_, mpm_);
  }
  std::fprintf(stderr, "sus: the last good state (step %ld, t = %.6e) is the last entry of %s/particles.pvd; "
               "the failing step's particles are in %s\n", step_, t_, archiver_.directory().c_str(), failed.c_str());
}

void Simulation::printTimings() const {
  const TaskTimers& timers = mpm_.timers();
  double total = 0;
  for (double s : timers.seconds()) total += s;
  std::fprintf(stderr, "sus: %ld steps, t = %.6e, %zu particles, wall %.3f s\n", step_, t_,
               mpm_.numParticles(), wallSeconds_);
  std::fprintf(stderr, "  %-34s %10s %7s\n", "task", "seconds", "share");
  for (size_t i = 0; i < timers.names().size(); ++i)
    std::fprintf(stderr, "  %-34s %10.3f %6.1f%%\n", timers.names()[i].c_str(), timers.seconds()[i],
                 total > 0 ? 100 * timers.seconds()[i] / total : 0.0);
  std::fprintf(stderr, "  particle-steps per second: %.4e\n", wallSeconds_ > 0 ? particleSteps_ / wallSeconds_ : 0.0);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double peakBytes = usage.ru_maxrss * 1024.0;  // Linux reports kilobytes
  std::fprintf(stderr, "  peak memory: %.1f MB, %.0f bytes per particle\n", peakBytes / 1e6,
               peakBytes / std::max<size_t>(mpm_.numParticles(), 1));
}

}  // namespace anode
