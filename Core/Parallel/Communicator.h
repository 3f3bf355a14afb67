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

// Marks a function or constructor outside namespace collective that every rank must call together
// (it calls collectives): the first parameter of its declaration, `Collective{}` at each call
// (docs/parallel.md).
struct Collective {};

class Communicator {
 public:
  // Starts MPI (threads funnelled through the main thread) when the environment shows a launch
  // by an MPI launcher; otherwise does nothing. `stop` ends MPI if `start` began it.
  static void start(int* argc, char*** argv);
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
};

class Neighbourhood;

// Every function here is collective: every rank of the run calls it, in the same order.
namespace collective {

// Reductions over all ranks, in place on `n` values; every rank gets the result.
void sum(double* values, int n);
void minimum(double* values, int n);
void maximum(double* values, int n);
double sum(double v);
double minimum(double v);
double maximum(double v);
int64_t sum(int64_t v);
// The smallest of each of `n` values over the ranks, on rank 0 only (the others' values are left
// as they were); in pieces of at most 2^30 bytes.
void minimumOnRoot(uint64_t* values, size_t n);
// The sum of v over the ranks before this one (0 on rank 0).
int64_t exclusiveSum(int64_t v);
bool any(bool v);
// The lowest rank on which `flag` holds, or -1 if it holds on none.
int firstRankWith(bool flag);
void barrier();

// Rank `root`'s bytes on every rank.
std::string broadcast(const std::string& bytes, int root);
// Every rank's bytes on every rank, in rank order.
std::vector<std::string> allGather(const std::string& bytes);
// send[r] goes to rank r; returns what each rank sent here, in rank order (MPI_Alltoallv).
std::vector<std::string> exchangeWithAll(const std::vector<std::string>& send);
// Sends send[i] to n.ranks()[i]; receive[i] gets what n.ranks()[i] sent (MPI_Neighbor_alltoallv).
void exchangeWithNeighbours(const Neighbourhood& n, const std::vector<std::string>& send,
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
  friend void collective::exchangeWithNeighbours(const Neighbourhood&,
                                                 const std::vector<std::string>&,
                                                 std::vector<std::string>&);
  struct Handle;
  std::vector<int> ranks_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace anode
