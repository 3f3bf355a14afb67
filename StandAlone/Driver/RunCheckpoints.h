// A run's checkpoints (Checkpoint.h) in its output directory: when the input's are due, writing
// one and dropping the older ones, restarting from the newest complete one (and, at a stop, saying
// which one), and loading the newest one again, where a replay to the last good state starts.
#pragma once

#include <cstdint>
#include <string>

#include "StandAlone/Driver/Checkpoint.h"

namespace anode {

struct HistoryRow;

class RunCheckpoints {
 public:
  RunCheckpoints() = default;
  // The input's <checkpoint> (none: no scheduled ones); the run starts at `startTime`.
  RunCheckpoints(const CheckpointSchedule& schedule, double startTime);

  // Hashes the input file, for the checkpoints' headers and a restart's warning that it changed.
  void hashInput(const std::string& input);
  // True if the step that ended at `time` (number `step`) writes one of the input's checkpoints.
  bool isDue(long step, double time) const;
  // The newest checkpoint of either kind, where a replay to the last good state starts.
  const std::string& newest() const { return newest_; }
  // Its step (-1 before any).
  long newestStep() const { return newestStep_; }

  // A fresh run's directory may hold an earlier run's checkpoints (an -o used before): rank 0
  // removes them before this run writes anything (its history and outputs replace that run's, so
  // those checkpoints would restart into a history that is no longer theirs, and their step
  // numbers would count before this run's own where only the newest are kept). An error there
  // stops every rank.
  void removeEarlierRuns(Collective, const std::string& dir) const;
  // Writes the state after `state.step` (its clock and counters in `state`; the run that writes
  // it is filled in here) to a checkpoint of `kind`, after the history up to it, and drops the
  // oldest of its kind.
  void write(Collective, CheckpointKind kind, CheckpointHeader state, DataArchiver& archiver,
             const MPM& mpm);
  // Continues the run of directory `dir` (`archiver` reopened there) from its newest complete
  // checkpoint, after removing the files a killed run left there; returns its header.
  CheckpointHeader restartFromNewest(Collective, const std::string& dir, DataArchiver& archiver,
                                     MPM& mpm);
  // Loads the newest checkpoint again (not the outputs), from which the steps up to `lastGood`
  // are replayed; returns its header.
  CheckpointHeader loadForReplay(Collective, long lastGood, MPM& mpm);
  // Warns if the replayed state of step `step` is not the one the run had (its history row).
  static void checkReplayed(Collective, long step, const HistoryRow& row, const MPM& mpm);
  // Rank 0 at the end of the run in `dir`: a run stopped before the input's end (`onRequest`:
  // by a signal; otherwise at `limit`, --max-timesteps or <max_wall_time>) after `step`, at `t`,
  // says which checkpoint `sus -restart` continues from; one that reached it removes the
  // automatic checkpoints.
  void atEnd(const std::string& dir, bool onRequest, bool reachedInputEnd, const char* limit,
             long step, double t) const;

 private:
  // Loads the newest complete checkpoint of `dir`; returns its header.
  CheckpointHeader loadNewest(Collective, const std::string& dir, DataArchiver& archiver, MPM& mpm);
  // Loads one checkpoint (Checkpoint.h; the output series and history only if `outputs` is not
  // null) and warns of what differs from this run; throws std::runtime_error, on every rank
  // together.
  CheckpointHeader load(Collective, const std::string& path, DataArchiver* outputs, MPM& mpm);

  CheckpointSchedule schedule_;
  std::string input_;       // the input file
  uint64_t inputHash_ = 0;  // its hash, stored in checkpoints
  std::string newest_;      // of either kind
  long newestStep_ = -1;
  // The time of the newest of the input's checkpoints (before any: the start's).
  double lastScheduledTime_ = 0;
};

}  // namespace anode
