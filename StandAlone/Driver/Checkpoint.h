// Checkpoints (UINTAH_UPS.md §2.3): <checkpoint cycle="N" interval="T"/> (or timestepInterval="S")
// inside <DataArchiver> writes the state a step starts from to DIR/checkpoints/step_NNNNNN.ckpt
// at the first step whose time reaches each multiple of T (or every S steps), keeping the newest
// N. Each file is written under a temporary name, ends with a hash of its bytes and is renamed
// into place; older ones are removed only after that. `sus -restart DIR` continues from the
// newest complete one (DESIGN.md §6). The files' format is here too (writeCheckpoint).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "Components/MPM/StableTimestep.h"
#include "Components/MPM/TimestepController.h"
#include "Core/Parallel/Communicator.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

class DataArchiver;
class MPM;

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

// What a checkpoint holds besides the output state and the particles: the run that wrote it and
// its clock and counters at the end of `step`.
struct CheckpointHeader {
  int threads = 0;         // OpenMP threads of the run that wrote it
  int ranks = 1;           // its ranks (writing: Communicator::size())
  uint64_t inputHash = 0;  // fileHash of its input
  double t = 0, dt = 0;    // the state's time and the next step's dt
  double ruleDt = 0;       // the dt the limits chose, of which dt is a part (Simulation::ruleDt_)
  StableTimestep::Limit dtLimit = StableTimestep::Mechanics;  // the limit that set dt
  bool dtSetByTimeControl = false;                // <Time>'s clamps changed the limit's dt (DtRule)
  TimestepController::ErrorControl errorControl;  // the error controller's state
  long step = 0;
  double particleSteps = 0;      // of every rank since step 0
  double wallSeconds = 0;        // of the runs up to the checkpoint
  double lastScheduledTime = 0;  // of the newest scheduled checkpoint (before any: the start)
  // Reading: the bytes of the files this rank read, and of the whole checkpoint.
  double bytesRead = 0, bytesInAll = 0;
};

// The hash of a file's bytes (the input's, kept in the header).
uint64_t fileHash(const std::string& path);

// Writes the checkpoint `path`: on one rank one file (header, output state, particles); on
// several, every rank's part, then rank 0's manifest (header, output state, boxes, the parts'
// hashes) under the checkpoint's name, so that it is complete once that name exists.
void writeCheckpoint(Collective, const std::string& path, const CheckpointHeader& header,
                     const DataArchiver& archiver, const MPM& mpm);
// Reads the checkpoint `path` into `mpm` on every rank, its particles shared out among this run's
// ranks (a distributed one of another rank count: each rank reads its share of the parts, and
// the particles move to their new ranks), and into `outputs` (the output series and the last
// history row) unless null; returns its header. Throws std::runtime_error, on every rank together.
CheckpointHeader loadCheckpoint(Collective, const std::string& path, DataArchiver* outputs,
                                MPM& mpm);

}  // namespace anode
