#include "Core/Parallel/Communicator.h"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace anode {

namespace {

bool started = false;
std::vector<void (*)()> stopHooks;  // Communicator::beforeStop
int worldRank = 0, worldSize = 1;
double seconds = 0, bytes = 0;

// Times one MPI call into `seconds`.
class CommunicationTimer {
 public:
  CommunicationTimer() : start_(std::chrono::steady_clock::now()) {}
  ~CommunicationTimer() {
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

void check(int status, const char* call) {
  if (status != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

void reduce(double* values, int n, MPI_Op op) {
  if (!started || n == 0) return;
  CommunicationTimer t;
  bytes += 8.0 * n;
  check(MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, op, MPI_COMM_WORLD), "MPI_Allreduce");
}

// The launchers' environment: Open MPI's mpirun, PMI and PMIx (srun, MPICH's hydra).
bool launchedByMpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> d(counts.size(), 0);
  for (size_t i = 1; i < counts.size(); ++i) d[i] = d[i - 1] + counts[i - 1];
  return d;
}

int byteCount(size_t n) {
  if (n > static_cast<size_t>(std::numeric_limits<int>::max()))
    throw std::runtime_error("MPI: a message of " + std::to_string(n) +
                             " bytes exceeds the 2 GiB one exchange can carry");
  return static_cast<int>(n);
}

}  // namespace

void Communicator::start(int* argc, char*** argv) {
  if (!launchedByMpi()) return;
  int provided = 0;
  check(MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &worldRank);
  MPI_Comm_size(MPI_COMM_WORLD, &worldSize);
}

void Communicator::beforeStop(void (*f)()) {
  if (started)
    stopHooks.push_back(f);
  else
    std::atexit(f);
}

void Communicator::stop() {
  for (auto it = stopHooks.rbegin(); it != stopHooks.rend(); ++it) (*it)();
  stopHooks.clear();
  if (started) MPI_Finalize();
  started = false;
}

void Communicator::abort(int code) {
  if (started) MPI_Abort(MPI_COMM_WORLD, code);
  std::exit(code);
}

int Communicator::rank() {
  return worldRank;
}
int Communicator::size() {
  return worldSize;
}

double Communicator::communicationSeconds() {
  return seconds;
}
double Communicator::bytesSent() {
  return bytes;
}

namespace collective {

void sum(double* values, int n) {
  reduce(values, n, MPI_SUM);
}
void minimum(double* values, int n) {
  reduce(values, n, MPI_MIN);
}
void maximum(double* values, int n) {
  reduce(values, n, MPI_MAX);
}

double sum(double v) {
  sum(&v, 1);
  return v;
}
double minimum(double v) {
  minimum(&v, 1);
  return v;
}
double maximum(double v) {
  maximum(&v, 1);
  return v;
}

int64_t sum(int64_t v) {
  if (!started) return v;
  CommunicationTimer t;
  bytes += 8;
  check(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return v;
}

int64_t exclusiveSum(int64_t v) {
  if (!started) return 0;
  CommunicationTimer t;
  bytes += 8;
  int64_t before = 0;
  check(MPI_Exscan(&v, &before, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Exscan");
  return worldRank == 0 ? 0 : before;  // MPI leaves rank 0's undefined
}

bool any(bool v) {
  return firstRankWith(v) >= 0;
}

int firstRankWith(bool flag) {
  int first = flag ? worldRank : worldSize;
  if (started) {
    CommunicationTimer t;
    bytes += 4;
    check(MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD),
          "MPI_Allreduce");
  }
  return first < worldSize ? first : -1;
}

void barrier() {
  if (!started) return;
  CommunicationTimer t;
  check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

std::string broadcast(const std::string& data, int root) {
  if (!started) return data;
  CommunicationTimer t;
  long long n = static_cast<long long>(data.size());
  check(MPI_Bcast(&n, 1, MPI_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = worldRank == root ? data : std::string(static_cast<size_t>(n), '\0');
  if (worldRank == root) bytes += static_cast<double>(n) * (worldSize - 1);
  check(MPI_Bcast(out.data(), byteCount(out.size()), MPI_CHAR, root, MPI_COMM_WORLD), "MPI_Bcast");
  return out;
}

std::vector<std::string> allGather(const std::string& data) {
  if (!started) return {data};
  CommunicationTimer t;
  int n = byteCount(data.size());
  std::vector<int> counts(worldSize);
  check(MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  const std::vector<int> at = displacements(counts);
  std::string all(static_cast<size_t>(at.back()) + counts.back(), '\0');
  bytes += static_cast<double>(n) * (worldSize - 1);
  check(MPI_Allgatherv(data.data(), n, MPI_CHAR, all.data(), counts.data(), at.data(), MPI_CHAR,
                       MPI_COMM_WORLD),
        "MPI_Allgatherv");
  std::vector<std::string> out(worldSize);
  for (int r = 0; r < worldSize; ++r) out[r] = all.substr(at[r], counts[r]);
  return out;
}

std::vector<std::string> exchangeWithAll(const std::vector<std::string>& send) {
  if (!started) return send;
  CommunicationTimer t;
  std::vector<int> sendCounts(worldSize), receiveCounts(worldSize);
  std::string out;
  for (int r = 0; r < worldSize; ++r) {
    sendCounts[r] = byteCount(send[r].size());
    out += send[r];
    if (r != worldRank) bytes += static_cast<double>(send[r].size());
  }
  check(
      MPI_Alltoall(sendCounts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT, MPI_COMM_WORLD),
      "MPI_Alltoall");
  const std::vector<int> sendAt = displacements(sendCounts),
                         receiveAt = displacements(receiveCounts);
  std::string in(static_cast<size_t>(receiveAt.back()) + receiveCounts.back(), '\0');
  check(MPI_Alltoallv(out.data(), sendCounts.data(), sendAt.data(), MPI_CHAR, in.data(),
                      receiveCounts.data(), receiveAt.data(), MPI_CHAR, MPI_COMM_WORLD),
        "MPI_Alltoallv");
  std::vector<std::string> received(worldSize);
  for (int r = 0; r < worldSize; ++r) received[r] = in.substr(receiveAt[r], receiveCounts[r]);
  return received;
}

}  // namespace collective

struct Neighbourhood::Handle {
  MPI_Comm graph = MPI_COMM_NULL;
};

Neighbourhood::Neighbourhood(Collective, std::vector<int> ranks) : ranks_(std::move(ranks)) {
  if (!started) return;
  handle_ = std::make_unique<Handle>();
  const int n = static_cast<int>(ranks_.size());
  check(MPI_Dist_graph_create_adjacent(MPI_COMM_WORLD, n, ranks_.data(), MPI_UNWEIGHTED, n,
                                       ranks_.data(), MPI_UNWEIGHTED, MPI_INFO_NULL, 0,
                                       &handle_->graph),
        "MPI_Dist_graph_create_adjacent");
}

Neighbourhood::Neighbourhood() = default;

Neighbourhood::~Neighbourhood() {
  if (handle_ && handle_->graph != MPI_COMM_NULL && started) MPI_Comm_free(&handle_->graph);
}

Neighbourhood::Neighbourhood(Neighbourhood&&) noexcept = default;
Neighbourhood& Neighbourhood::operator=(Neighbourhood&& other) noexcept {
  if (this != &other) {
    if (handle_ && handle_->graph != MPI_COMM_NULL && started) MPI_Comm_free(&handle_->graph);
    ranks_ = std::move(other.ranks_);
    handle_ = std::move(other.handle_);
  }
  return *this;
}

void collective::exchangeWithNeighbours(const Neighbourhood& neighbours,
                                        const std::vector<std::string>& send,
                                        std::vector<std::string>& receive) {
  const size_t n = neighbours.ranks_.size();
  receive.resize(n);
  if (!neighbours.handle_) return;
  CommunicationTimer t;
  std::vector<int> sendCounts(n), receiveCounts(n);
  for (size_t i = 0; i < n; ++i) {
    sendCounts[i] = byteCount(send[i].size());
    bytes += static_cast<double>(send[i].size());
  }
  check(MPI_Neighbor_alltoall(sendCounts.data(), 1, MPI_INT, receiveCounts.data(), 1, MPI_INT,
                              neighbours.handle_->graph),
        "MPI_Neighbor_alltoall");
  std::string out, in;
  for (const auto& s : send) out += s;
  const std::vector<int> sendAt = displacements(sendCounts),
                         receiveAt = displacements(receiveCounts);
  in.resize(n ? static_cast<size_t>(receiveAt.back()) + receiveCounts.back() : 0);
  check(MPI_Neighbor_alltoallv(out.data(), sendCounts.data(), sendAt.data(), MPI_CHAR, in.data(),
                               receiveCounts.data(), receiveAt.data(), MPI_CHAR,
                               neighbours.handle_->graph),
        "MPI_Neighbor_alltoallv");
  for (size_t i = 0; i < n; ++i) receive[i] = in.substr(receiveAt[i], receiveCounts[i]);
}

}  // namespace anode
