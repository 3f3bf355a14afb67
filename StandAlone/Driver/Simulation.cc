#include "StandAlone/Driver/Simulation.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/IntegratorFactory.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/StopRequest.h"
#include "StandAlone/Driver/RunReport.h"
#include "StandAlone/Driver/RunTimings.h"
#include "StandAlone/Driver/SetupReport.h"
#include "StandAlone/Driver/StepForecast.h"

namespace anode {

Simulation::Simulation(const RunOptions& options) : options_(options) {
  setup([&] { spec_ = std::make_unique<ProblemSpec>(options.input, options.ignoreUnsupported); });
}

Simulation::Simulation(const std::string& text, const std::string& name, const RunOptions& options)
    : options_(options) {
  setup([&] { spec_ = ProblemSpec::fromText(text, name, options.ignoreUnsupported); });
}

void Simulation::setup(const std::function<void()>& readSpec) {
  const Collective every = Communicator::everyRank();
  const auto start = std::chrono::steady_clock::now();
  // Everything that reads and checks the input calls no collective: a rank that cannot read it
  // (a path not shared between nodes) ends every rank here, not in the first collective.
  collective::readTogether(every, [&] {
    readSpec();
    readInput();
  });
  if (options_.countParticlesOnly) return;
  mpm_.distributeOverRanks(
      every, archiver_.savesConcentrationFields() || scenes_.draws("p.concentrationGradient"));
  takeStableTimestep(every, 0.0);
  setupSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  setupPeakBytes_ = usage.ru_maxrss * 1024.0;  // Linux: kilobytes
}

const ImplicitStep& Simulation::implicitStep() const {
  const auto* step = dynamic_cast<const ImplicitStep*>(integrator_.get());
  if (!step) throw std::logic_error("Simulation::implicitStep: the run is explicit");
  return *step;
}

void Simulation::readInput() {
  PSNode root = spec_->root();
  time_ = TimeControl::fromInput(root.requireChild("Time"));
  mpm_.problemSetup(root, time_.initTime, time_.maxTime, !options_.countParticlesOnly, [&] {
    const MPMFlags& flags = mpm_.problem().flags;
    dtController_.emplace(time_, flags.implicit ? &*flags.implicit : nullptr);
    integrator_ = makeIntegrator(root, mpm_, *dtController_);
  });
  archiver_ = DataArchiver::fromInput(root.requireChild("DataArchiver"),
                                      mpm_.problem().flags.doScalarDiffusion,
                                      static_cast<int>(mpm_.materials().size()));
  // As in Uintah, outputs by steps leave the clamp nothing to end a step on.
  if (time_.clampTimeToOutput && !archiver_.outputsByTime())
    root.requireChild("Time")
        .requireChild("clamp_time_to_output")
        .warn(
            "<clamp_time_to_output>true clamps no step: the outputs come every "
            "<outputTimestepInterval> steps, not at times (<outputInterval>)");
  archiver_.setMaterialColumns(mpm_.materials(), mpm_.grid());
  checkpoints_ = RunCheckpoints(CheckpointSchedule::fromInput(root.requireChild("DataArchiver")),
                                time_.initTime);
  scenes_ = SceneOutput::fromInput(root, time_, mpm_);
  spec_->checkAllUsed();
  inputMaxTimesteps_ = time_.maxTimesteps;
  if (options_.maxTimesteps > 0 &&
      (time_.maxTimesteps == 0 || options_.maxTimesteps < time_.maxTimesteps))
    time_.maxTimesteps = options_.maxTimesteps;
  t_ = time_.initTime;
}

void Simulation::takeStableTimestep(Collective every, double growsFrom) {
  const TimestepController::Plan plan =
      dtController_->plan(integrator_->stableTimestep(every), growsFrom, t_, nextTimeToEndOn());
  dt_ = plan.dt;
  ruleDt_ = plan.ruleDt;
  dtLimit_ = plan.limit;
  dtSetByTimeControl_ = plan.setByTimeControl;
}

std::optional<double> Simulation::nextTimeToEndOn() const {
  std::optional<double> next;
  if (dtController_->endsStepsOnOutputs()) next = archiver_.nextOutputTimeAfter(t_);
  if (dtController_->controlsError() && mpm_.diffusion()) {
    const double load = mpm_.diffusion()->nextLoadChangeAfter(t_);
    if (load < time_.maxTime && (!next || load < *next)) next = load;
  }
  return next;
}

void Simulation::stepMPM(Collective every) {
  const StepTaken taken = integrator_->advance(every, t_, dt_, ruleDt_);
  dt_ = taken.dt;
  growsFromDt_ = taken.ruleDt;
  dtController_->recordStep(integrator_->lastStepCounts().errorEstimate, taken.dt, taken.ruleDt);
}

void Simulation::advance(Collective every) {
  try {
    stepMPM(every);
    ScopedTimer timer(mpm_.timers(), mpm_.timers().task("stateChecks"));
    checks_.afterStep(every, mpm_, dt_);
  } catch (const StoppedOnAnotherRank&) {
    throw;
  } catch (const SimulationError& e) {
    throw SimulationError(atThisStep(e.what()));
  } catch (const LibraryFailure& e) {
    // On several ranks sus reports it and ends them all (the others may wait in the library).
    if (Communicator::size() > 1) throw LibraryFailure(atThisStep(e.what()));
    throw SimulationError(atThisStep(e.what()));
  }
  lastStepDt_ = dt_;
  finishStep(every);
}

std::string Simulation::atThisStep(const std::string& problem) const {
  std::ostringstream s;
  s << "step " << step_ + 1 << ", t = " << t_ + dt_ << ": " << problem;
  return s.str();
}

void Simulation::finishStep(Collective every) {
  t_ += dt_;
  ++step_;
  takeStableTimestep(every, growsFromDt_);
}

void Simulation::run() {
  const Collective every = Communicator::everyRank();
  runStart_ = std::chrono::steady_clock::now();
  const bool restart = !options_.restartDir.empty();
  start(every, restart);
  if (options_.progress && Communicator::isRoot())
    progress_.emplace(t_, time_.maxTime, step_, time_.maxTimesteps);
  // A checkpoint at the end of the run (killed before it wrote its last output) has no step left.
  const bool nothingLeft = restart && finished(every);
  if (nothingLeft && archiver_.lastOutputStep() != step_) writeOutput(every, false);
  while (!nothingLeft) {
    const StableTimestep::Limit stepLimit = dtLimit_;
    double stepDt = 0;
    try {
      stepDt = advanceAndRecord(every);
    } catch (const StopRequestedInStep&) {
      stopInStep(every);
      break;
    }
    const bool done = finished(every);
    const bool atInputEnd = done && reachedInputEnd();
    // A rebalance is followed by a checkpoint, so a replay to the last good state never
    // crosses one (it takes the same steps with the same boxes); a run stopped before the input's
    // end rebalances as the uninterrupted one would, so its restart continues with those boxes.
    bool rebalanced = false;
    if (atInputEnd || archiver_.isOutputStep(step_, t_)) {
      writeOutput(every, true);
      rebalanced = !atInputEnd && balance_.rebalance(every, mpm_, step_);
    }
    scenes_.renderDue(every, t_, mpm_, archiver_.directory());
    const Requests anyRank = requestsOfAnyRank(every, done);
    stoppedOnRequest_ = anyRank.stop;
    // A stop before the input's end (a signal, --max-timesteps, <max_wall_time>) leaves a
    // checkpoint at its step, so a restart takes no step twice.
    const bool stopping = anyRank.stop || (done && !atInputEnd);
    if (checkpoints_.isDue(step_, t_))
      writeCheckpoint(every, CheckpointKind::Scheduled);
    else if (rebalanced || stopping || anyRank.replayCheckpoint)
      writeCheckpoint(every, CheckpointKind::Automatic);
    // The stopped state as the series' last entry, after the checkpoint: a restart from it
    // removes this output, so the continued series is the uninterrupted run's.
    if (stopping && archiver_.lastOutputStep() != step_) writeOutput(every, true);
    if (progress_) updateProgress(stepLimit, stepDt, done);
    if (done || stoppedOnRequest_) break;
  }
  finishRun();
}

void Simulation::stopInStep(Collective every) {
  stoppedOnRequest_ = true;
  if (progress_) progress_->finish();
  if (Communicator::isRoot())
    std::fprintf(stderr, "sus: step %ld dropped: a stop was requested while it ran\n", step_ + 1);
  // The particles are the last completed step's again: its checkpoint (unless written), then
  // its output as the series' last entry, as a stop between steps leaves them.
  if (checkpoints_.newestStep() != step_) writeCheckpoint(every, CheckpointKind::Automatic);
  if (archiver_.lastOutputStep() != step_) writeOutput(every, false);
}

double Simulation::advanceAndRecord(Collective every) {
  const double plannedDt = dt_;
  const int plannedRule = dtSetByTimeControl_ ? int{kDtSetByTimeControl} : dtRule(dtLimit_);
  try {
    advance(every);
  } catch (const SimulationError&) {
    writeStateOnStop(every);
    throw;
  }
  const double stepDt = lastStepDt_;
  const int rule = stepDt < plannedDt ? int{kDtRetaken} : plannedRule;
  ++stepsByRule_[rule];
  const double particles = static_cast<double>(recordHistoryRow(every, stepDt, rule));
  particleSteps_ += particles;
  particleStepsOfThisProcess_ += particles;
  reportRunNotes(every);
  return stepDt;
}

void Simulation::updateProgress(StableTimestep::Limit stepLimit, double stepDt, bool done) {
  std::string limit = integrator_->describeLastStep(stepLimit);
  if (mpm_.diffusion()) limit += ", SOC " + chargeText(stateOfCharge_);
  progress_->update(step_, t_, stepDt, limit.c_str(), particleStepsOfThisProcess_, done);
}

void Simulation::finishRun() {
  if (progress_) progress_->finish();
  if (Communicator::isRoot())
    checkpoints_.atEnd(archiver_.directory(), stoppedOnRequest_, reachedInputEnd(),
                       time_.maxTimesteps > 0 && step_ >= time_.maxTimesteps ? "--max-timesteps"
                                                                             : "<max_wall_time>",
                       step_, t_);
  writeReport(reachedInputEnd()
                  ? "Written at the end of the run (step " + std::to_string(step_) + ")."
                  : "Written when the run stopped before its end, after step " +
                        std::to_string(step_) + ".");
  wallSeconds_ = wallTime();
}

void Simulation::start(Collective every, bool restart) {
  checkpoints_.hashInput(options_.input);
  if (restart) {
    archiver_.reopen(options_.restartDir);
    resumeFrom(checkpoints_.restartFromNewest(every, options_.restartDir, archiver_, mpm_));
    firstStepOfThisProcess_ = step_;
    scenes_.skipTimesUpTo(t_);
  } else {
    // Rank 0 picks the directory (the next free version) for all.
    const std::string dir = collective::broadcast(
        every,
        Communicator::isRoot() ? chooseOutputDirectory(options_.outputDir, archiver_.filebase())
                               : "",
        0);
    checkpoints_.removeEarlierRuns(every, dir);
    archiver_.open(every, dir, options_.input);
  }
  outputTask_ = mpm_.timers().task("output");
  checkpointTask_ = mpm_.timers().task("checkpoint");
  reportSetup(every);
  if (restart) {
    if (Communicator::isRoot())
      std::fprintf(stderr, "sus: restarting from %s (step %ld, t = %.6e)\n",
                   checkpoints_.newest().c_str(), step_, t_);
  } else {
    recordHistoryRow(every, 0.0, -1);
    writeOutput(every, false);
    scenes_.renderDue(every, t_, mpm_, archiver_.directory());
    writeCheckpoint(every, CheckpointKind::Automatic);
  }
}

double Simulation::wallTime() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart_).count();
}

