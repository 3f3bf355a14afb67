// sus: runs a Uintah-style .ups input, on one process or, under mpirun/srun, on every rank of
// the job (docs/parallel.md). Exit codes: 0 done, 1 I/O or internal error, 2 bad input (nothing
// written), 3 the simulation went bad (diagnostic printed), 4 stopped on request (SIGTERM,
// SIGINT or SIGUSR1, the one to send mpirun; a checkpoint written); a distributed run ends with the
// same code on every rank and prints each message once.
#include <malloc.h>
#include <omp.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "Core/Parallel/StopTogether.h"
#include "Core/Util/InstructionSet.h"
#include "Core/Util/StopRequest.h"
#include "StandAlone/Driver/OwnRanks.h"
#include "StandAlone/Driver/Simulation.h"

namespace {

const char* kUsage =
    "usage: sus [-o DIR] [--max-timesteps N] [--threads N] [--ignore-unsupported] input.ups\n"
    "       sus -restart DIR [--max-timesteps N] [--threads N] [--ignore-unsupported]\n"
    "  -o DIR               output directory (default: <filebase> of the input, versioned)\n"
    "  -restart DIR         continue the run in DIR from its newest checkpoint (<checkpoint> in\n"
    "                       <DataArchiver>), with DIR/input.ups; the same thread count gives the\n"
    "                       uninterrupted run's results bit for bit\n"
    "  --max-timesteps N    stop after N steps (at most; the input's max_Timesteps still holds)\n"
    "  --threads N          OpenMP threads (default: OMP_NUM_THREADS or all cores); an\n"
    "                       implicit input started without mpirun runs on N ranks of 1\n"
    "                       thread instead (mpirun -np N sus --threads 1), N > 1\n"
    "  --one-process        an implicit input on one process of N threads\n"
    "  --ignore-unsupported run without features the input asks for but this code lacks,\n"
    "                       listing each as a warning\n"
    "  --decompose N        set the input up (one process), print the boxes N ranks would\n"
    "                       draw, their particle counts, imbalance and ghost bytes, and exit\n";

long positiveNumber(const char* flag, const char* value) {
  char* end = nullptr;
  const long v = value ? std::strtol(value, &end, 10) : 0;
  if (!value || *end != '\0' || v < 1) {
    std::fprintf(stderr, "sus: %s needs a positive integer\n%s", flag, kUsage);
    std::exit(2);
  }
  return v;
}

// The arguments for the ranks of the one-command mode: this run's, with --threads 1.
std::vector<std::string> argumentsOfRanks(int argc, char** argv) {
  std::vector<std::string> arguments = {"--threads", "1"};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--threads") == 0)
      ++i;  // and its value
    else
      arguments.push_back(argv[i]);
  }
  return arguments;
}

// The one-command mode (OwnRanks.h): this run on `ranks` ranks of one thread; its exit code, or
// -1 (said why) when mpirun cannot start.
int runOnOwnRanks(int ranks, int argc, char** argv) {
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  const std::string program = n > 0 ? std::string(self, static_cast<size_t>(n)) : argv[0];
  std::fprintf(stderr,
               "sus: an implicit input: %d ranks of 1 thread under mpirun (--one-process: 1 "
               "process of %d threads)\n",
               ranks, ranks);
  std::string why;
  const int code = anode::runOnOwnRanks(ranks, program, argumentsOfRanks(argc, argv), why);
  if (code < 0)
    std::fprintf(stderr, "warning: %s: the run is 1 process of %d threads\n", why.c_str(), ranks);
  return code;
}

}  // namespace

