// A run of one input: setup (all validation, before any output), then the time loop.
#pragma once

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"
#include "Components/MPM/StateChecks.h"
#include "Components/MPM/SymmetryFaceWatch.h"
#include "Components/MPM/TimestepController.h"
#include "Core/Grid/TimeControl.h"
#include "StandAlone/Driver/DataArchiver.h"
#include "StandAlone/Driver/LoadBalance.h"
#include "StandAlone/Driver/Progress.h"
#include "StandAlone/Driver/RunCheckpoints.h"
#include "StandAlone/Driver/SceneOutput.h"

namespace anode {

class ImplicitStep;

struct RunOptions {
  std::string input;
  std::string outputDir;   // empty: from <filebase>
  std::string restartDir;  // continue the run in this directory from its newest checkpoint
  long maxTimesteps = 0;   // 0: as the input says
  bool ignoreUnsupported = false;
  bool progress = true;
  // Set the input up with its particles counted, not created, and stop there: for
  // MPM::describeDecomposition (sus --decompose N).
  bool countParticlesOnly = false;
};

class Simulation {
 public:
  // Reads and validates the whole input; throws InputError. Writes nothing.
  explicit Simulation(const RunOptions& options);
  // Same, from text held in memory (tests, studies); `name` stands for the file in messages.
  Simulation(const std::string& text, const std::string& name, const RunOptions& options);

  // Runs to the end, writing output; throws SimulationError if the state goes bad. Returns early,
  // after a checkpoint at the end of a step, when SIGTERM, SIGINT or SIGUSR1 asked it to stop
  // (stoppedOnRequest()).
  void run();
  bool stoppedOnRequest() const { return stoppedOnRequest_; }
  // One step without output (tests and studies).
  void advance() { advance(Communicator::everyRank()); }

  MPM& mpm() { return mpm_; }
  Integrator& integrator() { return *integrator_; }
  // The integrator of an implicit run (std::logic_error for an explicit one).
  const ImplicitStep& implicitStep() const;
  const TimeControl& timeControl() const { return time_; }
  const SceneOutput& scenes() const { return scenes_; }
  double time() const { return t_; }
  long step() const { return step_; }
  double dt() const { return dt_; }
  const std::vector<std::string>& warnings() const { return spec_->warnings(); }
  // The timings at the run's end (RunTimings.h).
  void printTimings(Collective) const;