bool Simulation::reachedInputEnd() const {
  return t_ >= time_.maxTime || (inputMaxTimesteps_ > 0 && step_ >= inputMaxTimesteps_);
}

bool Simulation::finished(Collective every) const {
  return t_ >= time_.maxTime || (time_.maxTimesteps > 0 && step_ >= time_.maxTimesteps) ||
         (time_.maxWallTime > 0 && collective::any(every, wallTime() >= time_.maxWallTime));
}

void Simulation::reportSetup(Collective every) {
  const size_t particles = mpm_.summarize(every).particles;
  const double imbalance = balance_.start(every, mpm_);
  printSetupReport(
      every, mpm_, {particles, imbalance, setupSeconds_, setupPeakBytes_, archiver_.directory()},
      Communicator::isRoot() ? forecastSteps(stepForecastInput()) : std::vector<std::string>{});
  for (const std::string& note : symmetryFaces_.start(every, mpm_))
    if (Communicator::isRoot()) std::fprintf(stderr, "%s\n", note.c_str());
}

StepForecastInput Simulation::stepForecastInput() const {
  StepForecastInput in;
  in.startTime = t_;
  in.maxTime = time_.maxTime;
  in.maxTimesteps = time_.maxTimesteps > 0 ? time_.maxTimesteps - step_ : 0;
  in.dt = dt_;
  in.limit = StableTimestep::name(dtLimit_);
  in.mechanicsLimited = dtLimit_ == StableTimestep::Mechanics;
  in.implicit = mpm_.problem().flags.implicit.has_value();
  in.errorControlled = dtController_->controlsError();
  in.cellSize = mpm_.grid().dx.minCoeff();
  for (size_t m = 0; m < mpm_.materials().size(); ++m)
    in.densities.emplace_back(describeMaterial(mpm_.materials()[m], m),
                              mpm_.materials()[m].density);
  return in;
}

