#include "StandAlone/Driver/Simulation.h"

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/IntegratorFactory.h"
#include "Core/Parallel/Communicator.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/AtomicFile.h"
#include "Core/Util/InstructionSet.h"
#include "StandAlone/Driver/RunReport.h"
#include "StandAlone/Driver/StepForecast.h"
#include "StandAlone/Driver/StopRequest.h"

namespace anode {

Simulation::Simulation(const RunOptions& options) : options_(options) {
  setup([&] { spec_ = std::make_unique<ProblemSpec>(options.input, options.ignoreUnsupported); });
}

Simulation::Simulation(const std::string& text, const std::string& name, const RunOptions& options)
    : options_(options) {
  setup([&] { spec_ = ProblemSpec::fromText(text, name, options.ignoreUnsupported); });
}

void Simulation::setup(const std::function<void()>& readSpec) {
  const auto start = std::chrono::steady_clock::now();
  // Everything that reads and checks the input calls no collective: a rank that cannot read it
  // (a path not shared between nodes) ends every rank here, not in the first collective.
  collective::readTogether([&] {
    readSpec();
    readInput();
  });
  if (options_.countParticlesOnly) return;
  mpm_.distributeOverRanks(Collective{});
  if (archiver_.savesConcentrationFields() || scenes_.draws("p.concentrationGradient"))
    mpm_.diffusion()->computeEveryMaterial();
  takeStableTimestep(0.0);
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
  if (mpm_.diffusion())
    archiver_.setMaterialColumns(mpm_.materials(), mpm_.diffusion()->lithiumTakingMaterials());
  checkpoints_ = CheckpointSchedule::fromInput(root.requireChild("DataArchiver"));
  scenes_ = SceneOutput::fromInput(root, time_, mpm_);
  spec_->checkAllUsed();
  inputMaxTimesteps_ = time_.maxTimesteps;
  if (options_.maxTimesteps > 0 &&
      (time_.maxTimesteps == 0 || options_.maxTimesteps < time_.maxTimesteps))
    time_.maxTimesteps = options_.maxTimesteps;
  t_ = time_.initTime;
  lastCheckpointTime_ = t_;
}

void Simulation::takeStableTimestep(double growsFrom) {
  const TimestepController::Plan plan = dtController_->plan(
      integrator_->stableTimestep(Collective{}), growsFrom, t_,
      time_.clampTimeToOutput ? archiver_.nextOutputTimeAfter(t_) : std::nullopt);
  dt_ = plan.dt;
  ruleDt_ = plan.ruleDt;
  dtLimit_ = plan.limit;
  dtSetByTimeControl_ = plan.setByTimeControl;
}

void Simulation::stepMPM() {
  const StepTaken taken = integrator_->advance(Collective{}, t_, dt_, ruleDt_);
  dt_ = taken.dt;
  growsFromDt_ = taken.ruleDt;
}

void Simulation::advance() {
  try {
    stepMPM();
    ScopedTimer timer(mpm_.timers(), mpm_.timers().task("stateChecks"));
    checks_.afterStep(Collective{}, mpm_, dt_);
  } catch (const StoppedOnAnotherRank&) {
    throw;
  } catch (const SimulationError& e) {
    std::ostringstream s;
    s << "step " << step_ + 1 << ", t = " << t_ + dt_ << ": " << e.what();
    throw SimulationError(s.str());
  }
  lastStepDt_ = dt_;
  finishStep();
}

void Simulation::finishStep() {
  t_ += dt_;
  ++step_;
  takeStableTimestep(growsFromDt_);
}

void Simulation::run() {
  runStart_ = std::chrono::steady_clock::now();
  inputHash_ = fileHash(options_.input);
  const bool restart = !options_.restartDir.empty();
  start(Collective{}, restart);
  if (options_.progress && Communicator::isRoot())
    progress_.emplace(t_, time_.maxTime, step_, time_.maxTimesteps);
  // A checkpoint at the end of the run (killed before it wrote its last output) has no step left.
  const bool nothingLeft = restart && finished(Collective{});
  if (nothingLeft && archiver_.lastOutputStep() != step_) writeOutput(false);
  while (!nothingLeft) {
    const StableTimestep::Limit stepLimit = dtLimit_;
    const double plannedDt = dt_;
    const int plannedRule = dtSetByTimeControl_ ? int{kDtSetByTimeControl} : int{stepLimit};
    try {
      advance();
    } catch (const SimulationError&) {
      writeStateOnStop();
      throw;
    }
    const double stepDt = lastStepDt_;
    const int rule = stepDt < plannedDt ? int{kDtRetaken} : plannedRule;
    ++stepsByRule_[rule];
    const double particles = static_cast<double>(recordHistoryRow(stepDt, rule));
    particleSteps_ += particles;
    particleStepsOfThisProcess_ += particles;
    reportSymmetryFaces();
    reportDiffusionNotes();
    const bool done = finished(Collective{});
    const bool atInputEnd = done && reachedInputEnd();
    // A rebalance is followed by a checkpoint, so a replay to the last good state never
    // crosses one (it takes the same steps with the same boxes).
    bool rebalanced = false;
    if (atInputEnd || archiver_.isOutputStep(step_, t_)) {
      writeOutput(true);
      rebalanced = !done && rebalance(Collective{});
    }
    scenes_.renderDue(t_, mpm_, archiver_.directory());
    const Requests anyRank = requestsOfAnyRank(Collective{}, done);
    stoppedOnRequest_ = anyRank.stop;
    // A stop before the input's end (a signal, --max-timesteps, <max_wall_time>) leaves a
    // checkpoint at its step, so a restart takes no step twice.
    const bool stopping = anyRank.stop || (done && !atInputEnd);
    if (checkpoints_.isDue(step_, t_, lastCheckpointTime_))
      writeCheckpoint(Collective{}, CheckpointKind::Scheduled);
    else if (rebalanced || stopping || anyRank.replayCheckpoint)
      writeCheckpoint(Collective{}, CheckpointKind::Automatic);
    // The stopped state as the series' last entry, after the checkpoint: a restart from it
    // removes this output, so the continued series is the uninterrupted run's.
    if (stopping && archiver_.lastOutputStep() != step_) writeOutput(true);
    if (progress_) {
      std::string limit = integrator_->describeLastStep(stepLimit);
      if (mpm_.diffusion()) {
        char charge[64];
        std::snprintf(charge, sizeof charge, ", SOC %.2f%% = %.0f mAh/g", 100 * stateOfCharge_,
                      stateOfCharge_ * kSiliconCapacityAtFull);
        limit += charge;
      }
      progress_->update(step_, t_, stepDt, limit.c_str(), particleStepsOfThisProcess_, done);
    }
    if (done || stoppedOnRequest_) break;
  }
  if (progress_) progress_->finish();
  if (Communicator::isRoot()) {
    if (stoppedOnRequest_)
      std::fprintf(stderr,
                   "sus: stopped on request (SIGTERM, SIGINT or SIGUSR1) after step %ld, t = "
                   "%.6e: checkpoint %s; continue with sus -restart %s\n",
                   step_, t_, newestCheckpoint_.c_str(), archiver_.directory().c_str());
    else if (!reachedInputEnd())
      std::fprintf(stderr,
                   "sus: stopped after step %ld, t = %.6e, before the input's end (%s): "
                   "checkpoint %s; continue with sus -restart %s\n",
                   step_, t_,
                   time_.maxTimesteps > 0 && step_ >= time_.maxTimesteps ? "--max-timesteps"
                                                                         : "<max_wall_time>",
                   newestCheckpoint_.c_str(), archiver_.directory().c_str());
    else
      removeAutomaticCheckpoints(archiver_.directory());
  }
  writeReport(reachedInputEnd()
                  ? "Written at the end of the run (step " + std::to_string(step_) + ")."
                  : "Written when the run stopped before its end, after step " +
                        std::to_string(step_) + ".");
  wallSeconds_ = wallTime();
}

void Simulation::start(Collective, bool restart) {
  std::string restartedFrom;
  if (restart) {
    restartedFrom = restartFromNewestCheckpoint(Collective{});
  } else {
    // Rank 0 picks the directory (the next free version) for all.
    const std::string dir = collective::broadcast(
        Communicator::isRoot() ? chooseOutputDirectory(options_.outputDir, archiver_.filebase())
                               : "",
        0);
    removeEarlierRunsCheckpoints(Collective{}, dir);
    archiver_.open(dir, options_.input);
  }
  outputTask_ = mpm_.timers().task("output");
  checkpointTask_ = mpm_.timers().task("checkpoint");
  reportSetup(Collective{});
  if (restart) {
    if (Communicator::isRoot())
      std::fprintf(stderr, "sus: restarting from %s (step %ld, t = %.6e)\n", restartedFrom.c_str(),
                   step_, t_);
  } else {
    recordHistoryRow(0.0, -1);
    writeOutput(false);
    scenes_.renderDue(t_, mpm_, archiver_.directory());
    writeCheckpoint(Collective{}, CheckpointKind::Automatic);
  }
}

double Simulation::wallTime() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart_).count();
}

