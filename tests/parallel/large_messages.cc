// Byte exchanges above 2 GiB (Core/Parallel/Communicator.h): run on 2 ranks under mpirun. MPI's
// counts and displacements are ints; the exchanges describe each message by a datatype of its
// bytes, so a message above 2^31 bytes, and an all-gather whose total is, arrive whole. Prints
// PASS, or FAIL with what differed (exit 1).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "Core/Parallel/Communicator.h"

namespace {

using anode::Collective;
using anode::Communicator;

// n bytes that differ with `seed` and along the message (8 at a time: gigabytes in seconds).
std::string pattern(size_t n, uint64_t seed) {
  std::string s(n, '\0');
  uint64_t x = seed * 0x9E3779B97F4A7C15ull + 1;
  for (size_t i = 0; i < n; i += 8) {
    x ^= x << 13, x ^= x >> 7, x ^= x << 17;
    std::memcpy(&s[i], &x, std::min<size_t>(8, n - i));
  }
  return s;
}

int failures = 0;

void expect(bool ok, const char* what) {
  if (ok) return;
  std::printf("FAIL: rank %d: %s\n", Communicator::rank(), what);
  ++failures;
}

}  // namespace

int main(int argc, char** argv) {
  Communicator::start(&argc, &argv);
  const int me = Communicator::rank(), other = 1 - me;
  if (Communicator::size() != 2) {
    std::printf("FAIL: needs 2 ranks\n");
    Communicator::stop();
    return 1;
  }
  const size_t above = (size_t{1} << 31) + 5;  // one message above 2^31 bytes
  const Collective every = Communicator::everyRank();
  {
    // All-gather of 1.1 GiB a rank: 2.2 GiB in all, past an int displacement.
    const size_t each = (size_t{11} << 30) / 10 + static_cast<size_t>(me);
    const std::vector<std::string> all =
        anode::collective::allGather(every, pattern(each, 10 + me));
    expect(all.size() == 2, "allGather: 2 pieces");
    for (int r = 0; r < 2; ++r)
      expect(all[r] == pattern((size_t{11} << 30) / 10 + static_cast<size_t>(r), 10 + r),
             "allGather: a rank's 1.1 GiB");
  }
  {
    std::vector<std::string> send(2);
    send[other] = me == 0 ? pattern(above, 20) : pattern(1000, 21);
    const std::vector<std::string> received = anode::collective::exchangeWithAll(every, send);
    expect(received[other] == (me == 1 ? pattern(above, 20) : pattern(1000, 21)),
           "exchangeWithAll: 2^31 + 5 bytes from rank 0, 1000 from rank 1");
    expect(received[me].empty(), "exchangeWithAll: nothing to itself");
  }
  {
    const anode::Neighbourhood pair(every, {other});
    std::vector<std::string> receive;
    anode::collective::exchangeWithNeighbours(
        every, pair, {me == 1 ? pattern(above, 30) : pattern(7, 31)}, receive);
    expect(receive.size() == 1 && receive[0] == (me == 0 ? pattern(above, 30) : pattern(7, 31)),
           "exchangeWithNeighbours: 2^31 + 5 bytes from rank 1, 7 from rank 0");
  }
  {
    const std::string sent =
        anode::collective::broadcast(every, me == 1 ? pattern(above, 40) : "", 1);
    expect(sent == pattern(above, 40), "broadcast: 2^31 + 5 bytes from rank 1");
  }
  const bool anyFailed = anode::collective::any(every, failures > 0);
  if (me == 0 && !anyFailed) std::printf("PASS\n");
  Communicator::stop();
  return anyFailed ? 1 : 0;
}
