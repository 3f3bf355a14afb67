#include "Core/Parallel/Communicator.h"

#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace anode {

namespace {

bool started = false;
std::vector<void (*)()> stopHooks;  // Communicator::beforeStop
int worldRank = 0, worldSize = 1;
double seconds = 0, bytes = 0;
long calls = 0;  // collective calls (every rank makes the same ones)

// Times one MPI call into `seconds`.
class CommunicationTimer {
 public:
  CommunicationTimer() : start_(std::chrono::steady_clock::now()) { ++calls; }
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

// The most bytes one MPI message carries here: counts are ints, and Open MPI 4.1 fails on a
// message above 2^31 bytes whatever its datatype. Larger messages go in pieces of this size.
constexpr size_t kLargest = size_t{1} << 30;
constexpr int kLargeMessageTag = 7001;

// The n <= kLargest bytes at p as one MPI datatype at their absolute address (for buffer
// MPI_BOTTOM), so that an exchange's counts and displacements are 1 and 0 whatever the sizes and
// their sum (MPI_Alltoallw's displacements are ints). MPI matches type signatures: n MPI_CHARs
// on either side, however each side builds them.
class BytesAt {
 public:
  BytesAt(const char* p, size_t n) {
    int length = static_cast<int>(n);
    MPI_Aint address = 0;
    MPI_Datatype bytes = MPI_CHAR;
    check(MPI_Get_address(p, &address), "MPI_Get_address");
    check(MPI_Type_create_struct(1, &length, &address, &bytes, &type_), "MPI_Type_create_struct");
    check(MPI_Type_commit(&type_), "MPI_Type_commit");
  }
  ~BytesAt() { MPI_Type_free(&type_); }
  BytesAt(const BytesAt&) = delete;
  BytesAt& operator=(const BytesAt&) = delete;
  MPI_Datatype type() const { return type_; }

 private:
  MPI_Datatype type_ = MPI_DATATYPE_NULL;
};

// The messages above kLargest of one exchange, point to point in pieces of at most kLargest (a
// pair posts its pieces in the same order, and MPI keeps the order of one sender's messages of
// one tag): posted as they are added, completed by wait.
class LargeMessages {
 public:
  void send(const std::string& bytes, int rank) {
    post(const_cast<char*>(bytes.data()), bytes.size(), rank, true);
  }
  void receive(std::string& bytes, int rank) { post(bytes.data(), bytes.size(), rank, false); }
  void wait() {
    check(MPI_Waitall(static_cast<int>(requests_.size()), requests_.data(), MPI_STATUSES_IGNORE),
          "MPI_Waitall");
    requests_.clear();
  }

