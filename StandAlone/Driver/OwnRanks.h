// The one-command mode (docs/parallel.md "One command, every core"): `sus input.ups` on an
// implicit input, started without a launcher and given (or defaulting to) N > 1 threads, runs as
// `mpirun -np N sus --threads 1 ...`, N ranks of one thread each. The quasi-static path spends
// most of its time in PETSc's solve, which Debian builds without threads: ranks, not threads,
// put every core in it. This process only waits for mpirun and passes a stop on.
#pragma once

#include <string>
#include <vector>

namespace anode {

// The cores this process may run on (its affinity mask), 0 if unknown.
int coresOfThisProcess();

// Whether the input at `path` asks for the implicit path (<MPM><time_integrator>implicit); false
// when it cannot be read (the run then says why).
bool asksForImplicitPath(const std::string& path);

// Runs `program` with `arguments` on `ranks` ranks under mpirun (found on PATH) in a process
// group of its own, so that a terminal's Ctrl-C reaches this process alone: SIGINT, SIGTERM and
// SIGUSR1 here become one SIGUSR1 to mpirun, which passes it to every rank (each stops as after
// a stop request, exit 4); mpirun gets SIGTERM if this process dies. Returns mpirun's exit code
// (the ranks'), or -1 with `why` set when mpirun cannot be started (not on PATH).
int runOnOwnRanks(int ranks, const std::string& program, const std::vector<std::string>& arguments,
                  std::string& why);

}  // namespace anode