bool Simulation::reachedInputEnd() const {
  return t_ >= time_.maxTime || (inputMaxTimesteps_ > 0 && step_ >= inputMaxTimesteps_);
}

bool Simulation::finished(Collective) const {
  return t_ >= time_.maxTime || (time_.maxTimesteps > 0 && step_ >= time_.maxTimesteps) ||
         (time_.maxWallTime > 0 && collective::any(wallTime() >= time_.maxWallTime));
}

void Simulation::removeEarlierRunsCheckpoints(Collective, const std::string& dir) {
  collective::onRootTogether(
      [&] {
        const size_t earlier = listCheckpoints(dir).size();
        removeOldCheckpoints(dir, CheckpointKind::Scheduled, 0);
        removeOldCheckpoints(dir, CheckpointKind::Automatic, 0);
        removeUnfinishedCheckpointParts(dir);
        if (earlier > 0)
          std::fprintf(stderr,
                       "sus: removed %zu checkpoint(s) of an earlier run from %s/checkpoints: "
                       "this run's history and outputs replace that run's\n",
                       earlier, dir.c_str());
        return std::string();
      },
      "rank 0 could not remove an earlier run's checkpoints");
}

std::string Simulation::restartFromNewestCheckpoint(Collective) {
  archiver_.reopen(options_.restartDir);
  if (Communicator::isRoot()) {
    removeTemporaryFiles(options_.restartDir);
    removeUnfinishedCheckpointParts(options_.restartDir);
  }
  collective::barrier();
  newestCheckpoint_ = loadNewestCheckpoint();
  firstStepOfThisProcess_ = step_;
  scenes_.skipTimesUpTo(t_);
  return newestCheckpoint_;
}

