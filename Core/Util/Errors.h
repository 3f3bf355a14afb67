// Error types carried to main(): bad input (exit code 2) and a simulation that went wrong (exit 3).
#pragma once

#include <stdexcept>
#include <string>

namespace anode {

// Input that cannot be run: always carries the file and line of the offending tag.
class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, int line, const std::string& message)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + message),
        file_(file),
        line_(line) {}
  const std::string& file() const { return file_; }
  int line() const { return line_; }

 private:
  std::string file_;
  int line_;
};

// A run that cannot continue (NaN, J <= 0, particle leaving the grid, ...).
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A numerical library (PETSc) failed in a step: the run cannot continue (exit 3). Unlike a
// SimulationError the ranks do not agree on it (collective::stopTogether): the others may wait in
// the library's own collectives, so under several ranks the rank that found it reports it and
// ends every rank (Simulation::advance).
class LibraryFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace anode
