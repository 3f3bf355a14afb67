// A diagnostic stop in a distributed run (docs/parallel.md): a problem one rank finds stops every
// rank in the same step, and no rank is left waiting in a collective the others never enter.
#pragma once

#include <cstdint>
#include <exception>
#include <stdexcept>
#include <string>

#include "Core/Parallel/Communicator.h"
#include "Core/Util/Errors.h"
#include "Core/Util/StopRequest.h"

namespace anode {

// The SimulationError another rank raised in this step: this rank stops too, without a message
// of its own (the rank that found the problem reports it).
class StoppedOnAnotherRank : public SimulationError {
 public:
  explicit StoppedOnAnotherRank(int rank)
      : SimulationError("stopped by rank " + std::to_string(rank)) {}
};

// A setup error the ranks agreed on (readTogether): found by `rank` (another rank, or this one
// when it was not an InputError); `input` when it was an InputError; `message` is that rank's,
// to print once.
class SetupFailedOnAnotherRank : public std::runtime_error {
 public:
  SetupFailedOnAnotherRank(int rank, int failing, bool input, const std::string& message)
      : std::runtime_error(message), rank(rank), failing(failing), input(input) {}
  int rank;     // the lowest rank that failed
  int failing;  // how many ranks failed
  bool input;
};

// A stop request (StopRequest.h) every rank found at the same point of a step: the step under
// way is dropped, its particles set back to its start, and the run ends as after a stop between
// steps.
class StopRequestedInStep : public std::runtime_error {
 public:
  StopRequestedInStep() : std::runtime_error("stopped on request in a step") {}
};

namespace collective {

// Throws StopRequestedInStep on every rank when a stop signal reached any rank. One reduction of
// a bool (nothing on a run of one rank).
inline void stopIfRequested(Collective every) {
  if (any(every, stopRequested())) throw StopRequestedInStep();
}

// Runs `phase`, a setup that calls no collective (reading the input, building what it asks for);
// when it throws on any rank (an input one rank cannot read, a memory check on one node), every
// rank throws after it, none is left waiting in a later collective: the lowest such rank its own
// error, the others SetupFailedOnAnotherRank with its message. One reduction and, on an error,
// a broadcast (nothing on a run of one rank).
template <class Phase>
void readTogether(Collective every, Phase&& phase) {
  std::exception_ptr error;
  std::string message;
  bool input = false;
  try {
    phase();
  } catch (const InputError& e) {
    error = std::current_exception();
    message = e.what();
    input = true;
  } catch (const std::exception& e) {
    error = std::current_exception();
    message = e.what();
  }
  const int first = firstRankWith(every, error != nullptr);
  if (first < 0) return;
  const int failing = static_cast<int>(sum(every, static_cast<int64_t>(error != nullptr)));
  const std::string shared = broadcast(every, (input ? "2" : "1") + message, first);
  // The first rank's own input error as it is; its other errors, on several ranks, agreed like
  // the others' (no rank is then left to abort the others).
  if (first == Communicator::rank() && (input || Communicator::size() == 1))
    std::rethrow_exception(error);
  throw SetupFailedOnAnotherRank(first, failing, shared[0] == '2', shared.substr(1));
}

// Runs `task` on rank 0 alone (file work the other ranks wait for); it returns an error message
// (empty: none) or throws. On an error every rank throws std::runtime_error after it: rank 0
// with the error, the others with `elsewhere`. One reduction of a bool.
template <class Task>
void onRootTogether(Collective every, Task&& task, const std::string& elsewhere) {
  std::string error;
  if (Communicator::isRoot()) {
    try {
      error = task();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (any(every, !error.empty()))
    throw std::runtime_error(Communicator::isRoot() ? error : elsewhere);
}

// Runs `phase`; when it throws a SimulationError on any rank, every rank throws after it: the
// lowest such rank its own error, the others StoppedOnAnotherRank. One reduction of an int
// (nothing on a run of one rank).
template <class Phase>
void stopTogether(Collective every, Phase&& phase) {
  std::exception_ptr error;
  try {
    phase();
  } catch (const SimulationError&) {
    error = std::current_exception();
  }
  const int first = firstRankWith(every, error != nullptr);
  if (first < 0) return;
  if (first == Communicator::rank()) std::rethrow_exception(error);
  throw StoppedOnAnotherRank(first);
}

}  // namespace collective

}  // namespace anode
