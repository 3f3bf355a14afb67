// A runtime fuzz of the quasi-static path: the numbers of small implicit inputs (but for the
// problem's size) scaled by 1e4 or 1e-4, negated, zeroed or made extreme, and ImpMPM options of
// <MPM> set to values setup accepts; each case runs this build's `sus` for a few steps in a child
// process (one process, one thread) and must end in exit 0 (ran), 2 (refused with file:line), 3
// (stopped with a diagnostic) or 4 (stopped on request: a case still running after a while is asked
// to stop) within the time limit. Any other exit code, a signal or a run past the limit is a
// failure, kept with its seed input and mutations.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace anode::fuzz {

// Changes a number of the text (a leaf element's value, or one component of a vector) or sets an
// ImpMPM option; deterministic for a seed.
class RunMutator {
 public:
  enum Operator { ScaleUp, ScaleDown, Negate, Zero, Extreme, ImplicitOption, kOperatorCount };
  static const char* operatorName(int op);

  explicit RunMutator(uint64_t seed) : rng_(seed) {}

  // Applies one operator; false (text unchanged) when the text offers it nothing to change.
  // `what` receives a one-line description.
  bool apply(int op, std::string& text, std::string* what);
  // Applies 1 to 3 random operators; returns their descriptions joined with "; ".
  std::string mutate(std::string& text, std::vector<int>* operatorsUsed = nullptr);

 private:
  size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }
  bool changeNumber(int op, std::string& text, std::string* what);
  std::mt19937_64 rng_;
};

struct RunFuzzOptions {
  uint64_t seed = 1;
  long cases = 300;
  long steps = 5;  // sus --max-timesteps
  // Seconds: a case still running after stopAfter is sent SIGUSR1 (a stop request, as a user
  // would send), and one running past caseTimeLimit is a failure (then killed).
  double stopAfter = 45, caseTimeLimit = 60;
  std::string sus;                  // the sus to run
  std::string workDir;              // each case's input and output; failures kept as failureN.ups
  std::vector<std::string> corpus;  // seed inputs
  bool progress = false;            // a line per case on stderr
};

struct RunFuzzFailure {
  long index;
  std::string seed, mutations, problem;
};

struct RunFuzzReport {
  long tried = 0;
  long ran = 0, refused = 0, diagnosed = 0, stopped = 0;  // exit 0, 2, 3 and 4
  long perOperator[RunMutator::kOperatorCount] = {};
  std::vector<RunFuzzFailure> failures;
  double seconds = 0, slowestCase = 0;
};

// The small implicit inputs: inputs/Stability/Implicit_*.ups, sorted.
std::vector<std::string> defaultRunCorpus(const std::string& sourceDir);

// The outcome of one run of sus: its exit code (-1 when it did not exit normally), the signal
// that ended it (0: none), whether it was asked to stop, whether it ran past the time limit (and
// was killed), its wall time.
struct SusRun {
  int exitCode = -1, signal = 0;
  bool askedToStop = false, timedOut = false;
  double seconds = 0;
};
// Runs `program` with `arguments`, its output to `logPath`: SIGUSR1 after `stopAfter` seconds,
// SIGKILL after `timeLimit`.
SusRun runWithTimeLimit(const std::string& program, const std::vector<std::string>& arguments,
                        const std::string& logPath, double stopAfter, double timeLimit);

RunFuzzReport runRunFuzz(const RunFuzzOptions& options);

}  // namespace anode::fuzz
