#include "Components/MPM/GhostNodes.h"

#include <algorithm>
#include <cstring>

namespace anode {

namespace {

// Calls f(local index) for the nodes of box b, z slowest and x fastest (the order both sides of
// an exchange list them in).
template <class F>
void forNodes(const Grid& local, const NodeBox& b, F&& f) {
  for (int k = b.first.z(); k <= b.last.z(); ++k)
    for (int j = b.first.y(); j <= b.last.y(); ++j)
      for (int i = b.first.x(); i <= b.last.x(); ++i) f(local.nodeIndex(i, j, k));
}

}  // namespace

GhostNodes::GhostNodes(Collective every, const Decomposition& d, const Grid& whole,
                       const Grid& local, int rank, int ghost)
    : neighbours_(every, d.neighbours(whole, rank, ghost)), rank_(rank), local_(local) {
  slotOfNode_.assign(local.numNodes(), -1);
  for (int r : neighbours_.ranks()) {
    const Grid other = d.window(whole, r, ghost);
    overlap_.push_back(NodeBox{local.firstNode(), local.lastNode()}.intersection(
        NodeBox{other.firstNode(), other.lastNode()}));
    forNodes(local, overlap_.back(), [&](int n) { slotOfNode_[n] = 0; });
  }
  for (int n = 0; n < local.numNodes(); ++n)
    if (slotOfNode_[n] == 0) {
      slotOfNode_[n] = static_cast<int>(sharedNodes_.size());
      sharedNodes_.push_back(n);
    }
}

NodeBox GhostNodes::setReach(Collective every, const NodeBox& mine) {
  // One all-reduce of the lowest corners and the negated highest; a rank reaching no node adds
  // nothing.
  constexpr double none = 1e9;
  double corners[6];
  for (int d = 0; d < 3; ++d) {
    corners[d] = mine.empty() ? none : mine.first[d];
    corners[3 + d] = mine.empty() ? none : -mine.last[d];
  }
  collective::minimum(every, corners, 6);
  reach_ = mine;
  for (int d = 0; d < 3; ++d) {
    reachOfAll_.first[d] = static_cast<int>(corners[d]);
    reachOfAll_.last[d] = static_cast<int>(-corners[3 + d]);
  }
  return reachOfAll_;
}

void GhostNodes::sumOverRanks(Collective every, const std::vector<NodeArray>& arrays) {
  const std::vector<int>& ranks = neighbours_.ranks();
  if (ranks.empty()) return;
  int width = 0;
  for (const NodeArray& a : arrays) width += a.width;
  // To each neighbour: this rank's reach box, then its parts on the shared nodes within it.
  std::vector<std::string> send(ranks.size()), receive;
  std::vector<double> values;
  for (size_t q = 0; q < ranks.size(); ++q) {
    values.clear();
    forNodes(local_, overlap_[q].intersection(reach_), [&](int n) {
      for (const NodeArray& a : arrays)
        for (int c = 0; c < a.width; ++c)
          values.push_back(a.values[static_cast<size_t>(n) * a.width + c]);
    });
    const int box[6] = {reach_.first.x(), reach_.first.y(), reach_.first.z(),
                        reach_.last.x(),  reach_.last.y(),  reach_.last.z()};
    send[q].assign(reinterpret_cast<const char*>(box), sizeof box);
    send[q].append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  collective::exchangeWithNeighbours(every, neighbours_, send, receive);
  // Every rank storing a shared node adds the parts in the same order (rank order, 0 + ...), so
  // they all hold the same value. Only the shared nodes some rank reaches take part: every part
  // of the others is zero, and so is their sum.
  std::vector<int> summed;
  forNodes(local_, reachOfAll_.intersection(NodeBox{local_.firstNode(), local_.lastNode()}),
           [&](int n) {
             if (slotOfNode_[n] >= 0) summed.push_back(n);
           });
  total_.resize(sharedNodes_.size() * width);
  const auto totalOf = [&](int n) { return &total_[static_cast<size_t>(slotOfNode_[n]) * width]; };
  for (int n : summed) std::fill_n(totalOf(n), width, 0.0);
  auto addReceived = [&](size_t q) {
    int box[6];
    std::memcpy(box, receive[q].data(), sizeof box);
    const NodeBox theirs{Vec3i(box[0], box[1], box[2]), Vec3i(box[3], box[4], box[5])};
    values.resize((receive[q].size() - sizeof box) / sizeof(double));
    if (!values.empty())
      std::memcpy(values.data(), receive[q].data() + sizeof box, values.size() * sizeof(double));
    const double* in = values.data();
    forNodes(local_, overlap_[q].intersection(theirs), [&](int n) {
      double* t = totalOf(n);
      for (int c = 0; c < width; ++c) t[c] += *in++;
    });
  };
  auto addOwn = [&] {
    for (int n : summed) {
      double* t = totalOf(n);
      for (const NodeArray& a : arrays)
        for (int c = 0; c < a.width; ++c) *t++ += a.values[static_cast<size_t>(n) * a.width + c];
    }
  };
  bool ownAdded = false;
  for (size_t q = 0; q < ranks.size(); ++q) {
    if (!ownAdded && ranks[q] > rank_) {
      addOwn();
      ownAdded = true;
    }
    addReceived(q);
  }
  if (!ownAdded) addOwn();
  for (int n : summed) {
    const double* t = totalOf(n);
    for (const NodeArray& a : arrays)
      for (int c = 0; c < a.width; ++c) a.values[static_cast<size_t>(n) * a.width + c] = *t++;
  }
}

void GhostNodes::unionOverRanks(Collective every, std::vector<unsigned char>& marks) const {
  const std::vector<int>& ranks = neighbours_.ranks();
  if (ranks.empty()) return;
  std::vector<std::string> send(ranks.size()), receive;
  // Both sides list the nodes of the same box: no rank marks a node outside reachOfAll_.
  for (size_t q = 0; q < ranks.size(); ++q)
    forNodes(local_, overlap_[q].intersection(reachOfAll_),
             [&](int n) { send[q] += static_cast<char>(marks[n]); });
  collective::exchangeWithNeighbours(every, neighbours_, send, receive);
  for (size_t q = 0; q < ranks.size(); ++q) {
    size_t e = 0;
    forNodes(local_, overlap_[q].intersection(reachOfAll_),
             [&](int n) { marks[n] |= static_cast<unsigned char>(receive[q][e++]); });
  }
}

}  // namespace anode
