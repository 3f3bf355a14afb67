// fuzz_inputs: the long version of the input-reader fuzz test (test_input_fuzz runs a quick one).
// Mutates the repository's inputs and runs setup on each case; every case must end in success or
// an InputError naming file:line. Exit code 0 when no case failed, 1 otherwise.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "tests/fuzz/FuzzHarness.h"

namespace {

const char* kUsage =
    "usage: fuzz_inputs [--cases N] [--seconds T] [--seed S] [--memory-budget-mb M]\n"
    "                   [--case-time-limit T] [--in-process] [--keep PATH] [--show-case I] "
    "[seed.ups ...]\n"
    "  --cases N            mutated inputs to try (default 100000)\n"
    "  --seconds T          stop after T seconds as well (default: no limit)\n"
    "  --seed S             random seed (default 1); case I of seed S is always the same input\n"
    "  --memory-budget-mb M setup's memory budget (default 1024): larger problems must be refused\n"
    "  --case-time-limit T  a case running longer is a hang (default 60 s)\n"
    "  --in-process         run cases in this process (faster; the first crash or hang ends the "
    "run)\n"
    "                       instead of one child process per case\n"
    "  --keep PATH          keep the case being run in PATH (default: a file in the temp "
    "directory);\n"
    "                       failing cases are kept as PATH.failureN.ups\n"
    "  --show-case I        print the mutations and text of case I and exit\n"
    "  seed.ups ...         seed inputs (default: the repository's inputs, valid_minimal.ups and\n"
    "                       ../shared/inputs/uintah/*.ups)\n";

double number(const char* flag, const char* value, bool integer) {
  char* end = nullptr;
  const double v = value ? std::strtod(value, &end) : 0;
  if (!value || *end != '\0' || !(v >= 0) ||
      (integer && v != static_cast<double>(static_cast<long long>(v)))) {
    std::fprintf(stderr, "fuzz_inputs: %s needs a non-negative %s\n%s", flag,
                 integer ? "integer" : "number", kUsage);
    std::exit(2);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  anode::fuzz::FuzzOptions options;
  options.cases = 100000;
  options.memoryBudget = size_t(1024) << 20;
  options.caseTimeLimit = 60;
  options.fork = true;
  options.progress = true;
  long showCase = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--cases") {
      options.cases = static_cast<long>(number("--cases", next, true)), ++i;
    } else if (a == "--seconds") {
      options.seconds = number("--seconds", next, false), ++i;
    } else if (a == "--seed") {
      options.seed = static_cast<uint64_t>(number("--seed", next, true)), ++i;
    } else if (a == "--memory-budget-mb") {
      options.memoryBudget = static_cast<size_t>(number("--memory-budget-mb", next, true)) << 20,
      ++i;
    } else if (a == "--case-time-limit") {
      options.caseTimeLimit = number("--case-time-limit", next, false), ++i;
    } else if (a == "--in-process") {
      options.fork = false;
    } else if (a == "--keep") {
      if (!next) {
        std::fprintf(stderr, "fuzz_inputs: --keep needs a path\n%s", kUsage);
        return 2;
      }
      options.casePath = next, ++i;
    } else if (a == "--show-case") {
      showCase = static_cast<long>(number("--show-case", next, true)), ++i;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "fuzz_inputs: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    } else {
      options.corpus.push_back(a);
    }
  }
  if (options.corpus.empty()) options.corpus = anode::fuzz::defaultCorpus(ANODE_SOURCE_DIR);
  if (options.corpus.empty()) {
    std::fprintf(stderr, "fuzz_inputs: no seed inputs found\n");
    return 2;
  }
  if (showCase >= 0) {
    std::vector<std::string> texts;
    for (const std::string& f : options.corpus) {
      FILE* in = std::fopen(f.c_str(), "rb");
      std::string t;
      char b[4096];
      size_t n;
      while (in && (n = std::fread(b, 1, sizeof b, in)) > 0) t.append(b, n);
      if (in) std::fclose(in);
      texts.push_back(t);
    }
    const anode::fuzz::FuzzCase c = anode::fuzz::makeCase(options, texts, showCase);
    std::printf("<!-- case %ld of %s: %s -->\n%s", showCase, c.seed.c_str(), c.mutations.c_str(),
                c.text.c_str());
    return 0;
  }
  std::fprintf(stderr, "fuzz_inputs: %zu seed inputs, seed %llu, memory budget %zu MB, %s\n",
               options.corpus.size(), static_cast<unsigned long long>(options.seed),
               options.memoryBudget >> 20,
               options.fork ? "a child process per case" : "in process");
  const anode::fuzz::FuzzReport r = anode::fuzz::runFuzz(options);
  std::printf(
      "fuzz_inputs: %ld cases in %.1f s: %ld accepted, %ld refused with file:line, %zu failures\n",
      r.tried, r.seconds, r.accepted, r.rejected, r.failures.size());
  std::printf("operators applied:");
  for (int op = 0; op < anode::fuzz::InputMutator::kOperatorCount; ++op)
    std::printf(" %s %ld%s", anode::fuzz::InputMutator::operatorName(op), r.perOperator[op],
                op + 1 < anode::fuzz::InputMutator::kOperatorCount ? "," : "\n");
  for (const auto& f : r.failures)
    std::printf("FAILURE case %ld of %s (%s): %s\n", f.index, f.seed.c_str(), f.mutations.c_str(),
                f.problem.c_str());
  return r.failures.empty() ? 0 : 1;
}
