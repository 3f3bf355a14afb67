// Drives the input reader with mutated inputs: each case runs setup only (anode::Simulation from
// text; never the time loop) and must end in success or an anode::InputError naming the case's
// file and a line of it. Anything else (another exception type, a crash, a case running longer
// than the time limit) is a failure, reported with the seed input and the mutations that made it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tests/fuzz/InputMutator.h"

namespace anode::fuzz {

struct FuzzOptions {
  uint64_t seed = 1;
  long cases = 3000;
  double seconds = 0;                       // also stop after this wall time (0: no limit)
  size_t memoryBudget = size_t(256) << 20;  // setup's memory budget during the run (MemoryBudget.h)
  double caseTimeLimit = 30;                // seconds; a case running longer is a hang
  bool fork = false;                        // each case in a child process: crashes and hangs are
                      // counted and the run goes on (else the first one ends it)
  std::string casePath;             // the case being run is kept here (and PATH.txt: its origin)
  std::vector<std::string> corpus;  // seed inputs
  bool progress = false;            // a line every 10 s on stderr
};

struct FuzzFailure {
  long index;
  std::string seed, mutations, problem;
};

struct FuzzReport {
  long tried = 0, accepted = 0, rejected = 0;
  std::vector<FuzzFailure> failures;
  long perOperator[InputMutator::kOperatorCount] = {};
  double seconds = 0;
};

// The repository's runnable inputs: inputs/**/*.ups, tests/bad_inputs/valid_minimal.ups and the
// shared Uintah inputs (../shared/inputs/uintah/*.ups) when present, sorted.
std::vector<std::string> defaultCorpus(const std::string& sourceDir);

// Runs setup on `text` (named `name` in messages). Returns "" when it ended in success
// (*accepted = true) or in an InputError that names `name` and a line of the text, else what
// went wrong.
std::string checkSetup(const std::string& text, const std::string& name, bool* accepted);

// The mutated text of case `index` (its own random stream, so one case reproduces alone) and
// which seed and mutations made it.
struct FuzzCase {
  std::string seed, text, mutations;
  std::vector<int> operators;
};
FuzzCase makeCase(const FuzzOptions& options, const std::vector<std::string>& seedTexts,
                  long index);

FuzzReport runFuzz(const FuzzOptions& options);

}  // namespace anode::fuzz
