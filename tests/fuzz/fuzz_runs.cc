// fuzz_runs: the long runtime fuzz of the quasi-static path (test_run_fuzz runs a quick one).
// Mutates the small implicit inputs and runs sus on each case for a few steps; every case must
// end in exit 0, 2 (file:line), 3 (a diagnostic) or 4 within the time limit. Exit code 0 when no
// case failed, 1 otherwise.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "tests/fuzz/RunFuzz.h"

namespace {

const char* kUsage =
    "usage: fuzz_runs [--cases N] [--seed S] [--steps N] [--stop-after T] [--case-time-limit T]\n"
    "                 [--work DIR] [--sus PATH] [seed.ups ...]\n"
    "  --cases N            mutated inputs to run (default 300)\n"
    "  --seed S             random seed (default 1); case I of seed S is always the same input\n"
    "  --steps N            sus --max-timesteps N (default 5)\n"
    "  --stop-after T       a case still running is sent SIGUSR1, a stop request (default 45 s)\n"
    "  --case-time-limit T  a case running longer is a failure (default 60 s)\n"
    "  --work DIR           each case's input, output and log; failures kept as\n"
    "                       DIR/failureN.ups with DIR/failureN.ups.txt (default fuzz_runs_work)\n"
    "  --sus PATH           the sus to run (default: this build's)\n"
    "  seed.ups ...         seed inputs (default: inputs/Stability/Implicit_*.ups)\n";

double number(const char* flag, const char* value) {
  char* end = nullptr;
  const double v = value ? std::strtod(value, &end) : 0;
  if (!value || *end != '\0' || !(v > 0)) {
    std::fprintf(stderr, "fuzz_runs: %s needs a positive number\n%s", flag, kUsage);
    std::exit(2);
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  anode::fuzz::RunFuzzOptions options;
  options.sus = ANODE_SUS;
  options.workDir = "fuzz_runs_work";
  options.progress = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "--cases") {
      options.cases = static_cast<long>(number("--cases", next)), ++i;
    } else if (a == "--seed") {
      options.seed = static_cast<uint64_t>(number("--seed", next)), ++i;
    } else if (a == "--steps") {
      options.steps = static_cast<long>(number("--steps", next)), ++i;
    } else if (a == "--stop-after") {
      options.stopAfter = number("--stop-after", next), ++i;
    } else if (a == "--case-time-limit") {
      options.caseTimeLimit = number("--case-time-limit", next), ++i;
    } else if ((a == "--work" || a == "--sus") && next) {
      (a == "--work" ? options.workDir : options.sus) = next, ++i;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "fuzz_runs: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    } else {
      options.corpus.push_back(a);
    }
  }
  if (options.corpus.empty()) options.corpus = anode::fuzz::defaultRunCorpus(ANODE_SOURCE_DIR);
  std::fprintf(stderr, "fuzz_runs: %zu seed inputs, seed %llu, %ld steps, %s\n",
               options.corpus.size(), static_cast<unsigned long long>(options.seed), options.steps,
               options.sus.c_str());
  const anode::fuzz::RunFuzzReport r = anode::fuzz::runRunFuzz(options);
  std::printf(
      "fuzz_runs: %ld cases in %.1f s (slowest %.1f s): %ld ran (exit 0), %ld refused with "
      "file:line (2), %ld stopped with a diagnostic (3), %ld stopped on request (4), %zu "
      "failures\n",
      r.tried, r.seconds, r.slowestCase, r.ran, r.refused, r.diagnosed, r.stopped,
      r.failures.size());
  std::printf("operators applied:");
  for (int op = 0; op < anode::fuzz::RunMutator::kOperatorCount; ++op)
    std::printf(" %s %ld%s", anode::fuzz::RunMutator::operatorName(op), r.perOperator[op],
                op + 1 < anode::fuzz::RunMutator::kOperatorCount ? "," : "\n");
  for (const auto& f : r.failures)
    std::printf("FAILURE case %ld of %s (%s): %s\n", f.index, f.seed.c_str(), f.mutations.c_str(),
                f.problem.c_str());
  return r.failures.empty() ? 0 : 1;
}
