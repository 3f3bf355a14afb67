// The one place that talks MPI (DESIGN.md §5, docs/parallel.md): the ranks of a run, reductions
// over them, and byte exchanges with a fixed set of neighbours or with every rank. A process not
// started by mpirun or srun never calls MPI: it is a run of one rank, and every reduction and
// exchange here is then the identity.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace anode {

class Communicator {
 public:
  // Starts MPI (threads funnelled through the main thread) when the environment shows a launch
  // by an MPI launcher; otherwise does nothing. `stop` ends MPI if `start` began it.
  static void start(int* argc, char*** argv);
  static void stop();
  // Ends every rank of the run with `code` (a rank that cannot reach the others' next collective).
  [[noreturn]] static void abort(int code);

  static int rank();
  static int size();
  static bool isRoot() { return rank() == 0; }

  // Reductions over all ranks, in place on `n` values; every rank gets the result.
  static void sum(double* values, int n);
  static void minimum(double* values, int n);
  static void maximum(double* values, int n);
  static double sum(double v);
  static double minimum(double v);
  static double maximum(double v);
  static int64_t sum(int64_t v);
  static bool any(bool v);
  // The lowest rank on which `flag` holds, or -1 if it holds on none.
  static int firstRankWith(bool flag);
  static void barrier();

  // Rank `root`'s bytes on every rank.
  static std::string broadcast(const std::string& bytes, int root);
  // Every rank's bytes on every rank, in rank order.
  static std::vector<std::string> allGather(const std::string& bytes);
  // send[r] goes to rank r; returns what each rank sent here, in rank order (MPI_Alltoallv).
  static std::vector<std::string> exchangeWithAll(const std::vector<std::string>& send);

  // Time spent in and bytes sent by the exchanges and reductions of this process so far.
  static double communicationSeconds();
  static double bytesSent();
};

// A fixed, symmetric set of neighbour ranks (each lists the other) and exchanges with them over
// one MPI distributed-graph communicator (MPI_Neighbor_alltoallv). Creating one is collective.
class Neighbourhood {
 public:
  Neighbourhood();
  explicit Neighbourhood(std::vector<int> ranks);
  ~Neighbourhood();
  Neighbourhood(Neighbourhood&&) noexcept;
  Neighbourhood& operator=(Neighbourhood&&) noexcept;

  const std::vector<int>& ranks() const { return ranks_; }
  // Sends send[i] to ranks()[i]; receive[i] gets what ranks()[i] sent. Every rank of the run
  // calls it together.
  void exchange(const std::vector<std::string>& send, std::vector<std::string>& receive) const;

 private:
  struct Handle;
  std::vector<int> ranks_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace anode
