// Quick runtime fuzz of the quasi-static path (the long run: fuzz_runs): mutated small implicit
// inputs run sus for a few steps and end in exit 0, 2 (file:line), 3 (a diagnostic) or 4.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>

#include "tests/TestFiles.h"
#include "tests/fuzz/RunFuzz.h"

namespace anode::fuzz {
namespace {

using testing::readFile;

TEST(RunMutator, EveryOperatorChangesAnImplicitInputAndIsReproducible) {
  const std::string seed =
      readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Stability/Implicit_contact_null.ups");
  ASSERT_FALSE(seed.empty());
  for (int op = 0; op < RunMutator::kOperatorCount; ++op) {
    std::string a = seed, b = seed, whatA, whatB;
    RunMutator ma(42 + op), mb(42 + op);
    // A draw may change nothing (zero of a zero, an option set to its own value).
    for (int k = 0; k < 10 && a == seed; ++k) ma.apply(op, a, &whatA);
    for (int k = 0; k < 10 && b == seed; ++k) mb.apply(op, b, &whatB);
    EXPECT_NE(a, seed) << RunMutator::operatorName(op);
    EXPECT_EQ(a, b) << RunMutator::operatorName(op);
    EXPECT_EQ(whatA, whatB);
    EXPECT_EQ(whatA.rfind(RunMutator::operatorName(op), 0), 0u) << whatA;
  }
}

TEST(RunMutator, ChangesOneComponentOfAVector) {
  std::string text = "<a><v>[1, 2, 3]</v></a>";
  RunMutator m(3);
  std::string what;
  ASSERT_TRUE(m.apply(RunMutator::Zero, text, &what));
  const int zeros = (text.find("[0,") != std::string::npos) +
                    (text.find(",0,") != std::string::npos) +
                    (text.find(",0]") != std::string::npos);
  EXPECT_EQ(zeros, 1) << text;
}

TEST(RunFuzz, AStopRequestThenTheTimeLimitEndTheRun) {
  const std::string dir = std::filesystem::temp_directory_path() / "anode_run_fuzz_limit";
  std::filesystem::create_directories(dir);
  // sleep ends at SIGUSR1 (its default action).
  SusRun run = runWithTimeLimit("/bin/sleep", {"30"}, dir + "/log", 0.2, 5);
  EXPECT_TRUE(run.askedToStop);
  EXPECT_FALSE(run.timedOut);
  EXPECT_EQ(run.signal, SIGUSR1);
  // A shell that ignores SIGUSR1 runs into the limit.
  run = runWithTimeLimit("/bin/sh", {"-c", "trap '' USR1; sleep 30"}, dir + "/log", 0.1, 0.4);
  EXPECT_TRUE(run.timedOut);
  EXPECT_LT(run.seconds, 5);
  EXPECT_EQ(run.signal, SIGKILL);
  std::filesystem::remove_all(dir);
}

// Every case ends in exit 0, 2, 3 or 4 within 10 s (a stop request after 5 s); a fifth of them
// or more reach the time loop, some are refused, so the mutations reach both setup and the loop.
TEST(RunFuzz, QuickRunEndsEveryCaseInAnExitCodeOfTheFour) {
  RunFuzzOptions options;
  options.corpus = defaultRunCorpus(ANODE_SOURCE_DIR);
  ASSERT_GE(options.corpus.size(), 6u);
  options.cases = 40;
  options.seed = 7;
  options.steps = 3;
  options.stopAfter = 5;
  options.caseTimeLimit = 10;
  options.sus = ANODE_SUS;
  options.workDir = std::filesystem::temp_directory_path() / "anode_run_fuzz_quick";
  const RunFuzzReport r = runRunFuzz(options);
  std::printf(
      "run fuzz: %ld cases in %.1f s (slowest %.1f s): %ld ran, %ld refused, %ld diagnosed, %ld "
      "stopped, %zu failures\n",
      r.tried, r.seconds, r.slowestCase, r.ran, r.refused, r.diagnosed, r.stopped,
      r.failures.size());
  EXPECT_EQ(r.tried, options.cases);
  for (const RunFuzzFailure& f : r.failures)
    ADD_FAILURE() << "case " << f.index << " of " << f.seed << " (" << f.mutations
                  << "): " << f.problem << " (kept in " << options.workDir << ")";
  EXPECT_GT(r.ran + r.diagnosed + r.stopped, r.tried / 5);  // reached the time loop
  EXPECT_GT(r.ran, 0);
  EXPECT_GT(r.refused, 0);
  if (r.failures.empty()) std::filesystem::remove_all(options.workDir);
}

}  // namespace
}  // namespace anode::fuzz
