#include "Components/MPM/GhostNodes.h"

#include <algorithm>
#include <cstring>

namespace anode {

GhostNodes::GhostNodes(const Decomposition& d, const Grid& whole, const Grid& local, int rank,
                       int ghost)
    : neighbours_(d.neighbours(whole, rank, ghost)), rank_(rank) {
  for (int r : neighbours_.ranks()) {
    const Grid other = d.window(whole, r, ghost);
    const Vec3i lo = local.firstNode().cwiseMax(other.firstNode());
    const Vec3i hi = local.lastNode().cwiseMin(other.lastNode());
    std::vector<int>& nodes = overlap_.emplace_back();
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i) nodes.push_back(local.nodeIndex(i, j, k));
    sharedNodes_.insert(sharedNodes_.end(), nodes.begin(), nodes.end());
  }
  std::sort(sharedNodes_.begin(), sharedNodes_.end());
  sharedNodes_.erase(std::unique(sharedNodes_.begin(), sharedNodes_.end()), sharedNodes_.end());
  for (const std::vector<int>& nodes : overlap_) {
    std::vector<int>& slots = slot_.emplace_back();
    for (int n : nodes)
      slots.push_back(static_cast<int>(
          std::lower_bound(sharedNodes_.begin(), sharedNodes_.end(), n) - sharedNodes_.begin()));
  }
}

void GhostNodes::sumOverRanks(const std::vector<NodeArray>& arrays) const {
  const std::vector<int>& ranks = neighbours_.ranks();
  if (ranks.empty()) return;
  int width = 0;
  for (const NodeArray& a : arrays) width += a.width;
  std::vector<std::string> send(ranks.size()), receive;
  std::vector<double> values;
  for (size_t q = 0; q < ranks.size(); ++q) {
    values.clear();
    for (int n : overlap_[q])
      for (const NodeArray& a : arrays)
        for (int c = 0; c < a.width; ++c)
          values.push_back(a.values[static_cast<size_t>(n) * a.width + c]);
    send[q].assign(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
  }
  neighbours_.exchange(send, receive);
  // Every rank storing a shared node adds the parts in the same order (rank order, 0 + ...), so
  // they all hold the same value.
  std::vector<double> total(sharedNodes_.size() * width, 0.0);
  auto addReceived = [&](size_t q) {
    values.resize(receive[q].size() / sizeof(double));
    std::memcpy(values.data(), receive[q].data(), values.size() * sizeof(double));
    const double* in = values.data();
    for (int s : slot_[q]) {
      double* t = &total[static_cast<size_t>(s) * width];
      for (int c = 0; c < width; ++c) t[c] += *in++;
    }
  };
  auto addOwn = [&] {
    for (size_t s = 0; s < sharedNodes_.size(); ++s) {
      double* t = &total[s * width];
      for (const NodeArray& a : arrays)
        for (int c = 0; c < a.width; ++c)
          *t++ += a.values[static_cast<size_t>(sharedNodes_[s]) * a.width + c];
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
  for (size_t s = 0; s < sharedNodes_.size(); ++s) {
    const double* t = &total[s * width];
    for (const NodeArray& a : arrays)
      for (int c = 0; c < a.width; ++c)
        a.values[static_cast<size_t>(sharedNodes_[s]) * a.width + c] = *t++;
  }
}

void GhostNodes::unionOverRanks(std::vector<unsigned char>& marks) const {
  const std::vector<int>& ranks = neighbours_.ranks();
  if (ranks.empty()) return;
  std::vector<std::string> send(ranks.size()), receive;
  for (size_t q = 0; q < ranks.size(); ++q)
    for (int n : overlap_[q]) send[q] += static_cast<char>(marks[n]);
  neighbours_.exchange(send, receive);
  for (size_t q = 0; q < ranks.size(); ++q)
    for (size_t e = 0; e < overlap_[q].size(); ++e)
      marks[overlap_[q][e]] |= static_cast<unsigned char>(receive[q][e]);
}

}  // namespace anode