size_t Simulation::recordHistoryRow(Collective every, double stepDt, int dtRule) {
  const StepSummary s = mpm_.summarize(every);
  const double lithiumRate =
      stepDt > 0 ? (s.totalLithium - archiver_.lastHistoryRow().totalLithium) / stepDt : 0.0;
  stateOfCharge_ = s.lithiumCapacity > 0 ? s.chargeableLithium / s.lithiumCapacity : 0.0;
  const std::optional<ImplicitOptions>& implicit = mpm_.problem().flags.implicit;
  const bool trapezoidal = implicit && implicit->concentrationCoupling ==
                                           ImplicitOptions::ConcentrationCoupling::Trapezoidal;
  archiver_.recordHistory(
      {step_, s.particles, t_, stepDt, s.kineticEnergy, s.minJ, s.maxJ,
       earlierWallSeconds_ + wallTime(), s.diffusion, s.totalLithium, s.minConcentration,
       s.maxConcentration, lithiumRate, stateOfCharge_},
      stepRecord(s, dtRule, integrator_->lastStepCounts(), trapezoidal,
                 dtController_->controlsError() ? &dtController_->errorControl() : nullptr),
      s.perMaterial, s.stress);
  return s.particles;
}

void Simulation::writeOutput(Collective every, bool afterStep) {
  ScopedTimer timer(mpm_.timers(), outputTask_);
  // Before any step of this process (the start, or a restart with no step left) the grid labels
  // are interpolated from the particles.
  if (archiver_.wantsGrid() && !afterStep) mpm_.interpolateToGridForOutput(every);
  // Between steps the weights are not needed: the output's copy of the particles takes their
  // memory instead of adding to the peak.
  mpm_.releaseInterpolationWeights();
  archiver_.writeOutput(every, step_, t_, mpm_);
}