// Runs the input (or with decomposeRanks > 0 only describes its boxes); returns the exit code.
int run(anode::RunOptions& options, long decomposeRanks) {
  const bool root = anode::Communicator::isRoot();
  // A stop asked for during setup ends the run at its first step (its checkpoint at step 0).
  anode::catchStopSignals();
  try {
    anode::Simulation sim(options);
    if (decomposeRanks > 0) {
      std::fputs(sim.mpm().describeDecomposition(static_cast<int>(decomposeRanks)).c_str(), stdout);
      return 0;
    }
    if (root)
      for (const std::string& w : sim.warnings()) std::fprintf(stderr, "warning: %s\n", w.c_str());
    // A launcher that binds each rank to fewer cores than it has threads (Open MPI binds to one
    // core for 2 ranks or fewer) makes the threads take turns: said once, not changed.
    const int cores = anode::coresOfThisProcess();
    const int crowded = anode::collective::firstRankWith(
        anode::Communicator::everyRank(), cores > 0 && omp_get_max_threads() > cores);
    if (root) {
      if (anode::Communicator::size() > 1)
        std::fprintf(stderr, "sus: %d ranks x %d thread(s), instruction set %s\n",
                     anode::Communicator::size(), omp_get_max_threads(),
                     anode::instructionSet().c_str());
      else
        std::fprintf(stderr, "sus: %d thread(s), instruction set %s\n", omp_get_max_threads(),
                     anode::instructionSet().c_str());
      if (crowded >= 0)
        std::fprintf(stderr,
                     "warning: rank %d runs %d threads on fewer cores (its binding): give "
                     "--threads, or bind each rank to as many cores (mpirun --map-by "
                     "slot:pe=N, srun --cpus-per-task=N)\n",
                     crowded, omp_get_max_threads());
    }
    try {
      sim.run();
    } catch (const anode::StoppedOnAnotherRank&) {
      return 3;  // the rank that found the problem reports it
    } catch (const anode::SimulationError& e) {
      std::fprintf(stderr, "sus: simulation stopped: %s\n", e.what());
      return 3;
    } catch (const anode::LibraryFailure& e) {  // of one rank of several (Errors.h)
      std::fprintf(stderr, "sus: simulation stopped on rank %d: %s\n", anode::Communicator::rank(),
                   e.what());
      anode::Communicator::abort(3);
    }
    sim.printTimings(anode::Communicator::everyRank());
    if (sim.stoppedOnRequest()) return 4;
  } catch (const anode::SetupFailedOnAnotherRank& e) {
    // An input error of other ranks only: rank 0 prints it, naming them (rank 0 reports its
    // own). Any other error: the rank that found it prints it.
    if (!e.input && e.rank == anode::Communicator::rank())
      std::fprintf(stderr, "sus: error on rank %d: %s\n", e.rank, e.what());
    if (root && e.input)
      std::fprintf(stderr,
                   "%s\n(found by rank %d, %d of the %d ranks: is the input on a file system "
                   "every node shares?)\n",
                   e.what(), e.rank, e.failing, anode::Communicator::size());
    return e.input ? 2 : 1;
  } catch (const anode::InputError& e) {
    // Every rank reads the same input and finds the same error: one reports it.
    if (root) std::fprintf(stderr, "%s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sus: error%s: %s\n",
                 anode::Communicator::size() > 1
                     ? (" on rank " + std::to_string(anode::Communicator::rank())).c_str()
                     : "",
                 e.what());
    // The other ranks may wait in a collective this rank will not enter.
    if (anode::Communicator::size() > 1) anode::Communicator::abort(1);
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  // Arrays above 1 MB come from the OS and go back to it when freed (glibc would otherwise raise
  // the threshold as they are freed and keep them in the heap): buffers freed between steps for
  // output then leave the peak memory.
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  const std::string missing = anode::missingInstructions();
  if (!missing.empty()) {
    std::fprintf(stderr,
                 "sus: built for instruction set %s, which this CPU lacks (%s): build for it with "
                 "cmake -DANODE_SIMD=none (or avx2), docs/performance.md\n",
                 anode::instructionSet().c_str(), missing.c_str());
    return 1;
  }
  anode::RunOptions options;
  long decomposeRanks = 0;
  bool oneProcess = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const char* next = i + 1 < argc ? argv[i + 1] : nullptr;
    if (a == "-h" || a == "--help") {
      std::fputs(kUsage, stdout);
      return 0;
    } else if (a == "-o") {
      if (!next) {
        std::fprintf(stderr, "sus: -o needs a directory\n%s", kUsage);
        return 2;
      }
      options.outputDir = next;
      ++i;
    } else if (a == "-restart" || a == "--restart") {
      if (!next) {
        std::fprintf(stderr, "sus: %s needs a directory\n%s", a.c_str(), kUsage);
        return 2;
      }
      options.restartDir = next;
      ++i;
    } else if (a == "--max-timesteps") {
      options.maxTimesteps = positiveNumber("--max-timesteps", next);
      ++i;
    } else if (a == "--threads") {
      omp_set_num_threads(static_cast<int>(positiveNumber("--threads", next)));
      ++i;
    } else if (a == "--one-process") {
      oneProcess = true;
    } else if (a == "--decompose") {
      decomposeRanks = positiveNumber("--decompose", next);
      ++i;
    } else if (a == "--ignore-unsupported") {
      options.ignoreUnsupported = true;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "sus: unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    } else if (options.input.empty()) {
      options.input = a;
    } else {
      std::fprintf(stderr, "sus: more than one input file given\n%s", kUsage);
      return 2;
    }
  }
  if (!options.restartDir.empty()) {
    if (!options.input.empty() || !options.outputDir.empty()) {
      std::fprintf(stderr, "sus: -restart DIR takes the input and output directory from DIR\n%s",
                   kUsage);
      return 2;
    }
    options.input = options.restartDir + "/input.ups";
  }
  if (options.input.empty()) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (decomposeRanks > 0 && !options.restartDir.empty()) {
    std::fprintf(stderr, "sus: --decompose takes an input, not -restart\n%s", kUsage);
    return 2;
  }
  if (!oneProcess && decomposeRanks == 0 && omp_get_max_threads() > 1 &&
      !anode::Communicator::launchedByLauncher() && anode::asksForImplicitPath(options.input)) {
    const int code = runOnOwnRanks(omp_get_max_threads(), argc, argv);
    if (code >= 0) return code;
  }
  anode::Communicator::start(&argc, &argv);
  if (decomposeRanks > 0 && anode::Communicator::size() > 1) {
    if (anode::Communicator::isRoot())
      std::fprintf(stderr, "sus: --decompose runs on one process, not under mpirun\n");
    anode::Communicator::stop();
    return 2;
  }
  options.countParticlesOnly = decomposeRanks > 0;
  const int code = run(options, decomposeRanks);
  anode::Communicator::stop();
  return code;
}
