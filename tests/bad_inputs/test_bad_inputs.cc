// Pins the error contract of sus: each malformed input exits 2 naming FILE:LINE:, writes nothing.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "tests/RunSus.h"

namespace fs = std::filesystem;

namespace {

const std::string kDir = std::string(ANODE_SOURCE_DIR) + "/tests/bad_inputs";
const std::string kValid = kDir + "/valid_minimal.ups";
const std::string kValidDiffusion = kDir + "/valid_diffusion.ups";
const std::string kUnsupported = kDir + "/unsupported_artificial_viscosity.ups";

using anode::testing::runSus;
using anode::testing::SusResult;

// A path in the temporary directory that does not exist yet.
fs::path freshOutputDir(const std::string& tag) {
  static int counter = 0;
  const fs::path p =
      fs::temp_directory_path() / ("anode_bad_inputs_" + tag + "_" + std::to_string(getpid()) +
                                   "_" + std::to_string(counter++));
  fs::remove_all(p);
  return p;
}

// The expectation a bad input carries in its header comment.
struct Expectation {
  int line = 0;
  std::string message;
};

// Reads `<!-- expect line=NN message="..." -->` from the first line after the XML declaration
// (or the first line); line stays 0 when the header is missing.
Expectation readExpectation(const std::string& file) {
  std::ifstream in(file);
  std::string first;
  std::getline(in, first);
  if (first.rfind("<?xml", 0) == 0) std::getline(in, first);
  static const std::regex header(R"re(^\s*<!-- expect line=(\d+) message="(.*)" -->\s*$)re");
  std::smatch m;
  Expectation e;
  if (std::regex_match(first, m, header)) {
    e.line = std::stoi(m[1]);
    e.message = m[2];
  }
  return e;
}

// Every .ups in the folder except the valid ones (valid_*.ups, the bases the others change in
// one place), sorted so the test order is stable.
std::vector<std::string> badInputs() {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(kDir))
    if (entry.path().extension() == ".ups" &&
        entry.path().filename().string().rfind("valid_", 0) != 0)
      files.push_back(entry.path().string());
  std::sort(files.begin(), files.end());
  return files;
}

std::string testName(const testing::TestParamInfo<std::string>& info) {
  std::string name = fs::path(info.param).stem().string();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class BadInput : public testing::TestWithParam<std::string> {};

TEST_P(BadInput, ExitsWithCode2NamingFileAndLineAndWritesNothing) {
  const std::string file = GetParam();
  const Expectation expect = readExpectation(file);
  ASSERT_GT(expect.line, 0) << file << " lacks the header <!-- expect line=NN message=\"...\" -->";
  ASSERT_FALSE(expect.message.empty()) << file << ": empty expected message";

  const fs::path out = freshOutputDir(fs::path(file).stem().string());
  const SusResult r = runSus({"-o", out.string(), file});
  EXPECT_EQ(r.exitCode, 2) << r.output;
  const std::string where = file + ":" + std::to_string(expect.line) + ":";
  EXPECT_NE(r.output.find(where), std::string::npos) << "expected '" << where << "' in:\n"
                                                     << r.output;
  EXPECT_NE(r.output.find(expect.message), std::string::npos)
      << "expected '" << expect.message << "' in:\n"
      << r.output;
  EXPECT_FALSE(fs::exists(out)) << "sus created " << out << " for a bad input";
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Files, BadInput, testing::ValuesIn(badInputs()), testName);

// The tests below are parameterized by the path they work on too, so that ctest lists that path
// (and `ctest -R bad` selects them with the bad inputs).
class Folder : public testing::TestWithParam<std::string> {};

TEST_P(Folder, HoldsTheRequiredBadInputs) {
  EXPECT_GE(badInputs().size(), 14u);
  EXPECT_TRUE(fs::exists(fs::path(GetParam()) / "valid_minimal.ups"));
  EXPECT_TRUE(fs::exists(fs::path(GetParam()) / "valid_diffusion.ups"));
  EXPECT_TRUE(fs::exists(kUnsupported));
}

TEST_P(Folder, HoldsTheFilesTheTestsWereBuiltFor) {
  std::vector<std::string> now;
  for (const auto& entry : fs::directory_iterator(GetParam()))
    if (entry.path().extension() == ".ups") now.push_back(entry.path().filename().string());
  std::sort(now.begin(), now.end());
  std::string joined;
  for (const auto& name : now) joined += (joined.empty() ? "" : ",") + name;
  EXPECT_EQ(joined, ANODE_INPUTS_AT_BUILD) << "rebuild test_bad_inputs to refresh the ctest list";
}

INSTANTIATE_TEST_SUITE_P(BadInputs, Folder, testing::Values(kDir), testName);

class ValidInput : public testing::TestWithParam<std::string> {};

TEST_P(ValidInput, RunsAndWritesParticles) {
  const fs::path out = freshOutputDir("valid");
  const SusResult r = runSus({"-o", out.string(), GetParam()});
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(fs::exists(out / "particles.pvd")) << r.output;
  EXPECT_EQ(r.output.find("warning:"), std::string::npos) << r.output;
  fs::remove_all(out);
}

TEST_P(ValidInput, UnknownCommandLineOptionExitsWithCode2) {
  const fs::path out = freshOutputDir("unknown_option");
  const SusResult r = runSus({"--no-such-option", "-o", out.string(), GetParam()});
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("unknown option --no-such-option"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out));
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Files, ValidInput, testing::Values(kValid, kValidDiffusion), testName);

class UnsupportedInput : public testing::TestWithParam<std::string> {};

TEST_P(UnsupportedInput, RunsWithAWarningUnderIgnoreUnsupported) {
  const std::string file = GetParam();
  const Expectation expect = readExpectation(file);
  const fs::path out = freshOutputDir("ignore_unsupported");
  const SusResult r = runSus({"--ignore-unsupported", "-o", out.string(), file});
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("warning: " + file + ":" + std::to_string(expect.line) + ":"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find(expect.message), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(out / "particles.pvd")) << r.output;
  fs::remove_all(out);
}

INSTANTIATE_TEST_SUITE_P(Files, UnsupportedInput, testing::Values(kUnsupported), testName);

}  // namespace
