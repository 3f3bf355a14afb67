// The one place that talks MPI (DESIGN.md §5, docs/parallel.md): the ranks of a run (Communicator,
// local to each rank) and the operations every rank calls together (namespace collective:
// reductions over the ranks, byte exchanges with a fixed set of neighbours or with every rank). A
// process not started by mpirun or srun never calls MPI: it is a run of one rank, and every
// reduction and exchange here is then the identity.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace anode {

// The tag of a call every rank makes together, in the same order (docs/parallel.md): the first
// parameter of every collective and of every function or constructor that calls one; a function
// passes on the tag it was given. Only Communicator::everyRank makes one, called where a run's
// ranks are known to take the same path: sus's main, the driver's run, setup and step, a test's
// body (tests/check_collective_tags.sh holds that list). A function without the tag cannot reach
// a collective.
class Collective {
 private:
  Collective() {}
  friend class Communicator;
};

class Communicator {
 public:
  // Starts MPI (threads funnelled through the main thread) when the environment shows a launch
  // by an MPI launcher; otherwise does nothing. `stop` ends MPI if `start` began it.
  static void start(int* argc, char*** argv);
  // Whether the environment shows such a launch (mpirun, srun, MPICH's hydra).
  static bool launchedByLauncher();
  static void stop();
  // Runs `f` in `stop` before MPI ends (a library that uses MPI too, such as PETSc, ends first);
  // when `start` did not begin MPI, at the process's exit.
  static void beforeStop(void (*f)());
  // Ends every rank of the run with `code` (a rank that cannot reach the others' next collective).
  [[noreturn]] static void abort(int code);

  static int rank();
  static int size();
  static bool isRoot() { return rank() == 0; }

  // Time spent in and bytes sent by the exchanges and reductions of this process so far.
  static double communicationSeconds();
  static double bytesSent();
  // The collective calls of this process so far (each reduction or exchange once).
  static long collectiveCalls();

  // The tag of the run's top level (see Collective).
  static Collective everyRank() { return Collective(); }
};

class Neighbourhood;

// Every function here is collective: every rank of the run calls it, in the same order.
namespace collective {

// Reductions over all ranks, in place on `n` values; every rank gets the result.
void sum(Collective, double* values, int n);
void minimum(Collective, double* values, int n);
void maximum(Collective, double* values, int n);
double sum(Collective, double v);
double minimum(Collective, double v);
double maximum(Collective, double v);
int64_t sum(Collective, int64_t v);
// The smallest of each of `n` values over the ranks, on rank 0 only (the others' values are left
// as they were); in pieces of at most 2^30 bytes.
void minimumOnRoot(Collective, uint64_t* values, size_t n);
// The sum of v over the ranks before this one (0 on rank 0).
int64_t exclusiveSum(Collective, int64_t v);
bool any(Collective, bool v);
// The lowest rank on which `flag` holds, or -1 if it holds on none.
int firstRankWith(Collective, bool flag);
void barrier(Collective);

// Rank `root`'s bytes on every rank.
std::string broadcast(Collective, const std::string& bytes, int root);
// Every rank's bytes on every rank, in rank order.
std::vector<std::string> allGather(Collective, const std::string& bytes);
// send[r] goes to rank r; returns what each rank sent here, in rank order (MPI_Alltoallv).
std::vector<std::string> exchangeWithAll(Collective, const std::vector<std::string>& send);
// Sends send[i] to n.ranks()[i]; receive[i] gets what n.ranks()[i] sent (MPI_Neighbor_alltoallv).
void exchangeWithNeighbours(Collective, const Neighbourhood& n,
                            const std::vector<std::string>& send,
                            std::vector<std::string>& receive);

}  // namespace collective

// A fixed, symmetric set of neighbour ranks (each lists the other): one MPI distributed-graph
// communicator for collective::exchangeWithNeighbours. Creating one is collective.
class Neighbourhood {
 public:
  Neighbourhood();
  Neighbourhood(Collective, std::vector<int> ranks);
  ~Neighbourhood();
  Neighbourhood(Neighbourhood&&) noexcept;
  Neighbourhood& operator=(Neighbourhood&&) noexcept;

  const std::vector<int>& ranks() const { return ranks_; }

 private:
  friend void collective::exchangeWithNeighbours(Collective, const Neighbourhood&,
                                                 const std::vector<std::string>&,
                                                 std::vector<std::string>&);
  struct Handle;
  std::vector<int> ranks_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace anode
