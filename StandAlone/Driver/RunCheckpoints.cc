#include "StandAlone/Driver/RunCheckpoints.h"

#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "Components/MPM/MPM.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/AtomicFile.h"
#include "Core/Util/BinaryStream.h"
#include "StandAlone/Driver/DataArchiver.h"

namespace anode {

RunCheckpoints::RunCheckpoints(const CheckpointSchedule& schedule, double startTime)
    : schedule_(schedule), lastScheduledTime_(startTime) {}

void RunCheckpoints::hashInput(const std::string& input) {
  input_ = input;
  inputHash_ = fileHash(input);
}

bool RunCheckpoints::isDue(long step, double time) const {
  return schedule_.isDue(step, time, lastScheduledTime_);
}

void RunCheckpoints::removeEarlierRuns(Collective every, const std::string& dir) const {
  collective::onRootTogether(
      every,
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

void RunCheckpoints::write(Collective every, CheckpointKind kind, CheckpointHeader state,
                           DataArchiver& archiver, const MPM& mpm) {
  archiver.writeHistory();  // history.csv holds every row up to the checkpoint's step
  const std::string dir = archiver.directory();
  // On the disk before the checkpoint, as the checkpoint before any older one is removed
  // (parts, then manifest, each synced with its directory): a crashed node leaves a whole one.
  const std::filesystem::path history = std::filesystem::path(dir) / "history.csv";
  if (Communicator::isRoot() && std::filesystem::exists(history)) syncToDisk(history.string());
  if (kind == CheckpointKind::Scheduled) lastScheduledTime_ = state.t;
  newest_ = checkpointPath(dir, state.step, kind);
  newestStep_ = state.step;
  state.threads = omp_get_max_threads();
  state.ranks = Communicator::size();
  state.inputHash = inputHash_;
  state.lastScheduledTime = lastScheduledTime_;
  writeCheckpoint(every, newest_, state, archiver, mpm);
  if (Communicator::isRoot()) {
    if (kind == CheckpointKind::Scheduled) {
      removeOldCheckpoints(dir, kind, schedule_.cycle);
      removeOldCheckpoints(dir, CheckpointKind::Automatic, 0);  // the scheduled one is newer
    } else {
      removeOldCheckpoints(dir, kind, 1);
    }
  }
  collective::barrier(every);
}

CheckpointHeader RunCheckpoints::restartFromNewest(Collective every, const std::string& dir,
                                                   DataArchiver& archiver, MPM& mpm) {
  if (Communicator::isRoot()) {
    removeTemporaryFiles(dir);
    removeUnfinishedCheckpointParts(dir);
  }
  collective::barrier(every);
  return loadNewest(every, dir, archiver, mpm);
}

CheckpointHeader RunCheckpoints::loadForReplay(Collective every, long lastGood, MPM& mpm) {
  const CheckpointHeader read = load(every, newest_, nullptr, mpm);
  if (read.step < lastGood && Communicator::isRoot())
    std::fprintf(stderr, "sus: replaying steps %ld to %ld from %s for the last good state\n",
                 read.step + 1, lastGood, newest_.c_str());
  return read;
}

void RunCheckpoints::checkReplayed(Collective every, long step, const HistoryRow& row,
                                   const MPM& mpm) {
  // The replayed state must be the one the run had: its history row says what it was.
  const StepSummary s = mpm.summarize(every);
  if ((row.step != step || row.kineticEnergy != s.kineticEnergy ||
       row.totalLithium != s.totalLithium) &&
      Communicator::isRoot())
    std::fprintf(
        stderr,
        "warning: the replayed step %ld differs from the run's (kinetic energy %.17g, not %.17g)\n",
        step, s.kineticEnergy, row.kineticEnergy);
}

void RunCheckpoints::atEnd(const std::string& dir, bool onRequest, bool reachedInputEnd,
                           const char* limit, long step, double t) const {
  if (onRequest)
    std::fprintf(stderr,
                 "sus: stopped on request (SIGTERM, SIGINT or SIGUSR1) after step %ld, t = "
                 "%.6e: checkpoint %s; continue with sus -restart %s\n",
                 step, t, newest_.c_str(), dir.c_str());
  else if (!reachedInputEnd)
    std::fprintf(stderr,
                 "sus: stopped after step %ld, t = %.6e, before the input's end (%s): "
                 "checkpoint %s; continue with sus -restart %s\n",
                 step, t, limit, newest_.c_str(), dir.c_str());
  else
    removeAutomaticCheckpoints(dir);
}

CheckpointHeader RunCheckpoints::loadNewest(Collective every, const std::string& dir,
                                            DataArchiver& archiver, MPM& mpm) {
  // Rank 0 lists the checkpoints, newest first, and checks their hashes; every rank then tries
  // the same ones (a rank whose view of the directory lags, or whose read fails, must not resume
  // from another step). One line each: "I path" intact, "D path" damaged (skipped), or "E error"
  // (an I/O error: the restart stops, nothing removed).
  std::string listed;
  if (Communicator::isRoot()) try {
      const std::vector<std::string> found = listCheckpoints(dir);
      if (found.empty())
        listed = "E no checkpoint in " + dir +
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
  std::istringstream lines(collective::broadcast(every, listed, 0));
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
    CheckpointHeader read;
    try {
      read = load(every, path, &archiver, mpm);  // fails on every rank together
    } catch (const std::runtime_error& e) {
      if (Communicator::isRoot())
        std::fprintf(stderr, "warning: skipping %s: %s\n", path.c_str(), e.what());
      continue;
    }
    // The outputs after it go only once it is loaded; an error here (a file that cannot be
    // written) stops the restart, and is no reason to go back to an older checkpoint.
    archiver.restoreOutputsTo(every, read.step);
    newest_ = path;
    newestStep_ = read.step;
    return read;
  }
  throw std::runtime_error("no complete checkpoint in " + dir + "/checkpoints");
}

CheckpointHeader RunCheckpoints::load(Collective every, const std::string& path,
                                      DataArchiver* outputs, MPM& mpm) {
  const CheckpointHeader read = loadCheckpoint(every, path, outputs, mpm);
  lastScheduledTime_ = read.lastScheduledTime;
  const double mostRead = collective::maximum(every, read.bytesRead);
  if (!Communicator::isRoot()) return read;
  if (Communicator::size() > 1 && outputs)
    std::fprintf(stderr, "sus: the rank that read most of %s read %.4g of its %.4g bytes (%.2f)\n",
                 path.c_str(), mostRead, read.bytesInAll, mostRead / read.bytesInAll);
  if (read.inputHash != inputHash_)
    std::fprintf(
        stderr,
        "warning: %s changed since %s was written; the run continues with the changed input\n",
        input_.c_str(), path.c_str());
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
  return read;
}

}  // namespace anode
