#include "Core/Parallel/BisectionSearch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace anode {

RegionCounts::RegionCounts(const CellBox& region, const double* perCell)
    : region_(region), n_(region.upper - region.lower) {
  const Vec3i m = n_ + Vec3i::Ones();
  prefix_.assign(static_cast<size_t>(m.cast<long>().prod()), 0.0);
  const auto at = [&](int i, int j, int k) {
    return (static_cast<size_t>(k) * m.y() + j) * m.x() + i;
  };
  for (int k = 0; k < n_.z(); ++k)
    for (int j = 0; j < n_.y(); ++j)
      for (int i = 0; i < n_.x(); ++i)
        prefix_[at(i + 1, j + 1, k + 1)] =
            perCell[(static_cast<size_t>(k) * n_.y() + j) * n_.x() + i] +
            prefix_[at(i, j + 1, k + 1)] + prefix_[at(i + 1, j, k + 1)] +
            prefix_[at(i + 1, j + 1, k)] - prefix_[at(i, j, k + 1)] - prefix_[at(i, j + 1, k)] -
            prefix_[at(i + 1, j, k)] + prefix_[at(i, j, k)];
}

double RegionCounts::in(const CellBox& box) const {
  const Vec3i lo = (box.lower.cwiseMax(region_.lower) - region_.lower);
  const Vec3i hi = (box.upper.cwiseMin(region_.upper) - region_.lower);
  if ((hi.array() <= lo.array()).any()) return 0;
  const Vec3i m = n_ + Vec3i::Ones();
  const auto p = [&](int i, int j, int k) {
    return prefix_[(static_cast<size_t>(k) * m.y() + j) * m.x() + i];
  };
  return p(hi.x(), hi.y(), hi.z()) - p(lo.x(), hi.y(), hi.z()) - p(hi.x(), lo.y(), hi.z()) -
         p(hi.x(), hi.y(), lo.z()) + p(lo.x(), lo.y(), hi.z()) + p(lo.x(), hi.y(), lo.z()) +
         p(hi.x(), lo.y(), lo.z()) - p(lo.x(), lo.y(), lo.z());
}

BisectionSearch::BisectionSearch(const RegionCounts& counts, long budget)
    : counts_(counts), budget_(budget) {}

BisectionCut BisectionSearch::cut(const CellBox& box, int ranks) {
  const BisectionCut chosen = best(box, ranks).cut;
  if (chosen.axis < 0)
    throw std::runtime_error("recursive bisection: a box of " + std::to_string(box.cellCount()) +
                             " cells cannot hold " + std::to_string(ranks) + " ranks");
  return chosen;
}

BisectionSearch::Choice BisectionSearch::best(const CellBox& box, int ranks) {
  if (ranks == 1) return {counts_.in(box), {}};
  const auto key = std::make_tuple(box.lower.x(), box.lower.y(), box.lower.z(), box.upper.x(),
                                   box.upper.y(), box.upper.z(), ranks);
  if (const auto found = known_.find(key); found != known_.end()) return found->second;
  // The cuts near the even share: per cell plane, the ranks halved or shared as the cut shares
  // the particles (rounded either way, and one rank further), each part a cell per rank; the
  // busier part's particles per rank bound what its subtree's busiest rank can hold.
  struct Candidate {
    double bound;
    int evenness;
    BisectionCut cut;
  };
  const double total = counts_.in(box);
  if (total <= 0) {
    // No particles: the middle of an axis, the ranks halved, as a level-by-level cut.
    const Vec3i extent = box.upper - box.lower;
    const std::array<std::vector<double>, 3> none{std::vector<double>(extent.x(), 0.0),
                                                  std::vector<double>(extent.y(), 0.0),
                                                  std::vector<double>(extent.z(), 0.0)};
    Choice empty{INFINITY, {}};
    try {
      empty = {0.0, bisectionCut(box, none, ranks)};
    } catch (const std::runtime_error&) {
    }
    known_.emplace(key, empty);
    return empty;
  }
  std::vector<Candidate> candidates;
  for (int d = 0; d < 3; ++d) {
    const int extent = box.upper[d] - box.lower[d];
    if (extent < 2) continue;
    const long across = box.cellCount() / extent;
    for (int j = 1; j < extent; ++j) {
      CellBox low = box;
      low.upper[d] = box.lower[d] + j;
      const double below = counts_.in(low);
      // The level-by-level cut's shares and one rank beyond: every level-by-level cut is here.
      const RankShares shares =
          sharesOfRanks(below, total, ranks, j * across, (extent - j) * across, true);
      for (int i = 0; i < shares.count; ++i) {
        const int left = shares.left[i];
        const double bound = std::max(below / left, (total - below) / (ranks - left));
        candidates.push_back({bound, std::abs(2 * left - ranks), {d, box.lower[d] + j, left}});
      }
    }
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.bound, a.evenness, a.cut.axis, a.cut.at, a.cut.left) <
           std::tie(b.bound, b.evenness, b.cut.axis, b.cut.at, b.cut.left);
  });
  // No cut, or none whose parts can be cut in turn: infinitely busy (cut() throws).
  Choice chosen{INFINITY, {}};
  for (const Candidate& c : candidates) {
    // Sorted by bound: no later cut can leave fewer particles on the busiest rank. Beyond the
    // budget, the first cut whose parts can be cut.
    if (c.bound >= chosen.busiest || (budget_ <= 0 && chosen.cut.axis >= 0)) break;
    --budget_;
    CellBox low = box, high = box;
    low.upper[c.cut.axis] = high.lower[c.cut.axis] = c.cut.at;
    const double busiest =
        std::max(best(low, c.cut.left).busiest, best(high, ranks - c.cut.left).busiest);
    if (busiest < chosen.busiest) chosen = {busiest, c.cut};
  }
  known_.emplace(key, chosen);
  return chosen;
}

}  // namespace anode