void Simulation::reportRunNotes(Collective every) {
  std::vector<std::string> lines = symmetryFaces_.afterStep(every, mpm_, step_, t_);
  if (mpm_.diffusion())
    for (const std::string& note : mpm_.diffusion()->takeRunNotes())
      if (Communicator::isRoot()) lines.push_back("note: " + note);  // the same on every rank
  for (const std::string& line : lines) {
    if (progress_) progress_->finish();
    std::fprintf(stderr, "%s\n", line.c_str());
  }
}

Simulation::Requests Simulation::requestsOfAnyRank(Collective every, bool done) const {
  double anyRank[2] = {stopRequested() ? 1.0 : 0.0,
                       wallTime() - newestCheckpointWallTime_ >= kReplayInterval ? 1.0 : 0.0};
  if (!done) collective::maximum(every, anyRank, 2);
  return {!done && anyRank[0] > 0, !done && anyRank[1] > 0};
}

void Simulation::writeStateOnStop(Collective every) {
  archiver_.writeHistory();
  if (progress_) progress_->finish();
  // The failing step's particles outside the .pvd series, then the last good state (the end of
  // step_) as the series' last entry.
  const std::string failed = archiver_.writeFailedState(every, step_ + 1, mpm_);
  replayToLastGoodState(every);
  if (Communicator::isRoot()) removeAutomaticCheckpoints(archiver_.directory());
  if (archiver_.lastOutputStep() != step_) {
    if (archiver_.wantsGrid()) mpm_.interpolateToGridForOutput(every);
    archiver_.writeOutput(every, step_, t_, mpm_);
  }
  if (Communicator::isRoot())
    std::fprintf(
        stderr,
        "sus: the last good state (step %ld, t = %.6e) is the last entry of %s/particles.pvd; "
        "the failing step's particles are in %s\n",
        step_, t_, archiver_.directory().c_str(), failed.c_str());
  writeReport("Written when step " + std::to_string(step_ + 1) +
              " failed (the run's log says why); the last good state is step " +
              std::to_string(step_) + ".");
}