void Simulation::reportSetup(Collective) {
  const size_t particles = mpm_.summarize(Collective{}).particles;
  layoutImbalance_ = mpm_.layout().imbalance(Collective{});
  // Setup's wall time and the memory it left (the peak so far), of the slowest and the largest
  // rank and of the smallest.
  double setup[4] = {setupSeconds_, setupPeakBytes_, -setupSeconds_, -setupPeakBytes_};
  if (Communicator::size() > 1) collective::maximum(setup, 4);
  if (Communicator::isRoot()) {
    if (Communicator::size() > 1)
      std::fprintf(stderr,
                   "sus: setup %.2f s on the slowest rank (%.2f s on the fastest), peak memory "
                   "%.1f MB on the largest rank (%.1f MB on the smallest)\n",
                   setup[0], -setup[2], setup[1] / 1e6, -setup[3] / 1e6);
    else
      std::fprintf(stderr, "sus: setup %.2f s, peak memory %.1f MB\n", setup[0], setup[1] / 1e6);
    std::fprintf(stderr,
                 "sus: %zu particles in %zu material(s), grid %dx%dx%d cells, output in %s\n",
                 particles, mpm_.materials().size(), mpm_.grid().cells.x(), mpm_.grid().cells.y(),
                 mpm_.grid().cells.z(), archiver_.directory().c_str());
    if (Communicator::size() > 1)
      std::fprintf(stderr,
                   "sus: %d ranks: %s, ghost layers %d cells; particles per rank max/mean %.3f\n",
                   Communicator::size(), mpm_.layout().boxes().describe().c_str(),
                   mpm_.layout().ghostWidth(), layoutImbalance_);
    if (mpm_.diffusion())
      for (const std::string& line : mpm_.diffusion()->setupReport())
        std::fprintf(stderr, "sus: %s\n", line.c_str());
    for (const std::string& line : forecastSteps(stepForecastInput()))
      std::fprintf(stderr, "%s%s\n", line.rfind("note:", 0) == 0 ? "" : "sus: ", line.c_str());
  }
  for (const std::string& note : symmetryFaces_.start(Collective{}, mpm_))
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
  in.cellSize = mpm_.grid().dx.minCoeff();
  for (size_t m = 0; m < mpm_.materials().size(); ++m)
    in.densities.emplace_back(describeMaterial(mpm_.materials()[m], m),
                              mpm_.materials()[m].density);
  return in;
}

