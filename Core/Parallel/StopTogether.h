// A diagnostic stop in a distributed run (docs/parallel.md): a problem one rank finds stops every
// rank in the same step, and no rank is left waiting in a collective the others never enter.
#pragma once

#include <exception>
#include <string>

#include "Core/Parallel/Communicator.h"
#include "Core/Util/Errors.h"

namespace anode {

// The SimulationError another rank raised in this step: this rank stops too, without a message
// of its own (the rank that found the problem reports it).
class StoppedOnAnotherRank : public SimulationError {
 public:
  explicit StoppedOnAnotherRank(int rank)
      : SimulationError("stopped by rank " + std::to_string(rank)) {}
};

namespace collective {

// Runs `phase`; when it throws a SimulationError on any rank, every rank throws after it: the
// lowest such rank its own error, the others StoppedOnAnotherRank. One reduction of an int
// (nothing on a run of one rank).
template <class Phase>
void stopTogether(Phase&& phase) {
  std::exception_ptr error;
  try {
    phase();
  } catch (const SimulationError&) {
    error = std::current_exception();
  }
  const int first = firstRankWith(error != nullptr);
  if (first < 0) return;
  if (first == Communicator::rank()) std::rethrow_exception(error);
  throw StoppedOnAnotherRank(first);
}

}  // namespace collective

}  // namespace anode
