// Pins checkpoint/restart (StandAlone/Driver/Checkpoint.h): a run interrupted after a checkpoint
// and continued with `sus -restart DIR` writes the same files as the uninterrupted run, bit for bit
// with the same thread count; a damaged newest checkpoint is skipped for the one before; a run
// killed with SIGKILL at any moment leaves every file under its final name complete, and can be
// continued to the uninterrupted run's result; a stop signal in a quasi-static step drops it.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <tinyxml2.h>
#include <unistd.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLUnstructuredGridReader.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <random>
#include <regex>
#include <sstream>
#include <thread>

#include "Core/ProblemSpec/ProblemSpec.h"
#include "Core/Util/BinaryStream.h"
#include "RunSus.h"
#include "StandAlone/Driver/Checkpoint.h"
#include "StandAlone/Driver/DataArchiver.h"
#include "TestFiles.h"

namespace fs = std::filesystem;

namespace anode {
namespace {

using testing::readFile;

const std::string kSus = ANODE_SUS;
const std::string kSource = ANODE_SOURCE_DIR;

// A scratch directory for one test, removed at the end.
struct Scratch {
  fs::path dir;
  explicit Scratch(const std::string& name) {
    dir =
        fs::temp_directory_path() / ("anode_checkpoint_" + name + "_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  ~Scratch() { fs::remove_all(dir); }
};

// sus on one process of 2 threads (an implicit input too) with `args`, then `more`.
testing::SusResult sus(std::vector<std::string> args, const std::vector<std::string>& more = {}) {
  args.insert(args.begin(), {"--one-process", "--threads", "2"});
  args.insert(args.end(), more.begin(), more.end());
  return testing::runSus(args);
}

// The input with <checkpoint> added to <DataArchiver> (when `checkpoint` is not empty).
fs::path withCheckpoint(const std::string& input, const std::string& checkpoint,
                        const fs::path& to) {
  std::string text = readFile(input);
  if (!checkpoint.empty()) {
    const size_t end = text.find("</DataArchiver>");
    EXPECT_NE(end, std::string::npos);
    text.insert(end, checkpoint);
  }
  std::ofstream(to) << text;
  return to;
}

// history.csv without its last column (wall seconds, which differ run to run).
std::string historyWithoutWallTime(const fs::path& dir) {
  std::istringstream in(readFile(dir / "history.csv"));
  std::string line, out;
  while (std::getline(in, line)) out += line.substr(0, line.rfind(',')) + "\n";
  return out;
}

// Every output file (all but checkpoints, history.csv and report.html, which holds the wall
// time and the directory) has the same bytes in both runs, and history.csv the same rows but for
// the wall time.
void expectSameOutputs(const fs::path& a, const fs::path& b) {
  const auto compared = [](const std::string& rel) {
    return rel.rfind("checkpoints", 0) != 0 && rel != "history.csv" && rel != "report.html";
  };
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    const std::string rel = fs::relative(e.path(), a).string();
    if (e.is_regular_file() && compared(rel)) files.push_back(rel);
  }
  for (const auto& e : fs::recursive_directory_iterator(b)) {
    const std::string rel = fs::relative(e.path(), b).string();
    if (e.is_regular_file() && compared(rel)) {
      EXPECT_TRUE(fs::exists(a / rel)) << rel << " only in the restarted run";
    }
  }
  EXPECT_TRUE(fs::exists(a / "report.html") && fs::exists(b / "report.html"));
  ASSERT_GT(files.size(), 3u);
  for (const std::string& f : files) {
    ASSERT_TRUE(fs::exists(b / f)) << f << " missing in the restarted run";
    EXPECT_TRUE(readFile(a / f) == readFile(b / f)) << f << " differs";
  }
  EXPECT_EQ(historyWithoutWallTime(a), historyWithoutWallTime(b));
}

struct RestartCase {
  std::string name, input, checkpoint;  // checkpoint: element to add ("" if the input has one)
  long interruptAt;                     // steps of the interrupted run
  std::vector<std::string> steps;       // e.g. {"--max-timesteps", "150"} for both runs
};

void PrintTo(const RestartCase& c, std::ostream* os) {
  *os << c.name;
}

class Restart : public ::testing::TestWithParam<RestartCase> {};

TEST_P(Restart, ContinuesBitForBit) {
  const RestartCase& c = GetParam();
  if (!fs::exists(c.input)) GTEST_SKIP() << "input not present: " << c.input;
  Scratch s(c.name);
  const fs::path input = withCheckpoint(c.input, c.checkpoint, s.dir / "input.ups");
  const testing::SusResult whole = sus(c.steps, {"-o", (s.dir / "whole").string(), input.string()});
  ASSERT_EQ(whole.exitCode, 0) << whole.output;
  ASSERT_EQ(sus({"--max-timesteps", std::to_string(c.interruptAt), "-o", (s.dir / "parts").string(),
                 input.string()})
                .exitCode,
            0);
  // The stop at --max-timesteps leaves a checkpoint at its step: the restart takes no step twice.
  const std::vector<std::string> checkpoints = listCheckpoints((s.dir / "parts").string());
  ASSERT_FALSE(checkpoints.empty()) << "the interrupted run wrote no checkpoint";
  char name[32];
  std::snprintf(name, sizeof name, "step_%06ld.ckpt", c.interruptAt);
  EXPECT_NE(checkpoints.front().find(name), std::string::npos) << checkpoints.front();
  const testing::SusResult second = sus({"-restart", (s.dir / "parts").string()}, c.steps);
  ASSERT_EQ(second.exitCode, 0) << second.output;
  EXPECT_NE(second.output.find("restarting from " + checkpoints.front()), std::string::npos)
      << second.output;
  expectSameOutputs(s.dir / "whole", s.dir / "parts");
}

INSTANTIATE_TEST_SUITE_P(
    Inputs, Restart,
    ::testing::Values(
        // 3-D CPDI pillar: flux BCs, non_linear1 with pressure, plasticity, a rendered scene.
        RestartCase{"pillar",
                    kSource + "/inputs/Pillar/PillarLithiation.ups",
                    "<checkpoint cycle=\"2\" timestepInterval=\"40\"/>",
                    100,
                    {"--max-timesteps", "150"}},
        // Uintah's 2-D pillar, unmodified (its own <checkpoint interval>): particle splitting.
        RestartCase{"nanopillar2d",
                    kSource + "/../shared/inputs/uintah/NanoPillar2D_FBC_Sym.ups",
                    "",
                    500,
                    {}},
        // Auto-cycled flux, checkpoint after the first flip.
        RestartCase{"autocycle", kSource + "/tests/checkpoint/AutoCycleSlab.ups", "", 1000, {}},
        // A <diff_curve> past its second switch at the checkpoint: the curve's interval is state.
        RestartCase{"diffcurve", kSource + "/tests/checkpoint/DiffCurveSlab.ups", "", 800, {}},
        // Quasi-static steps: dt 10 us four times, then 6 and 4 by Newton's iteration counts;
        // the restart at step 5 must take step 6 with the dt of the run that was interrupted.
        RestartCase{"implicit",
                    kSource + "/inputs/Stability/Implicit_yield_0.14_walls.ups",
                    "<checkpoint cycle=\"2\" timestepInterval=\"1\"/>",
                    5,
                    {}},
        // Quasi-static steps chosen by their error estimates: the controller's state (the last
        // two estimates, their sum) is in the checkpoint.
        RestartCase{"implicit_error_control",
                    kSource + "/tests/checkpoint/ErrorControlledBar.ups",
                    "",
                    6,
                    {}},
        // A surface reaction's potential (the cutoff at step 63 ended its current): the
        // potentials are in the checkpoint, and the current resumes at step 104 as uninterrupted.
        RestartCase{"surface_reaction",
                    kSource + "/inputs/Verification/SurfaceReactionBar.ups",
                    "<checkpoint cycle=\"2\" timestepInterval=\"10\"/>",
                    70,
                    {"--max-timesteps", "110"}},
        // Implicit dynamics: the particles' accelerations (Newmark's state) are in the
        // checkpoint; blocks colliding at step 10.
        RestartCase{"implicit_dynamic",
                    kSource + "/tests/parallel/ImplicitCollidingBlocks.ups",
                    "",
                    10,
                    {"--max-timesteps", "15"}}),
    [](const ::testing::TestParamInfo<RestartCase>& info) { return info.param.name; });

TEST(Restart, SkipsADamagedNewestCheckpoint) {
  Scratch s("damaged");
  const std::string input = kSource + "/tests/checkpoint/AutoCycleSlab.ups";
  ASSERT_EQ(sus({"-o", (s.dir / "whole").string(), input}).exitCode, 0);
  ASSERT_EQ(sus({"--max-timesteps", "1000", "-o", (s.dir / "parts").string(), input}).exitCode, 0);
  const std::vector<std::string> checkpoints = listCheckpoints((s.dir / "parts").string());
  // The stop's at step 1000, then the schedule's at 900 and 600 (cycle = 2).
  ASSERT_EQ(checkpoints.size(), 3u);
  EXPECT_NE(checkpoints[0].find("auto_step_001000.ckpt"), std::string::npos) << checkpoints[0];
  // The history is in history.csv, not in the checkpoints: 300 steps more add only the .pvd
  // entries of their outputs, far less than 300 rows.
  EXPECT_LT(fs::file_size(checkpoints[1]), fs::file_size(checkpoints[2]) + 300 * 40);
  EXPECT_TRUE(hasIntactHash(checkpoints[0]));
  fs::resize_file(checkpoints[0], fs::file_size(checkpoints[0]) / 2);
  EXPECT_FALSE(hasIntactHash(checkpoints[0]));
  // A kill during the append to history.csv cuts its last line short: the restart drops it with
  // the rows after its checkpoint.
  std::ofstream(s.dir / "parts" / "history.csv", std::ios::app) << "1001,1.5e";
  const testing::SusResult second = sus({"-restart", (s.dir / "parts").string()});
  ASSERT_EQ(second.exitCode, 0) << second.output;
  const std::string& log = second.output;
  EXPECT_NE(log.find("skipping " + checkpoints[0]), std::string::npos) << log;
  EXPECT_NE(log.find("restarting from " + checkpoints[1]), std::string::npos) << log;
  expectSameOutputs(s.dir / "whole", s.dir / "parts");
}

const std::string kSlab = kSource + "/tests/checkpoint/AutoCycleSlab.ups";

// AutoCycleSlab stopped at step 1000 (--max-timesteps) in DIR/run, which it returns: its
// checkpoints are the stop's (1000) and the schedule's 900 and 600 (cycle = 2).
fs::path slabStoppedAtStep1000(const Scratch& s) {
  const fs::path run = s.dir / "run";
  EXPECT_EQ(sus({"--max-timesteps", "1000", "-o", run.string(), kSlab}).exitCode, 0);
  EXPECT_EQ(listCheckpoints(run.string()).size(), 3u);
  return run;
}

// An output the restart cannot restore (here history.csv, which a directory stands in for: as
// root no file permission stops a write) stops it with exit 1 naming the file, and every output
// stays: an I/O error is not a damaged checkpoint, to be answered by going back to an older one
// and removing what came after it.
TEST(Restart, AnOutputItCannotRestoreStopsItWithEveryOutputKept) {
  Scratch s("unwritable");
  const fs::path run = slabStoppedAtStep1000(s);
  ASSERT_FALSE(::testing::Test::HasFailure());
  const auto files = [&] {
    std::vector<std::string> names;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(run))
      if (e.path().string().find("checkpoints") == std::string::npos)
        names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  fs::rename(run / "history.csv", s.dir / "history.csv");
  fs::create_directory(run / "history.csv");
  const std::vector<std::string> before = files();
  const testing::SusResult restart = sus({"-restart", run.string()});
  EXPECT_EQ(restart.exitCode, 1) << restart.output;
  EXPECT_NE(restart.output.find((run / "history.csv").string()), std::string::npos)
      << restart.output;
  EXPECT_EQ(restart.output.find("skipping"), std::string::npos) << restart.output;
  EXPECT_EQ(files(), before);
  EXPECT_EQ(listCheckpoints(run.string()).size(), 3u);
}

// A fresh run into the directory of an earlier, longer one: the earlier run's checkpoints (steps
// 600, 900, 1000) go first, so the fresh run keeps its own newest ones and a restart continues it,
// not the earlier run. With them left, the restart took the earlier run's step 900.
TEST(Checkpoint, AFreshRunRemovesAnEarlierRunsCheckpoints) {
  Scratch s("rerun");
  const fs::path run = slabStoppedAtStep1000(s);
  ASSERT_FALSE(::testing::Test::HasFailure());
  const testing::SusResult again = sus({"--max-timesteps", "400", "-o", run.string(), kSlab});
  ASSERT_EQ(again.exitCode, 0) << again.output;
  EXPECT_NE(again.output.find("removed 3 checkpoint(s) of an earlier run"), std::string::npos)
      << again.output;
  const std::vector<std::string> left = listCheckpoints(run.string());
  ASSERT_FALSE(left.empty());
  EXPECT_NE(left[0].find("auto_step_000400.ckpt"), std::string::npos) << left[0];
  for (const std::string& c : left) {
    const std::smatch m = [&] {
      std::smatch found;
      std::regex_search(c, found, std::regex(R"(step_(\d+)\.ckpt$)"));
      return found;
    }();
    ASSERT_FALSE(m.empty()) << c;
    EXPECT_LE(std::stol(m[1].str()), 400) << c;
  }
  const testing::SusResult restart = sus({"--max-timesteps", "450", "-restart", run.string()});
  ASSERT_EQ(restart.exitCode, 0) << restart.output;
  EXPECT_NE(restart.output.find("(step 400,"), std::string::npos) << restart.output;
}

// The end summary of a restarted run gives the particle-steps per second of its own steps (not of
// every step since step 0 over its own wall time), and the whole run's beside them.
TEST(Restart, SummaryRateCountsTheStepsOfThisRun) {
  Scratch s("rate");
  const std::string run = (s.dir / "run").string();
  const std::string input = kSource + "/tests/checkpoint/AutoCycleSlab.ups";
  ASSERT_EQ(sus({"--max-timesteps", "1000", "-o", run, input}).exitCode, 0);
  const testing::SusResult restart = sus({"-restart", run});  // to the input's 2000 steps
  ASSERT_EQ(restart.exitCode, 0) << restart.output;
  std::smatch m;
  static const std::regex from(R"rx(restarting from \S+ \(step (\d+),)rx");
  ASSERT_TRUE(std::regex_search(restart.output, m, from)) << restart.output;
  const long first = std::stol(m[1]);
  EXPECT_EQ(first, 1000);  // the stop's own checkpoint
  // At the input's end the run's own checkpoints are removed (the schedule's stay).
  for (const std::string& c : listCheckpoints(run))
    EXPECT_EQ(c.find("auto_step"), std::string::npos) << c;
  static const std::regex summary(
      R"rx(sus: 2000 steps, t = \S+, (\d+) particles, wall (\S+) s \(after the restart: (\d+) steps, from step (\d+)\))rx");
  ASSERT_TRUE(std::regex_search(restart.output, m, summary)) << restart.output;
  const double particles = std::stod(m[1]), wall = std::stod(m[2]);
  const long steps = std::stol(m[3]);
  EXPECT_EQ(std::stol(m[4]), first);
  EXPECT_EQ(steps, 2000 - first);
  static const std::regex rate(R"rx(particle-steps per second: (\S+))rx");
  ASSERT_TRUE(std::regex_search(restart.output, m, rate)) << restart.output;
  ASSERT_GT(wall, 0);
  // The wall time is printed to 1 ms, the rate to 5 digits.
  EXPECT_NEAR(std::stod(m[1]) * wall / (steps * particles), 1.0, 0.0005 / wall + 1e-4)
      << restart.output;
  static const std::regex whole(
      R"rx(since step 0, with the runs before the restart: (\S+) particle-steps in)rx");
  ASSERT_TRUE(std::regex_search(restart.output, m, whole)) << restart.output;
  EXPECT_NEAR(std::stod(m[1]) / (2000 * particles), 1.0, 1e-4) << restart.output;
}

// Outputs whose files are gone (removed by hand, or not carried with the checkpoint to another
// machine) leave the series on restart: particles.pvd names no missing file.
TEST(Restart, LeavesMissingOutputsOutOfTheSeries) {
  Scratch s("missing");
  const std::string run = (s.dir / "run").string();
  ASSERT_EQ(
      sus({"--max-timesteps", "1000", "-o", run, kSource + "/tests/checkpoint/AutoCycleSlab.ups"})
          .exitCode,
      0);
  fs::remove(s.dir / "run" / "particles" / "step_000250.vtu");
  const testing::SusResult restart = sus({"--max-timesteps", "1100", "-restart", run});
  ASSERT_EQ(restart.exitCode, 0) << restart.output;
  EXPECT_NE(restart.output.find("1 particles output(s) of the checkpoint's series are not in"),
            std::string::npos)
      << restart.output;
  const std::string pvd = readFile(s.dir / "run" / "particles.pvd");
  EXPECT_EQ(pvd.find("step_000250"), std::string::npos) << pvd;
  EXPECT_NE(pvd.find("step_000500"), std::string::npos) << pvd;
  static const std::regex file(R"rx(file="([^"]+)")rx");
  for (std::sregex_iterator m(pvd.begin(), pvd.end(), file), end; m != end; ++m)
    EXPECT_TRUE(fs::exists(s.dir / "run" / (*m)[1].str())) << (*m)[1].str();
}

// A restart that cannot write particles.pvd stops (exit code 1) with every output file and
// history.csv as they were: the outputs after its checkpoint (here the stop's output at the
// checkpoint's own step) go only once the series and the history are written.
TEST(Restart, KeepsEveryOutputWhenItCannotWriteTheSeries) {
  Scratch s("unwritable");
  const fs::path run = s.dir / "run";
  ASSERT_EQ(sus({"--max-timesteps", "1000", "-o", run.string(),
                 kSource + "/tests/checkpoint/AutoCycleSlab.ups"})
                .exitCode,
            0);
  const auto outputs = [&] {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(run / "particles"))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  };
  const std::vector<std::string> before = outputs();
  ASSERT_NE(std::find(before.begin(), before.end(), "step_001000.vtu"), before.end());
  const std::string history = readFile(run / "history.csv");
  fs::remove(run / "particles.pvd");
  fs::create_directories(run / "particles.pvd" / "in_the_way");
  const testing::SusResult restart = sus({"--max-timesteps", "1100", "-restart", run.string()});
  EXPECT_EQ(restart.exitCode, 1) << restart.output;
  EXPECT_EQ(outputs(), before);
  EXPECT_EQ(readFile(run / "history.csv"), history);
}

TEST(CheckpointSchedule, KeepsUintahsTwoWithoutCycle) {
  const auto spec = ProblemSpec::fromText(
      "<Uintah_specification><DataArchiver><checkpoint timestepInterval=\"5\"/></DataArchiver>"
      "</Uintah_specification>",
      "checkpoint.ups");
  const CheckpointSchedule s =
      CheckpointSchedule::fromInput(spec->root().requireChild("DataArchiver"));
  EXPECT_EQ(s.cycle, 2);
  EXPECT_EQ(s.stepInterval, 5);
}

// A checkpoint's bytes depend on the state only: the padding of the history row it holds,
// whatever the memory held where the row was built, is stored as zeros.
TEST(Checkpoint, HistoryRowPaddingIsStoredAsZeros) {
  Scratch s("padding");
  std::vector<std::string> saved;
  for (const unsigned char fill : {0x00, 0xab}) {
    alignas(HistoryRow) unsigned char memory[sizeof(HistoryRow)];
    std::memset(memory, fill, sizeof memory);
    HistoryRow* row = new (memory) HistoryRow;  // default-initialized: the bytes stay
    row->step = 7;
    row->particles = 20;
    row->time = row->dt = row->kineticEnergy = row->minJ = row->maxJ = row->wallSeconds = 1;
    row->diffusion = true;
    row->totalLithium = row->minConcentration = row->maxConcentration = 0.5;
    row->lithiumRate = row->stateOfCharge = 0.5;
    DataArchiver archiver;
    archiver.recordHistory(*row, StepRecord{});
    const fs::path path = s.dir / ("state_" + std::to_string(fill));
    BinaryWriter out(path.string());
    archiver.saveState(out);
    out.finish();
    saved.push_back(readFile(path));
  }
  EXPECT_TRUE(saved[0] == saved[1]);
}

TEST(Restart, WithoutACheckpointIsAnError) {
  Scratch s("none");
  ASSERT_EQ(sus({"--max-timesteps", "3", "-o", (s.dir / "run").string(),
                 kSource + "/inputs/Pillar/PillarImpact.ups"})
                .exitCode,
            0);
  // The stop left its own checkpoint; without it (removed, or a run to the input's end without
  // a schedule) there is none.
  ASSERT_EQ(listCheckpoints((s.dir / "run").string()).size(), 1u);
  fs::remove_all(s.dir / "run" / "checkpoints");
  const testing::SusResult restart = sus({"-restart", (s.dir / "run").string()});
  EXPECT_EQ(restart.exitCode, 1);
  EXPECT_NE(restart.output.find("no checkpoint in"), std::string::npos) << restart.output;
}

// A run stopped by a diagnostic (exit 3) writes the last good state by replaying from its newest
// checkpoint: the automatic one at the start, or a scheduled one. That state is the one a run
// ending normally at the same step writes, byte for byte.
TEST(Restart, StoppedRunReplaysItsLastGoodState) {
  const std::string unstable =
      kSource + "/inputs/Stability/Multiplier_0.8.ups";  // stops at step 33
  for (const std::string& schedule :
       {std::string(), std::string("<checkpoint cycle=\"1\" timestepInterval=\"10\"/>")}) {
    Scratch s(schedule.empty() ? "replay_auto" : "replay_scheduled");
    const fs::path input = withCheckpoint(unstable, schedule, s.dir / "input.ups");
    const testing::SusResult stopped = sus({"-o", (s.dir / "stopped").string(), input.string()});
    ASSERT_EQ(stopped.exitCode, 3) << stopped.output;
    const std::string& log = stopped.output;
    const std::smatch m = [&] {
      std::smatch found;
      std::regex_search(log, found, std::regex(R"(last good state \(step (\d+),)"));
      return found;
    }();
    ASSERT_FALSE(m.empty()) << log;
    const long lastGood = std::stol(m[1].str());
    EXPECT_NE(log.find(schedule.empty() ? "auto_step_000000.ckpt" : "step_000030.ckpt"),
              std::string::npos)
        << log;
    EXPECT_EQ(log.find("warning"), std::string::npos) << log;
    ASSERT_EQ(sus({"--max-timesteps", std::to_string(lastGood), "-o", (s.dir / "ended").string(),
                   input.string()})
                  .exitCode,
              0);
    char name[64];
    std::snprintf(name, sizeof name, "particles/step_%06ld.vtu", lastGood);
    ASSERT_TRUE(fs::exists(s.dir / "stopped" / name)) << name;
    EXPECT_TRUE(readFile(s.dir / "stopped" / name) == readFile(s.dir / "ended" / name)) << name;
    // Automatic checkpoints do not outlive the run; scheduled ones stay.
    EXPECT_EQ(fs::exists(s.dir / "stopped" / "checkpoints"), !schedule.empty());
  }
}

// Every file under its final name is complete: VTU files read with all particles, .pvd files
// parse and list existing files, history.csv rows are whole (but for a last one cut short),
// checkpoints carry their hash, PNGs end with their IEND chunk, report.html parses.
void expectEveryFileComplete(const fs::path& dir, long particles) {
  static const std::regex temporary(R"(.*\.tmp\d+)");
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const fs::path& p = e.path();
    const std::string name = p.filename().string();
    if (std::regex_match(name, temporary)) continue;  // not a final name: removed on restart
    if (p.extension() == ".vtu") {
      auto reader = vtkSmartPointer<vtkXMLUnstructuredGridReader>::New();
      reader->SetFileName(p.c_str());
      reader->Update();
      EXPECT_EQ(reader->GetOutput()->GetNumberOfPoints(), particles) << p;
    } else if (p.extension() == ".pvd") {
      tinyxml2::XMLDocument doc;
      ASSERT_EQ(doc.LoadFile(p.c_str()), tinyxml2::XML_SUCCESS) << p;
      const tinyxml2::XMLElement* collection = doc.RootElement()->FirstChildElement("Collection");
      ASSERT_NE(collection, nullptr) << p;
      for (const auto* d = collection->FirstChildElement("DataSet"); d;
           d = d->NextSiblingElement("DataSet"))
        EXPECT_TRUE(fs::exists(dir / d->Attribute("file"))) << d->Attribute("file");
    } else if (name == "history.csv") {
      std::istringstream in(readFile(p));
      std::string header, line;
      std::getline(in, header);
      const auto columns = std::count(header.begin(), header.end(), ',');
      // Rows are appended: a kill during the append may cut the last one short, no other.
      while (std::getline(in, line) && !in.eof())
        EXPECT_EQ(std::count(line.begin(), line.end(), ','), columns) << line;
    } else if (p.extension() == ".ckpt") {
      EXPECT_TRUE(hasIntactHash(p.string())) << p;
    } else if (name == "report.html") {
      tinyxml2::XMLDocument doc;
      EXPECT_EQ(doc.LoadFile(p.c_str()), tinyxml2::XML_SUCCESS) << p;
    } else if (p.extension() == ".png") {
      const std::string png = readFile(p);
      EXPECT_TRUE(png.size() > 12 && png.compare(png.size() - 8, 4, "IEND") == 0) << p;
    }
  }
}

// Starts sus with `args` in a child process, its stderr to `log`; returns the child's pid.
// Starts sus with `args`, or `launcher` (e.g. mpirun -np 2) with sus and `args`; its stderr to
// `log`.
pid_t startSus(const std::vector<std::string>& args, const fs::path& log,
               const std::vector<std::string>& launcher = {}) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : launcher) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(const_cast<char*>(kSus.c_str()));
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    FILE* out = std::freopen(log.c_str(), "w", stderr);
    (void)out;
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

// Starts sus with `args` and kills it with SIGKILL after `delay`.
void runAndKill(const std::vector<std::string>& args, std::chrono::milliseconds delay,
                const fs::path& log) {
  const pid_t pid = startSus(args, log);
  ASSERT_GE(pid, 0);
  std::this_thread::sleep_for(delay);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
}

// Kills: 5 by default; ANODE_KILLS=N for a longer study (docs/stability.md).
int numberOfKills() {
  const char* n = std::getenv("ANODE_KILLS");
  return n ? std::max(1, std::atoi(n)) : 5;
}

int temporaryFiles(const fs::path& dir) {
  static const std::regex temporary(R"(.*\.tmp\d+)");
  int n = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (std::regex_match(e.path().filename().string(), temporary)) ++n;
  return n;
}

// SIGTERM stops the run at the end of its step with a checkpoint there (exit code 4): the
// restart continues from that very step to the uninterrupted run's files.
TEST(Restart, SigtermStopsWithACheckpointAtTheLastStep) {
  Scratch s("sigterm");
  const std::string input = kSource + "/inputs/Pillar/PillarLithiation.ups";
  const fs::path run = s.dir / "stopped";
  const pid_t pid = startSus({"--threads", "1", "-o", run.string(), input}, s.dir / "stopped.log");
  ASSERT_GE(pid, 0);
  // The first checkpoint is written once setup is done: then the steps run.
  for (int i = 0; i < 600 && listCheckpoints(run.string()).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  kill(pid, SIGTERM);
  int status = 0;
  waitpid(pid, &status, 0);
  const std::string log = readFile(s.dir / "stopped.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 4) << log;
  EXPECT_NE(log.find("stopped on request"), std::string::npos) << log;
  const std::vector<std::string> checkpoints = listCheckpoints(run.string());
  ASSERT_FALSE(checkpoints.empty());
  std::istringstream history(readFile(run / "history.csv"));
  std::string row, last;
  while (std::getline(history, row)) last = row;
  const long stoppedAt = std::stol(last);
  EXPECT_NE(checkpoints.front().find(std::to_string(stoppedAt) + ".ckpt"), std::string::npos)
      << checkpoints.front() << " is not at the last step " << stoppedAt;
  const std::string steps = std::to_string(stoppedAt + 5);
  ASSERT_EQ(
      sus({"--threads", "1", "--max-timesteps", steps, "-o", (s.dir / "whole").string(), input})
          .exitCode,
      0);
  const testing::SusResult restart =
      sus({"--threads", "1", "--max-timesteps", steps, "-restart", run.string()});
  ASSERT_EQ(restart.exitCode, 0) << restart.output;
  expectSameOutputs(s.dir / "whole", run);
}

TEST(Restart, KilledRunsLeaveCompleteFilesAndContinueToTheSameResult) {
  Scratch s("killed");
  // Output every 2 steps and a checkpoint every 3 (and pictures), so that kills often land during
  // a write.
  std::string text = readFile(kSource + "/inputs/Pillar/PillarLithiation.ups");
  text = std::regex_replace(text, std::regex("<outputInterval>[^<]*</outputInterval>"),
                            "<outputTimestepInterval>2</outputTimestepInterval>");
  text.insert(text.find("</DataArchiver>"), "<checkpoint cycle=\"3\" timestepInterval=\"3\"/>");
  const fs::path input = s.dir / "input.ups";
  std::ofstream(input) << text;
  const auto started = std::chrono::steady_clock::now();
  const testing::SusResult whole =
      sus({"--max-timesteps", "120", "-o", (s.dir / "whole").string(), input.string()});
  ASSERT_EQ(whole.exitCode, 0) << whole.output;
  const auto wholeRun = std::chrono::duration_cast<std::chrono::milliseconds>(
      std::chrono::steady_clock::now() - started);
  const std::string run = (s.dir / "killed").string();
  std::mt19937 random(1);
  // ms: from setup to a few outputs in (a tenth of the whole run, at least 1200 ms: on a loaded
  // machine a fixed 1200 ms could end every try before the first checkpoint).
  std::uniform_int_distribution<int> delay(250,
                                           std::max(1200, static_cast<int>(wholeRun.count() / 10)));
  const int kills = numberOfKills();
  int duringWrites = 0;
  // Each kill before the first checkpoint doubles the next delay: under load, the fresh starts
  // could otherwise all end before step 3 and leave no checkpoint to resume from.
  int freshStarts = 0;
  for (int k = 0; k < kills; ++k) {
    const bool resume = !listCheckpoints(run).empty();
    const std::vector<std::string> args =
        resume
            ? std::vector<std::string>{"--threads", "2", "--max-timesteps", "120", "-restart", run}
            : std::vector<std::string>{"--threads", "2", "--max-timesteps", "120",
                                       "-o",        run, input.string()};
    const int scale = resume ? 1 : 1 << freshStarts++;
    runAndKill(args, std::chrono::milliseconds(scale * delay(random)), s.dir / "kill.log");
    if (!fs::exists(run)) continue;  // killed before it made its directory (a loaded machine)
    if (temporaryFiles(run) > 0) ++duringWrites;
    expectEveryFileComplete(run, 12660);
    if (::testing::Test::HasFailure()) break;
  }
  std::printf("%d kills, %d of them during a write (a temporary file left behind)\n", kills,
              duringWrites);
  ASSERT_FALSE(listCheckpoints(run).empty()) << "no checkpoint written before the kills";
  const testing::SusResult last = sus({"--max-timesteps", "120", "-restart", run});
  ASSERT_EQ(last.exitCode, 0) << last.output;
  expectEveryFileComplete(run, 12660);
  expectSameOutputs(s.dir / "whole", run);
}

// A stop signal in a quasi-static step drops the step under way within 5 s (exit code 4): the
// checkpoint of the step before is the run's last, and the restart continues from it to the
// uninterrupted run's files. On one process (its threads) and in the one-command mode (two ranks
// under mpirun, the signal to sus passed on to mpirun as SIGUSR1), for each stop signal; and
// under mpirun started by hand, SIGUSR1 sent to mpirun (SIGINT and SIGTERM it turns into
// SIGKILL; its restart is the one-command mode's, the same two ranks of one thread).
struct StopCase {
  std::string name;
  std::vector<std::string> mode;  // the arguments that choose one process or the ranks
  int signal;
  bool restart;                            // and the restart compared with the uninterrupted run
  std::vector<std::string> launcher = {};  // the stopped run's (mpirun -np 2), then mode's
};

void PrintTo(const StopCase& c, std::ostream* os) {
  *os << c.name;
}

class StopInStep : public ::testing::TestWithParam<StopCase> {};

std::vector<std::string> ranksOfOneThread(std::vector<std::string> args) {
  args.insert(args.begin(), {"--threads", "1"});
  return args;
}

TEST_P(StopInStep, DropsTheStepUnderWayAndTheRestartContinuesBitForBit) {
  const StopCase& c = GetParam();
  Scratch s("stop_" + c.name);
  // Its first step takes several seconds (Newton 10, diffusion sub-steps) on 2 cores.
  const std::string input = kSource + "/inputs/Paper/QuasiStatic_Fig4.ups";
  const auto withMode = [&](std::vector<std::string> args) {
    args.insert(args.begin(), c.mode.begin(), c.mode.end());
    return args;
  };
  const fs::path run = s.dir / "stopped";
  // Under a launcher: its ranks of one thread, as the one-command mode runs them.
  std::vector<std::string> stopped = {"--max-timesteps", "2", "-o", run.string(), input};
  stopped = c.launcher.empty() ? withMode(stopped) : ranksOfOneThread(stopped);
  const pid_t pid = startSus(stopped, s.dir / "log", c.launcher);
  ASSERT_GE(pid, 0);
  // The start's checkpoint is its last write before the first step.
  for (int i = 0; i < 600 && listCheckpoints(run.string()).empty(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  std::this_thread::sleep_for(std::chrono::milliseconds(1000));
  const auto sent = std::chrono::steady_clock::now();
  kill(pid, c.signal);
  int status = 0;
  waitpid(pid, &status, 0);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  const std::string log = readFile(s.dir / "log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 4) << log;
  EXPECT_LT(seconds, 5.0) << log;
  EXPECT_NE(log.find("step 1 dropped"), std::string::npos) << log;
  EXPECT_NE(log.find("stopped on request"), std::string::npos) << log;
  if (!c.restart) return;
  const fs::path whole = s.dir / "whole";
  const testing::SusResult uninterrupted =
      testing::runSus(withMode({"--max-timesteps", "2", "-o", whole.string(), input}));
  ASSERT_EQ(uninterrupted.exitCode, 0) << uninterrupted.output;
  const testing::SusResult restart =
      testing::runSus(withMode({"--max-timesteps", "2", "-restart", run.string()}));
  ASSERT_EQ(restart.exitCode, 0) << restart.output;
  expectSameOutputs(whole, run);
}

const std::vector<std::string> kOneProcess = {"--one-process", "--threads", "2"};
const std::vector<std::string> kOneCommand = {"--threads", "2"};
// As root here (tests and CI run as root), on 2 cores.
const std::vector<std::string> kMpirun = {"mpirun",          "-q",  "--allow-run-as-root",
                                          "--oversubscribe", "-np", "2"};

INSTANTIATE_TEST_SUITE_P(
    Signals, StopInStep,
    ::testing::Values(StopCase{"sigint_one_process", kOneProcess, SIGINT, true},
                      StopCase{"sigterm_one_process", kOneProcess, SIGTERM, false},
                      StopCase{"sigusr1_one_process", kOneProcess, SIGUSR1, false},
                      StopCase{"sigint_one_command", kOneCommand, SIGINT, true},
                      StopCase{"sigterm_one_command", kOneCommand, SIGTERM, false},
                      StopCase{"sigusr1_one_command", kOneCommand, SIGUSR1, false},
                      StopCase{"sigusr1_mpirun", kOneCommand, SIGUSR1, false, kMpirun}),
    [](const ::testing::TestParamInfo<StopCase>& i) { return i.param.name; });

}  // namespace
}  // namespace anode