 private:
  void post(char* p, size_t n, int rank, bool out) {
    for (size_t done = 0; done < n; done += kLargest) {
      const int length = static_cast<int>(std::min(kLargest, n - done));
      requests_.emplace_back();
      if (out)
        check(MPI_Isend(p + done, length, MPI_CHAR, rank, kLargeMessageTag, MPI_COMM_WORLD,
                        &requests_.back()),
              "MPI_Isend");
      else
        check(MPI_Irecv(p + done, length, MPI_CHAR, rank, kLargeMessageTag, MPI_COMM_WORLD,
                        &requests_.back()),
              "MPI_Irecv");
    }
  }
  std::vector<MPI_Request> requests_;
};

// One datatype per message of an MPI_Alltoallw: the message's bytes, or none when it is above
// kLargest (LargeMessages carries it).
struct MessageTypes {
  std::vector<std::unique_ptr<BytesAt>> owned;
  std::vector<MPI_Datatype> types;
  std::vector<int> counts, zeros;
  void add(const std::string& bytes) {
    const bool inline_ = bytes.size() <= kLargest;
    owned.push_back(std::make_unique<BytesAt>(bytes.data(), inline_ ? bytes.size() : 0));
    types.push_back(owned.back()->type());
    counts.push_back(1);
    zeros.push_back(0);
  }
};

}  // namespace

bool Communicator::launchedByLauncher() {
  return launchedByMpi();
}

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
long Communicator::collectiveCalls() {
  return calls;
}

namespace collective {

void sum(Collective, double* values, int n) {
  reduce(values, n, MPI_SUM);
}
void minimumOnRoot(Collective, uint64_t* values, size_t n) {
  if (!started || n == 0) return;
  CommunicationTimer t;
  bytes += 8.0 * static_cast<double>(n);
  const bool root = Communicator::isRoot();
  for (size_t first = 0; first < n; first += kLargest / 8) {
    const int count = static_cast<int>(std::min(n - first, kLargest / 8));
    check(MPI_Reduce(root ? MPI_IN_PLACE : values + first, root ? values + first : nullptr, count,
                     MPI_UINT64_T, MPI_MIN, 0, MPI_COMM_WORLD),
          "MPI_Reduce");
  }
}
void minimum(Collective, double* values, int n) {
  reduce(values, n, MPI_MIN);
}
void maximum(Collective, double* values, int n) {
  reduce(values, n, MPI_MAX);
}

double sum(Collective every, double v) {
  sum(every, &v, 1);
  return v;
}
double minimum(Collective every, double v) {
  minimum(every, &v, 1);
  return v;
}
double maximum(Collective every, double v) {
  maximum(every, &v, 1);
  return v;
}

int64_t sum(Collective, int64_t v) {
  if (!started) return v;
  CommunicationTimer t;
  bytes += 8;
  check(MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Allreduce");
  return v;
}

int64_t exclusiveSum(Collective, int64_t v) {
  if (!started) return 0;
  CommunicationTimer t;
  bytes += 8;
  int64_t before = 0;
  check(MPI_Exscan(&v, &before, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD), "MPI_Exscan");
  return worldRank == 0 ? 0 : before;  // MPI leaves rank 0's undefined
}

bool any(Collective every, bool v) {
  return firstRankWith(every, v) >= 0;
}

int firstRankWith(Collective, bool flag) {
  int first = flag ? worldRank : worldSize;
  if (started) {
    CommunicationTimer t;
    bytes += 4;
    check(MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD),
          "MPI_Allreduce");
  }
  return first < worldSize ? first : -1;
}

void barrier(Collective) {
  if (!started) return;
  CommunicationTimer t;
  check(MPI_Barrier(MPI_COMM_WORLD), "MPI_Barrier");
}

std::string broadcast(Collective, const std::string& data, int root) {
  if (!started) return data;
  CommunicationTimer t;
  long long n = static_cast<long long>(data.size());
  check(MPI_Bcast(&n, 1, MPI_LONG_LONG, root, MPI_COMM_WORLD), "MPI_Bcast");
  std::string out = worldRank == root ? data : std::string(static_cast<size_t>(n), '\0');
  if (worldRank == root) bytes += static_cast<double>(n) * (worldSize - 1);
  for (size_t done = 0; done < out.size(); done += kLargest)
    check(MPI_Bcast(out.data() + done, static_cast<int>(std::min(kLargest, out.size() - done)),
                    MPI_CHAR, root, MPI_COMM_WORLD),
          "MPI_Bcast");
  return out;
}

std::vector<std::string> allGather(Collective, const std::string& data) {
  if (!started) return {data};
  CommunicationTimer t;
  int64_t size = static_cast<int64_t>(data.size());
  std::vector<int64_t> sizes(worldSize);
  check(MPI_Allgather(&size, 1, MPI_INT64_T, sizes.data(), 1, MPI_INT64_T, MPI_COMM_WORLD),
        "MPI_Allgather");
  bytes += static_cast<double>(data.size()) * (worldSize - 1);
  std::vector<std::string> gathered(worldSize);
  LargeMessages large;
  MessageTypes mine, in;
  mine.add(data);
  for (int r = 0; r < worldSize; ++r) {
    gathered[r].resize(static_cast<size_t>(sizes[r]));
    in.add(gathered[r]);
    if (r == worldRank) continue;
    if (gathered[r].size() > kLargest) large.receive(gathered[r], r);
    if (data.size() > kLargest) large.send(data, r);
  }
  const std::vector<MPI_Datatype> sendTypes(worldSize, mine.types[0]);
  const std::vector<int> ones(worldSize, 1), zeros(worldSize, 0);
  check(MPI_Alltoallw(MPI_BOTTOM, ones.data(), zeros.data(), sendTypes.data(), MPI_BOTTOM,
                      in.counts.data(), in.zeros.data(), in.types.data(), MPI_COMM_WORLD),
        "MPI_Alltoallw");
  large.wait();
  if (data.size() > kLargest) gathered[worldRank] = data;
  return gathered;
}

std::vector<std::string> exchangeWithAll(Collective, const std::vector<std::string>& send) {
  if (!started) return send;
  CommunicationTimer t;
  std::vector<int64_t> sendSizes(worldSize), receiveSizes(worldSize);
  for (int r = 0; r < worldSize; ++r) {
    sendSizes[r] = static_cast<int64_t>(send[r].size());
    if (r != worldRank) bytes += static_cast<double>(send[r].size());
  }
  check(MPI_Alltoall(sendSizes.data(), 1, MPI_INT64_T, receiveSizes.data(), 1, MPI_INT64_T,
                     MPI_COMM_WORLD),
        "MPI_Alltoall");
  std::vector<std::string> received(worldSize);
  LargeMessages large;
  MessageTypes out, in;
  for (int r = 0; r < worldSize; ++r) {
    received[r].resize(static_cast<size_t>(receiveSizes[r]));
    out.add(send[r]);
    in.add(received[r]);
    if (r == worldRank) continue;
    if (send[r].size() > kLargest) large.send(send[r], r);
    if (received[r].size() > kLargest) large.receive(received[r], r);
  }
  check(MPI_Alltoallw(MPI_BOTTOM, out.counts.data(), out.zeros.data(), out.types.data(), MPI_BOTTOM,
                      in.counts.data(), in.zeros.data(), in.types.data(), MPI_COMM_WORLD),
        "MPI_Alltoallw");
  large.wait();
  if (send[worldRank].size() > kLargest) received[worldRank] = send[worldRank];
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

void collective::exchangeWithNeighbours(Collective, const Neighbourhood& neighbours,
                                        const std::vector<std::string>& send,
                                        std::vector<std::string>& receive) {
  const size_t n = neighbours.ranks_.size();
  receive.resize(n);
  if (!neighbours.handle_) return;
  CommunicationTimer t;
  std::vector<int64_t> sendSizes(n), receiveSizes(n);
  for (size_t i = 0; i < n; ++i) {
    sendSizes[i] = static_cast<int64_t>(send[i].size());
    bytes += static_cast<double>(send[i].size());
  }
  check(MPI_Neighbor_alltoall(sendSizes.data(), 1, MPI_INT64_T, receiveSizes.data(), 1, MPI_INT64_T,
                              neighbours.handle_->graph),
        "MPI_Neighbor_alltoall");
  // Each message straight from and into its own string: MPI_CHARs at absolute displacements
  // (MPI_Aint), or none when it is above kLargest (LargeMessages carries it).
  std::vector<int> sendCounts(n), receiveCounts(n);
  std::vector<MPI_Aint> sendAt(n), receiveAt(n);
  const std::vector<MPI_Datatype> types(n, MPI_CHAR);
  LargeMessages large;
  for (size_t i = 0; i < n; ++i) {
    receive[i].resize(static_cast<size_t>(receiveSizes[i]));
    const int rank = neighbours.ranks_[i];
    if (send[i].size() > kLargest)
      large.send(send[i], rank);
    else
      sendCounts[i] = static_cast<int>(send[i].size());
    if (receive[i].size() > kLargest)
      large.receive(receive[i], rank);
    else
      receiveCounts[i] = static_cast<int>(receive[i].size());
    check(MPI_Get_address(send[i].data(), &sendAt[i]), "MPI_Get_address");
    check(MPI_Get_address(receive[i].data(), &receiveAt[i]), "MPI_Get_address");
  }
  check(MPI_Neighbor_alltoallw(MPI_BOTTOM, sendCounts.data(), sendAt.data(), types.data(),
                               MPI_BOTTOM, receiveCounts.data(), receiveAt.data(), types.data(),
                               neighbours.handle_->graph),
        "MPI_Neighbor_alltoallw");
  large.wait();
}

}  // namespace anode