size_t Simulation::recordHistoryRow(double stepDt, int dtRule) {
  const StepSummary s = mpm_.summarize(Collective{});
  const double lithiumRate =
      stepDt > 0 ? (s.totalLithium - archiver_.lastHistoryRow().totalLithium) / stepDt : 0.0;
  stateOfCharge_ = s.lithiumCapacity > 0 ? s.chargeableLithium / s.lithiumCapacity : 0.0;
  const bool trapezoidal = mpm_.problem().flags.implicit && s.diffusion && s.lithiumCapacity > 0 &&
                           mpm_.problem().flags.implicit->concentrationCoupling ==
                               ImplicitOptions::ConcentrationCoupling::Trapezoidal;
  const StepCounts counts = integrator_->lastStepCounts();
  const double couplingCorrection =
      trapezoidal ? std::max(0.0, counts.couplingCorrection) / s.lithiumCapacity : -1.0;
  archiver_.recordHistory({step_, s.particles, t_, stepDt, s.kineticEnergy, s.minJ, s.maxJ,
                           earlierWallSeconds_ + wallTime(), s.diffusion, s.totalLithium,
                           s.minConcentration, s.maxConcentration, lithiumRate, stateOfCharge_},
                          {s.elasticEnergy, dtRule, counts.newtonIterations,
                           counts.krylovIterations, couplingCorrection},
                          s.perMaterial);
  return s.particles;
}

void Simulation::writeOutput(bool afterStep) {
  ScopedTimer timer(mpm_.timers(), outputTask_);
  // Before any step of this process (the start, or a restart with no step left) the grid labels
  // are interpolated from the particles.
  if (archiver_.wantsGrid() && !afterStep) mpm_.interpolateToGridForOutput(Collective{});
  // Between steps the weights are not needed: the output's copy of the particles takes their
  // memory instead of adding to the peak.
  mpm_.releaseInterpolationWeights();
  archiver_.writeOutput(Collective{}, step_, t_, mpm_);
}

void Simulation::reportSymmetryFaces() {
  for (const std::string& warning : symmetryFaces_.afterStep(Collective{}, mpm_, step_, t_)) {
    if (progress_) progress_->finish();
    std::fprintf(stderr, "%s\n", warning.c_str());
  }
}

void Simulation::reportDiffusionNotes() {
  if (!mpm_.diffusion()) return;
  for (const std::string& note : mpm_.diffusion()->takeRunNotes()) {
    if (!Communicator::isRoot()) continue;  // every rank holds the same notes
    if (progress_) progress_->finish();
    std::fprintf(stderr, "note: %s\n", note.c_str());
  }
}

Simulation::Requests Simulation::requestsOfAnyRank(Collective, bool done) const {
  double anyRank[2] = {stopRequested() ? 1.0 : 0.0,
                       wallTime() - newestCheckpointWallTime_ >= kReplayInterval ? 1.0 : 0.0};
  if (!done) collective::maximum(anyRank, 2);
  return {!done && anyRank[0] > 0, !done && anyRank[1] > 0};
}