void Simulation::replayToLastGoodState(Collective every) {
  const long lastGood = step_;
  resumeFrom(checkpoints_.loadForReplay(every, lastGood, mpm_));
  while (step_ < lastGood) {
    stepMPM(every);
    finishStep(every);
  }
  RunCheckpoints::checkReplayed(every, step_, archiver_.lastHistoryRow(), mpm_);
}

void Simulation::writeCheckpoint(Collective every, CheckpointKind kind) {
  ScopedTimer timer(mpm_.timers(), checkpointTask_);
  checkpoints_.write(every, kind, checkpointState(), archiver_, mpm_);
  newestCheckpointWallTime_ = wallTime();
  // At the input's checkpoints and the start, not at the automatic ones every 10 minutes: the
  // report reads the whole history.csv (a gigabyte after millions of steps).
  if (kind == CheckpointKind::Scheduled || step_ == 0)
    writeReport("Written at the checkpoint of step " + std::to_string(step_) +
                " (the run went on from there, or stopped: see its log).");
}

void Simulation::writeReport(const std::string& status) {
  if (!Communicator::isRoot()) return;
  ScopedTimer timer(mpm_.timers(), outputTask_);
  try {
    writeRunReport(archiver_.directory(), status);
  } catch (const std::exception& e) {
    if (progress_) progress_->finish();
    std::fprintf(stderr, "warning: report.html not written: %s\n", e.what());
  }
}

CheckpointHeader Simulation::checkpointState() const {
  CheckpointHeader state;
  state.t = t_;
  state.dt = dt_;
  state.ruleDt = ruleDt_;
  state.dtLimit = dtLimit_;
  state.dtSetByTimeControl = dtSetByTimeControl_;
  state.errorControl = dtController_->errorControl();
  state.step = step_;
  state.particleSteps = particleSteps_;
  state.wallSeconds = earlierWallSeconds_ + wallTime();
  return state;
}

void Simulation::resumeFrom(const CheckpointHeader& read) {
  t_ = read.t;
  dt_ = read.dt;
  ruleDt_ = read.ruleDt;
  dtLimit_ = read.dtLimit;
  dtSetByTimeControl_ = read.dtSetByTimeControl;
  dtController_->resumeErrorControl(read.errorControl);
  step_ = read.step;
  particleSteps_ = read.particleSteps;
  earlierWallSeconds_ = read.wallSeconds;
}

void Simulation::printTimings(Collective every) const {
  anode::printTimings(
      every,
      {step_, t_, !options_.restartDir.empty(), firstStepOfThisProcess_, stepsByRule_,
       particleSteps_, particleStepsOfThisProcess_, wallSeconds_, earlierWallSeconds_},
      mpm_, *integrator_);
}

}  // namespace anode
