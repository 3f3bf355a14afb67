// Quick fuzz run of the input reader (the long run: fuzz_inputs): mutated repository inputs run
// setup only and must end in success or an InputError naming file:line; no crash, no other
// exception, no hang, nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "Core/Util/MemoryBudget.h"
#include "tests/fuzz/FuzzHarness.h"

namespace anode::fuzz {
namespace {

const std::string kMinimal = std::string(ANODE_SOURCE_DIR) + "/tests/bad_inputs/valid_minimal.ups";

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ElementScan, FindsNestedElementsWithTheirContent) {
  const std::string t =
      "<?xml version='1.0'?>\n<!-- <no> -->\n<a x=\"1>2\"><b>3</b><c/><d><e>[1,2]</e></d></a>";
  const auto e = scanElements(t);
  ASSERT_EQ(e.size(), 5u);
  EXPECT_EQ(t.substr(e[0].nameBegin, e[0].nameLength), "a");
  EXPECT_FALSE(e[0].leaf);
  EXPECT_EQ(t.substr(e[1].begin, e[1].end - e[1].begin), "<b>3</b>");
  EXPECT_EQ(t.substr(e[1].contentBegin, e[1].contentEnd - e[1].contentBegin), "3");
  EXPECT_TRUE(e[2].selfClosing);
  EXPECT_EQ(t.substr(e[2].begin, e[2].end - e[2].begin), "<c/>");
  EXPECT_FALSE(e[3].leaf);
  EXPECT_EQ(t.substr(e[4].contentBegin, e[4].contentEnd - e[4].contentBegin), "[1,2]");
  EXPECT_EQ(e[0].end, t.size());
}

TEST(InputMutator, EveryOperatorChangesTheMinimalInputAndIsReproducible) {
  const std::string seed = readFile(kMinimal);
  ASSERT_FALSE(seed.empty());
  for (int op = 0; op < InputMutator::kOperatorCount; ++op) {
    std::string a = seed, b = seed, whatA, whatB;
    InputMutator ma(42 + op), mb(42 + op);
    bool applied = false;
    // An operator may draw a no-op (a value replaced by itself): a few draws suffice.
    for (int k = 0; k < 10 && a == seed; ++k) applied = ma.apply(op, a, &whatA) || applied;
    for (int k = 0; k < 10 && b == seed; ++k) mb.apply(op, b, &whatB);
    EXPECT_TRUE(applied) << InputMutator::operatorName(op);
    EXPECT_NE(a, seed) << InputMutator::operatorName(op);
    EXPECT_EQ(a, b) << InputMutator::operatorName(op);
    EXPECT_EQ(whatA, whatB);
    EXPECT_EQ(whatA.rfind(InputMutator::operatorName(op), 0), 0u) << whatA;
  }
}

TEST(CheckSetup, AcceptsTheMinimalInputAndAcceptsFileLineRefusals) {
  bool accepted = false;
  EXPECT_EQ(checkSetup(readFile(kMinimal), "minimal.ups", &accepted), "");
  EXPECT_TRUE(accepted);
  EXPECT_EQ(checkSetup("<Uintah_specification>\n</Uintah_specification>\n", "empty.ups", &accepted),
            "");
  EXPECT_FALSE(accepted);
  EXPECT_EQ(checkSetup("", "nothing.ups", &accepted), "");
  EXPECT_FALSE(accepted);
}

TEST(CheckSetup, RefusesAnAbsurdGridWithinTheBudgetInsteadOfAllocating) {
  std::string text = readFile(kMinimal);
  const size_t at = text.find("<resolution>");
  ASSERT_NE(at, std::string::npos);
  const size_t end = text.find("</resolution>", at);
  text.replace(at, end - at, "<resolution>[2000,2000,2000]");
  setMemoryBudget(size_t(256) << 20);
  bool accepted = true;
  EXPECT_EQ(checkSetup(text, "huge.ups", &accepted), "");
  setMemoryBudget(0);
  EXPECT_FALSE(accepted);
}

// A quick fuzz run over `corpus`: every case tried ends in success or a file:line input error,
// and both outcomes occur (the mutations reach past the parser into setup).
FuzzReport quickRun(const std::vector<std::string>& corpus, long cases, uint64_t seed,
                    const char* label) {
  FuzzOptions options;
  options.corpus = corpus;
  options.cases = cases;
  options.seed = seed;
  options.memoryBudget = size_t(256) << 20;
  options.caseTimeLimit = 60;
  const FuzzReport r = runFuzz(options);
  std::printf(
      "fuzz (%s): %ld cases in %.1f s over %zu seed inputs: %ld accepted, %ld refused with "
      "file:line, %zu failures\n",
      label, r.tried, r.seconds, corpus.size(), r.accepted, r.rejected, r.failures.size());
  EXPECT_EQ(r.tried, options.cases);
  for (size_t k = 0; k < r.failures.size() && k < 20; ++k)
    ADD_FAILURE() << "case " << r.failures[k].index << " of " << r.failures[k].seed << " ("
                  << r.failures[k].mutations << "): " << r.failures[k].problem;
  EXPECT_GT(r.accepted, r.tried / 50);
  EXPECT_GT(r.rejected, r.tried / 2);
  return r;
}

TEST(InputFuzz, QuickRunEndsEveryCaseInSuccessOrAFileLineInputError) {
  const std::vector<std::string> corpus = defaultCorpus(ANODE_SOURCE_DIR);
  ASSERT_GE(corpus.size(), 10u);
  const FuzzReport r = quickRun(corpus, 3000, 7, "all seeds");
  for (int op = 0; op < InputMutator::kOperatorCount; ++op)
    EXPECT_GT(r.perOperator[op], 0) << InputMutator::operatorName(op);
}

// The implicit inputs among the seeds (<time_integrator>implicit).
std::vector<std::string> implicitCorpus() {
  std::vector<std::string> out;
  for (const std::string& f : defaultCorpus(ANODE_SOURCE_DIR))
    if (readFile(f).find("<time_integrator>implicit") != std::string::npos) out.push_back(f);
  return out;
}

TEST(ImplicitOptions, EveryEditOfAnImpMPMTagEndsInSuccessOrAFileLineInputError) {
  const std::string seed =
      readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Stability/Implicit_contact_null.ups");
  ASSERT_NE(seed.find("<time_integrator>implicit"), std::string::npos);
  bool accepted = false;
  ASSERT_EQ(checkSetup(seed, "implicit.ups", &accepted), "");
  ASSERT_TRUE(accepted);
  const std::vector<std::string> values = {
      "-1",         "0",           "-0",     "1e300",  "1e400", "nan",  "inf",
      "2147483648", "-2147483649", "1e-300", "abc",    "",      "true", "false",
      "implicit",   "explicit",    "petsc",  "simple", "0.5",   "25"};
  // Not a number or not a finite one, or negative: every numeric tag refuses these.
  const std::vector<std::string> refused = {"-1", "1e400", "nan", "inf", "abc", ""};
  for (const std::string& tag : implicitTags()) {
    const bool numeric = tag != "time_integrator" && tag != "dynamic" && tag != "solver";
    for (const std::string& v : values) {
      std::string text = seed;
      ASSERT_TRUE(editTag(text, "MPM", tag, TagEdit::Set, v));
      EXPECT_EQ(checkSetup(text, "implicit.ups", &accepted), "") << "<" << tag << ">" << v;
      if (numeric && std::find(refused.begin(), refused.end(), v) != refused.end()) {
        EXPECT_FALSE(accepted) << "<" << tag << ">" << v << " was accepted";
      }
      ASSERT_TRUE(editTag(text, "MPM", tag, TagEdit::Duplicate));
      EXPECT_EQ(checkSetup(text, "implicit.ups", &accepted), "") << "<" << tag << "> twice";
      ASSERT_TRUE(editTag(text, "MPM", tag, TagEdit::Remove));
      EXPECT_EQ(checkSetup(text, "implicit.ups", &accepted), "") << "<" << tag << "> removed";
    }
  }
}

TEST(SurfaceReaction, EveryEditOfItsTagsEndsInSuccessOrAFileLineInputError) {
  const std::string seed =
      readFile(std::string(ANODE_SOURCE_DIR) + "/inputs/Verification/SurfaceReactionBar.ups");
  bool accepted = false;
  ASSERT_EQ(checkSetup(seed, "bar.ups", &accepted), "");
  ASSERT_TRUE(accepted);
  const std::vector<std::string> values = {"-1",  "0",   "1",   "0.45", "1e300", "1e400",
                                           "nan", "inf", "abc", "",     "0.5"};
  const std::vector<std::string> refused = {"1e400", "nan", "inf", "abc", ""};
  for (const std::string& tag : surfaceReactionTags())
    for (const std::string& v : values) {
      std::string text = seed;
      ASSERT_TRUE(editTag(text, "surface_reaction", tag, TagEdit::Set, v));
      EXPECT_EQ(checkSetup(text, "bar.ups", &accepted), "") << "<" << tag << ">" << v;
      if (std::find(refused.begin(), refused.end(), v) != refused.end()) {
        EXPECT_FALSE(accepted) << "<" << tag << ">" << v << " was accepted";
      }
      ASSERT_TRUE(editTag(text, "surface_reaction", tag, TagEdit::Duplicate));
      EXPECT_EQ(checkSetup(text, "bar.ups", &accepted), "") << "<" << tag << "> twice";
    }
}

TEST(InputFuzz, QuickRunOnTheImplicitInputsReachesTheImpMPMTags) {
  const std::vector<std::string> corpus = implicitCorpus();
  ASSERT_GE(corpus.size(), 5u);
  const FuzzReport r = quickRun(corpus, 600, 11, "implicit seeds");
  std::printf("fuzz (implicit seeds): %ld ImpMPM tag edits\n",
              r.perOperator[InputMutator::ImplicitOption]);
  EXPECT_GT(r.perOperator[InputMutator::ImplicitOption], r.tried / 20);
}

}  // namespace
}  // namespace anode::fuzz