bool Simulation::rebalance(Collective) {
  if (Communicator::size() == 1) return false;
  const double before = mpm_.layout().imbalance(Collective{});
  const double growth =
      mpm_.problem().flags.implicit ? kRebalanceImbalanceImplicit : kRebalanceImbalance;
  if (before <= growth * layoutImbalance_) return false;
  ScopedTimer timer(mpm_.timers(), mpm_.timers().task("rebalance"));
  mpm_.layout().redistributeParticles(Collective{});
  const double after = mpm_.layout().imbalance(Collective{});
  if (Communicator::isRoot())
    std::fprintf(stderr,
                 "sus: step %ld: particles per rank max/mean %.3f, %.2f times the %.3f the boxes "
                 "started with: boxes drawn anew (%s), now %.3f\n",
                 step_, before, before / layoutImbalance_, layoutImbalance_,
                 mpm_.layout().boxes().describe().c_str(), after);
  layoutImbalance_ = after;
  return true;
}

void Simulation::writeStateOnStop() {
  archiver_.writeHistory();
  if (progress_) progress_->finish();
  // The failing step's particles outside the .pvd series, then the last good state (the end of
  // step_) as the series' last entry.
  const std::string failed = archiver_.writeFailedState(Collective{}, step_ + 1, mpm_);
  replayToLastGoodState();
  if (Communicator::isRoot()) removeAutomaticCheckpoints(archiver_.directory());
  if (archiver_.lastOutputStep() != step_) {
    if (archiver_.wantsGrid()) mpm_.interpolateToGridForOutput(Collective{});
    archiver_.writeOutput(Collective{}, step_, t_, mpm_);
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

void Simulation::replayToLastGoodState() {
  const long lastGood = step_;
  loadCheckpoint(Collective{}, newestCheckpoint_, false);
  if (step_ < lastGood && Communicator::isRoot())
    std::fprintf(stderr, "sus: replaying steps %ld to %ld from %s for the last good state\n",
                 step_ + 1, lastGood, newestCheckpoint_.c_str());
  while (step_ < lastGood) {
    stepMPM();
    finishStep();
  }
  // The replayed state must be the one the run had: its history row says what it was.
  const StepSummary s = mpm_.summarize(Collective{});
  const HistoryRow& row = archiver_.lastHistoryRow();
  if ((row.step != step_ || row.kineticEnergy != s.kineticEnergy ||
       row.totalLithium != s.totalLithium) &&
      Communicator::isRoot())
    std::fprintf(
        stderr,
        "warning: the replayed step %ld differs from the run's (kinetic energy %.17g, not %.17g)\n",
        step_, s.kineticEnergy, row.kineticEnergy);
}

void Simulation::writeCheckpoint(Collective, CheckpointKind kind) {
  ScopedTimer timer(mpm_.timers(), checkpointTask_);
  const double wallSeconds = earlierWallSeconds_ + wallTime();
  archiver_.writeHistory();  // history.csv holds every row up to the checkpoint's step
  const std::string dir = archiver_.directory();
  // On the disk before the checkpoint, as the checkpoint before any older one is removed
  // (parts, then manifest, each synced with its directory): a crashed node leaves a whole one.
  const std::filesystem::path history = std::filesystem::path(dir) / "history.csv";
  if (Communicator::isRoot() && std::filesystem::exists(history)) syncToDisk(history.string());
  if (kind == CheckpointKind::Scheduled) lastCheckpointTime_ = t_;
  newestCheckpoint_ = checkpointPath(dir, step_, kind);
  anode::writeCheckpoint(
      Collective{}, newestCheckpoint_,
      {omp_get_max_threads(), Communicator::size(), inputHash_, t_, dt_, ruleDt_, dtLimit_,
       dtSetByTimeControl_, step_, particleSteps_, wallSeconds, lastCheckpointTime_},
      archiver_, mpm_);
  if (Communicator::isRoot()) {
    if (kind == CheckpointKind::Scheduled) {
      removeOldCheckpoints(dir, kind, checkpoints_.cycle);
      removeOldCheckpoints(dir, CheckpointKind::Automatic, 0);  // the scheduled one is newer
    } else {
      removeOldCheckpoints(dir, kind, 1);
    }
  }
  collective::barrier();
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

void Simulation::loadCheckpoint(Collective, const std::string& path, bool outputs) {
  const CheckpointHeader read =
      anode::loadCheckpoint(Collective{}, path, outputs ? &archiver_ : nullptr, mpm_);
  t_ = read.t;
  dt_ = read.dt;
  ruleDt_ = read.ruleDt;
  dtLimit_ = read.dtLimit;
  dtSetByTimeControl_ = read.dtSetByTimeControl;
  step_ = read.step;
  particleSteps_ = read.particleSteps;
  earlierWallSeconds_ = read.wallSeconds;
  lastCheckpointTime_ = read.lastScheduledTime;
  const double mostRead = collective::maximum(read.bytesRead);
  if (!Communicator::isRoot()) return;
  if (Communicator::size() > 1 && outputs)
    std::fprintf(stderr, "sus: the rank that read most of %s read %.4g of its %.4g bytes (%.2f)\n",
                 path.c_str(), mostRead, read.bytesInAll, mostRead / read.bytesInAll);
  if (read.inputHash != inputHash_)
    std::fprintf(
        stderr,
        "warning: %s changed since %s was written; the run continues with the changed input\n",
        options_.input.c_str(), path.c_str());
  if (read.threads != omp_get_max_threads())
    std::fprintf(stderr,
                 "warning: %s was written with %d thread(s), this run has %d: the continued run "
                 "matches an uninterrupted one to round-off, not bit for bit\n",
                 path.c_str(), read.threads, omp_get_max_threads());
  if (read.ranks != Communicator::size())
    std::fprintf(stderr,
                 "sus: %s was written by %d rank(s), this run has %d: its particles are shared out "
                 "anew; the continued run matches an uninterrupted one to round-off\n",
                 path.c_str(), read.ranks, Communicator::size());
}

std::string Simulation::loadNewestCheckpoint() {
  // Rank 0 lists the checkpoints, newest first, and checks their hashes; every rank then tries
  // the same ones (a rank whose view of the directory lags, or whose read fails, must not resume
  // from another step). One line each: "I path" intact, "D path" damaged (skipped), or "E error"
  // (an I/O error: the restart stops, nothing removed).
  std::string listed;
  if (Communicator::isRoot()) try {
      const std::vector<std::string> found = listCheckpoints(options_.restartDir);
      if (found.empty())
        listed = "E no checkpoint in " + options_.restartDir +
                 "/checkpoints (the input needs <checkpoint cycle=\"N\" interval=\"T\"/> in "
                 "<DataArchiver>)\n";
      for (const std::string& path : found) {
        std::string error;
        const HashCheck check = checkHash(path, &error);
        if (check == HashCheck::Unreadable) {
          listed += "E " + error + " (nothing was removed)\n";
          break;
        }
        listed += (check == HashCheck::Intact ? "I " : "D ") + path + "\n";
      }
    } catch (const std::exception& e) {  // the directory unreadable: every rank stops
      listed = std::string("E ") + e.what() + " (nothing was removed)\n";
    }
  std::istringstream lines(collective::broadcast(listed, 0));
  for (std::string line; std::getline(lines, line);) {
    const std::string path = line.substr(2);
    if (line[0] == 'E') throw std::runtime_error(path);
    if (line[0] == 'D') {
      if (Communicator::isRoot())
        std::fprintf(stderr,
                     "warning: skipping %s: incomplete or damaged (its hash does not match)\n",
                     path.c_str());
      continue;
    }
    try {
      loadCheckpoint(Collective{}, path, true);  // fails on every rank together
    } catch (const std::runtime_error& e) {
      if (Communicator::isRoot())
        std::fprintf(stderr, "warning: skipping %s: %s\n", path.c_str(), e.what());
      continue;
    }
    // The outputs after it go only once it is loaded; an error here (a file that cannot be
    // written) stops the restart, and is no reason to go back to an older checkpoint.
    archiver_.restoreOutputsTo(step_);
    return path;
  }
  throw std::runtime_error("no complete checkpoint in " + options_.restartDir + "/checkpoints");
}

void Simulation::printTimings() const {
  // Per task the slowest rank's time (the others wait for it at the next exchange).
  const TaskTimers& timers = mpm_.timers();
  std::vector<double> seconds = timers.seconds();
  collective::maximum(seconds.data(), static_cast<int>(seconds.size()));
  const size_t particles =
      static_cast<size_t>(collective::sum(static_cast<int64_t>(countParticles(mpm_.materials()))));
  const double imbalance = mpm_.layout().imbalance(Collective{});
  const long collectiveCalls = Communicator::collectiveCalls();  // before this summary's own
  double communication[2] = {Communicator::bytesSent(), Communicator::communicationSeconds()};
  collective::sum(communication, 1);
  collective::maximum(communication + 1, 1);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double ownPeak = usage.ru_maxrss * 1024.0;  // Linux: kilobytes
  const double peakBytes = collective::maximum(ownPeak), allPeaks = collective::sum(ownPeak);
  if (!Communicator::isRoot()) return;
  double total = 0;
  for (double v : seconds) total += v;
  std::fprintf(stderr, "sus: %ld steps, t = %.6e, %zu particles, wall %.3f s", step_, t_, particles,
               wallSeconds_);
  if (!options_.restartDir.empty())
    std::fprintf(stderr, " (after the restart: %ld steps, from step %ld)",
                 step_ - firstStepOfThisProcess_, firstStepOfThisProcess_);
  std::fprintf(stderr, "\n");
  std::fprintf(stderr, "  %-34s %10s %7s\n", "task", "seconds", "share");
  for (size_t i = 0; i < timers.names().size(); ++i)
    std::fprintf(stderr, "  %-34s %10.3f %6.1f%%\n", timers.names()[i].c_str(), seconds[i],
                 total > 0 ? 100 * seconds[i] / total : 0.0);
  std::string limits;
  for (int rule = 0; rule < kDtRules; ++rule)
    if (stepsByRule_[rule] > 0)
      limits += (limits.empty() ? "" : ", ") + std::string(dtRuleName(rule)) + " " +
                std::to_string(stepsByRule_[rule]);
  if (!limits.empty()) std::fprintf(stderr, "  steps whose dt the limit set: %s\n", limits.c_str());
  const std::string solver = integrator_->summary(step_ - firstStepOfThisProcess_);
  if (!solver.empty()) std::fprintf(stderr, "  %s\n", solver.c_str());
  std::fprintf(stderr, "  instruction set: %s\n", instructionSet().c_str());
  // This process's steps over its wall time; after a restart also the whole run's (the time
  // of each earlier process up to its last checkpoint, as the steps).
  std::fprintf(stderr, "  particle-steps per second: %.4e\n",
               wallSeconds_ > 0 ? particleStepsOfThisProcess_ / wallSeconds_ : 0.0);
  if (!options_.restartDir.empty()) {
    const double wholeWall = earlierWallSeconds_ + wallSeconds_;
    std::fprintf(stderr,
                 "  since step 0, with the runs before the restart: %.4e particle-steps in "
                 "%.3f s, %.4e per second\n",
                 particleSteps_, wholeWall, wholeWall > 0 ? particleSteps_ / wholeWall : 0.0);
  }
  if (Communicator::size() > 1)
    std::fprintf(stderr,
                 "  %d ranks: particles per rank max/mean %.3f; sent %.4g bytes in all, %.4g per "
                 "step; communication at most %.3f s on a rank; %ld collective calls, %.1f per "
                 "step\n",
                 Communicator::size(), imbalance, communication[0],
                 step_ > firstStepOfThisProcess_
                     ? communication[0] / (step_ - firstStepOfThisProcess_)
                     : 0.0,
                 communication[1], collectiveCalls,
                 step_ > firstStepOfThisProcess_
                     ? static_cast<double>(collectiveCalls) / (step_ - firstStepOfThisProcess_)
                     : 0.0);
  std::fprintf(
      stderr, "  peak memory: %.1f MB, %.0f bytes per particle%s\n", peakBytes / 1e6,
      allPeaks / std::max<size_t>(particles, 1),
      Communicator::size() > 1
          ? " (the largest rank's peak; per particle: every rank's peak over all particles)"
          : "");
}

}  // namespace anode