 private:
  // Reads the input (readSpec sets spec_) on every rank, agreeing on its errors, then lays the
  // problem out over the ranks.
  void setup(const std::function<void()>& readSpec);
  void readInput();
  // The MPM's step from t_ over dt_: explicit, or quasi-static (which may retake it with a
  // smaller dt_).
  void stepMPM(Collective);
  // advance() on the run's tag: the step, its state checks and finishStep.
  void advance(Collective);
  // `problem` prefixed with the step under way and its end time, as diagnostics name them.
  std::string atThisStep(const std::string& problem) const;
  // The end of a step: time, step count and the next dt.
  void finishStep(Collective);
  // The time after t_ the next step ends on, if any (TimestepController::plan): the next output
  // time where steps end on them, and under error control a flux load curve's next time.
  std::optional<double> nextTimeToEndOn() const;
  // dt_ for the step from t_ (TimestepController's plan), the last step's limits grown from
  // `growsFrom`.
  void takeStableTimestep(Collective, double growsFrom);
  // The run's start: opens its directory (a new one, or the restart directory at its newest
  // checkpoint), reports the setup and, unless a restart, records and writes the initial state
  // with a checkpoint.
  void start(Collective, bool restart);
  // One step of the time loop: advance() (a failed step: writeStateOnStop, and the error
  // rethrown), the step's history row and counts, and its notes; returns the dt it took.
  double advanceAndRecord(Collective);
  // A step dropped by a stop request in one of its long phases (StopRequestedInStep): the
  // checkpoint and the output of the last completed step.
  void stopInStep(Collective);
  // The progress line after a step of `stepDt`, whose dt `stepLimit` set.
  void updateProgress(StableTimestep::Limit stepLimit, double stepDt, bool done);
  // The run's end: a stopped run's way to continue (RunCheckpoints::atEnd), report.html and the
  // wall time of the time loop.
  void finishRun();
  // Seconds since run() began.
  double wallTime() const;
  // Whether the run has reached the end <Time> sets (time, steps or wall time). Collective
  // when a wall time is set.
  bool finished(Collective) const;
  // Whether the run reached the end the input sets (maxTime or <max_Timesteps>), not a limit of
  // this process (--max-timesteps, <max_wall_time>) after which a restart continues.
  bool reachedInputEnd() const;
  // The lines on the run's setup: particles, grid, ranks, diffusion, the steps forecast,
  // symmetry faces.
  void reportSetup(Collective);
  // What the forecast of the run's steps needs (StepForecast.h), from its state now.
  struct StepForecastInput stepForecastInput() const;
  // Appends the state's row (after a step of `stepDt`, whose dt `dtRule` set: a DtRule, -1 for
  // the start) to the history; returns the particle count.
  size_t recordHistoryRow(Collective, double stepDt, int dtRule);
  // Writes the output of step_; `afterStep`: the grid labels hold the last step's nodal values.
  void writeOutput(Collective, bool afterStep);
  // Prints the symmetry-face warnings (from the rank that found them) and the diffusion's notes
  // (a galvanostatic current ending) of the step just taken.
  void reportRunNotes(Collective);
  // What any rank asks for at the end of a step (none after the last): to stop, and its own
  // checkpoint (kReplayInterval of wall time since the last one). One exchange.
  struct Requests {
    bool stop = false, replayCheckpoint = false;
  };
  Requests requestsOfAnyRank(Collective, bool done) const;
  // After a failed step: writes its particles and the last good state (DESIGN.md §8).
  void writeStateOnStop(Collective);
  // Brings the state back to the end of step_ (the last good one) by loading the newest
  // checkpoint and taking the same steps again (they are deterministic).
  void replayToLastGoodState(Collective);
  // Writes the state after step_ to a checkpoint (RunCheckpoints::write) and, at a scheduled one
  // or the start, writes report.html.
  void writeCheckpoint(Collective, CheckpointKind kind);
  // Rank 0: report.html of the output directory (RunReport.h) with `status`; a failure to write
  // it is a warning on stderr, not a stop (history.csv and the outputs it reads are intact).
  void writeReport(const std::string& status);
  // The clock and counters of the state after step_, as a checkpoint holds them.
  CheckpointHeader checkpointState() const;
  // Continues from a checkpoint's clock and counters.
  void resumeFrom(const CheckpointHeader& read);

  RunOptions options_;
  std::unique_ptr<ProblemSpec> spec_;
  MPM mpm_;
  TimeControl time_;
  std::optional<TimestepController> dtController_;  // after the input is read
  std::unique_ptr<Integrator> integrator_;          // chosen at setup by <time_integrator>
  DataArchiver archiver_;
  SceneOutput scenes_;
  StateChecks checks_;
  SymmetryFaceWatch symmetryFaces_;
  RunCheckpoints checkpoints_;
  LoadBalance balance_;
  double t_ = 0, dt_ = 0;
  double ruleDt_ = 0;       // the dt the limits chose; dt_ is less where clamped to an output time
  double lastStepDt_ = 0;   // the dt the last step took (an implicit one may retake it smaller)
  double growsFromDt_ = 0;  // the dt the next step's limits grow from (StepTaken::ruleDt)
  StableTimestep::Limit dtLimit_ = StableTimestep::Mechanics;  // the limit that set dt_
  bool dtSetByTimeControl_ = false;           // <Time>'s clamps changed that limit's dt
  std::array<long, kDtRules> stepsByRule_{};  // steps of this process's run per DtRule
  long step_ = 0;
  long inputMaxTimesteps_ = 0;  // <max_Timesteps> (0: none), before --max-timesteps
  double stateOfCharge_ = 0;    // of the last history row
  // Particle-steps of every rank: since step 0, restarts included (as of the state: checkpoints
  // hold it), and of this process's steps.
  double particleSteps_ = 0, particleStepsOfThisProcess_ = 0;
  long firstStepOfThisProcess_ = 0;  // the step it started from (a restart's)
  double wallSeconds_ = 0;           // of this process's time loop
  bool stoppedOnRequest_ = false;
  double earlierWallSeconds_ = 0;  // of the runs before a restart, for history.csv
  double setupSeconds_ = 0,
         setupPeakBytes_ = 0;  // this rank's setup: wall time, peak memory after it
  std::chrono::steady_clock::time_point runStart_;
  double newestCheckpointWallTime_ = 0;  // wallTime() when this process last wrote one
  int outputTask_ = 0, checkpointTask_ = 0;
  std::optional<ProgressReporter> progress_;  // on rank 0 unless RunOptions::progress is false
};

}  // namespace anode
