// Checkpoints (UINTAH_UPS.md §2.3): <checkpoint cycle="N" interval="T"/> (or timestepInterval="S")
// inside <DataArchiver> writes the state a step starts from to DIR/checkpoints/step_NNNNNN.ckpt
// at the first step whose time reaches each multiple of T (or every S steps), keeping the newest
// N. Each file is written under a temporary name, ends with a hash of its bytes and is renamed
// into place; older ones are removed only after that. `sus -restart DIR` continues from the
// newest complete one (DESIGN.md §6).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct CheckpointSchedule {
  int cycle = 0;                   // checkpoints kept; 0: none written
  std::optional<double> interval;  // simulation time between checkpoints
  long stepInterval = 0;           // steps between checkpoints

  // Reads <checkpoint> of the <DataArchiver> block if there is one.
  static CheckpointSchedule fromInput(const PSNode& archiver);
  bool enabled() const { return cycle > 0; }
  // True if the step that ended at `time` (number `step`) writes a checkpoint, the last one
  // having been written at `lastTime` (the start time before the first).
  bool isDue(long step, double time, double lastTime) const;
};

// Scheduled checkpoints are the input's <checkpoint>; the run also writes one of its own at the
// start and every kReplayInterval seconds of wall time (an automatic one, at most one kept), so
// that a run that stops can replay its last good state (Simulation::writeStateOnStop) and any
// run can be restarted. Automatic ones are removed when the run ends.
enum class CheckpointKind { Scheduled, Automatic };
constexpr double kReplayInterval = 600;

// DIR/checkpoints/step_NNNNNN.ckpt (scheduled) or auto_step_NNNNNN.ckpt (automatic)
std::string checkpointPath(const std::string& dir, long step, CheckpointKind kind);
// A distributed run's checkpoint is the manifest at checkpointPath and one part per rank in the
// folder checkpointParts: rank_NNNN.part.
std::string checkpointParts(const std::string& checkpoint);
std::string checkpointPart(const std::string& checkpoint, int rank);
// The checkpoints of both kinds in DIR/checkpoints, newest (highest step) first.
std::vector<std::string> listCheckpoints(const std::string& dir);
// Removes all but the newest `keep` checkpoints of that kind.
void removeOldCheckpoints(const std::string& dir, CheckpointKind kind, int keep);
// At the end of a run: removes the automatic checkpoints, and DIR/checkpoints if that empties it.
void removeAutomaticCheckpoints(const std::string& dir);
// Removes the parts of distributed checkpoints whose manifest was never written (a killed run).
void removeUnfinishedCheckpointParts(const std::string& dir);
// Removes the temporary files a killed run left in DIR (names ending in .tmp<pid>); returns
// how many.
int removeTemporaryFiles(const std::string& dir);

}  // namespace anode
