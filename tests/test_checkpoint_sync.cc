// A checkpoint is on the disk before an older one goes (a node that crashes after the removal
// leaves a whole checkpoint): sus runs with tests/checkpoint/sync_log.cc preloaded, which logs
// every fsync, rename and removal, and the log's order is checked, on 1 and 2 ranks. Label
// large: the sanitizers' runtime must come first in a process, before any preloaded library.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "tests/RunSus.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

std::vector<std::string> runLogged(const std::string& launcher, const fs::path& dir) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path log = dir / "sync.log";
  const std::string command =
      "ANODE_SYNC_LOG=" + log.string() + " LD_PRELOAD=" + ANODE_SYNC_LOG_LIBRARY + " " + launcher +
      " " + ANODE_SUS + " --threads 1 --max-timesteps 1000 -o " + (dir / "run").string() + " " +
      ANODE_SOURCE_DIR + "/tests/checkpoint/AutoCycleSlab.ups > " + (dir / "sus.log").string() +
      " 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::vector<std::string> lines;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Index of the last line before `end` equal to `line`, or -1.
long lastBefore(const std::vector<std::string>& lines, long end, const std::string& line) {
  for (long i = end - 1; i >= 0; --i)
    if (lines[i] == line) return i;
  return -1;
}

void expectSyncedBeforeRemoval(const std::vector<std::string>& lines, const fs::path& run,
                               int ranks) {
  static const std::regex manifest(R"(.*/checkpoints/(auto_)?step_\d+\.ckpt)");
  static const std::regex renamed(R"(rename (\S+) (.*/checkpoints/(auto_)?step_\d+\.ckpt))");
  const std::string checkpoints = fs::canonical(run / "checkpoints").string();
  int removals = 0;
  for (long i = 0; i < static_cast<long>(lines.size()); ++i) {
    if (lines[i].rfind("unlink ", 0) != 0 || !std::regex_match(lines[i].substr(7), manifest))
      continue;
    ++removals;
    SCOPED_TRACE(lines[i]);
    // The newest checkpoint written before it: its manifest synced, renamed, then its directory.
    long r = i - 1;
    std::smatch m;
    while (r >= 0 && !std::regex_match(lines[r], m, renamed)) --r;
    ASSERT_GE(r, 0) << "no checkpoint written before the removal";
    const std::string tmp = fs::weakly_canonical(m[1].str()).string();
    const std::string written = fs::weakly_canonical(m[2].str()).string();
    EXPECT_GE(lastBefore(lines, r, "fsync " + tmp), 0) << written << " renamed unsynced";
    bool directorySynced = false;
    for (long k = r + 1; k < i; ++k) directorySynced |= lines[k] == "fsync " + checkpoints;
    EXPECT_TRUE(directorySynced) << "checkpoints/ not synced after " << written;
    EXPECT_GE(lastBefore(lines, r, "fsync " + fs::canonical(run / "history.csv").string()), 0);
    for (int rank = 0; ranks > 1 && rank < ranks; ++rank) {
      char part[32];
      std::snprintf(part, sizeof part, "/rank_%04d.part", rank);
      const std::string parts = written + ".parts";
      long renamedPart = -1;
      for (long k = r - 1; k >= 0 && renamedPart < 0; --k)
        if (lines[k].rfind("rename ", 0) == 0 &&
            lines[k].size() > parts.size() + std::strlen(part) &&
            lines[k].compare(lines[k].size() - parts.size() - std::strlen(part), std::string::npos,
                             parts + part) == 0)
          renamedPart = k;
      ASSERT_GE(renamedPart, 0) << "part " << rank << " of " << written;
      const std::string partTmp = lines[renamedPart].substr(7, lines[renamedPart].find(' ', 7) - 7);
      EXPECT_GE(lastBefore(lines, renamedPart, "fsync " + partTmp), 0) << part;
      EXPECT_GE(lastBefore(lines, r, "fsync " + parts), 0) << parts;
    }
  }
  EXPECT_GE(removals, 2) << "the run removed fewer checkpoints than the test expects";
}

TEST(CheckpointSync, OnTheDiskBeforeAnOlderOneIsRemoved) {
  const fs::path dir = fs::temp_directory_path() / ("anode_sync_" + std::to_string(::getpid()));
  const std::vector<std::string> one = runLogged("", dir);
  expectSyncedBeforeRemoval(one, dir / "run", 1);
  const std::vector<std::string> two = runLogged(
      "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
      "OMPI_MCA_rmaps_base_oversubscribe=1 OMP_WAIT_POLICY=passive mpirun -np 2 -x LD_PRELOAD "
      "-x ANODE_SYNC_LOG",
      dir);
  expectSyncedBeforeRemoval(two, dir / "run", 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace anode
