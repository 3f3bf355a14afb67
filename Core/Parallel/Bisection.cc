#include "Core/Parallel/Bisection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace anode {

namespace {

// The occupied extent of `planes` (first to last nonzero), or the whole when empty.
int span(const std::vector<double>& planes) {
  int first = -1, last = -1;
  for (int p = 0; p < static_cast<int>(planes.size()); ++p)
    if (planes[p] > 0) {
      if (first < 0) first = p;
      last = p;
    }
  return first < 0 ? static_cast<int>(planes.size()) : last - first + 1;
}

// A cut after `cut` planes along an axis giving its first part `left` of the ranks, the load of
// the busier part (particles per rank over the box's mean), and the axis' preference when two
// cuts load alike.
struct Candidate {
  int cut = 0, left = 0;
  double load = INFINITY;
  long preference = 0;
};

// Whether candidate a is better than b: a lighter load (by more than 1e-3), else a more even
// split of the ranks, else the preferred axis.
bool better(const Candidate& a, const Candidate& b, int ranks) {
  if (std::abs(a.load - b.load) > 1e-3) return a.load < b.load;
  if (std::abs(2 * a.left - ranks) != std::abs(2 * b.left - ranks))
    return std::abs(2 * a.left - ranks) < std::abs(2 * b.left - ranks);
  return a.preference > b.preference;
}

// The best cut along axis d, each part at least a cell per rank (load infinite when none).
// Beside the even split of the ranks, a cut may give its first part the share of the ranks
// nearest its share of the particles (rounded either way), when that loads the busier part less.
Candidate cutAlong(const CellBox& box, const std::vector<double>& planes, int d, int ranks) {
  Candidate best;
  const Vec3i extent = box.upper - box.lower;
  if (extent[d] < 2) return best;
  const long across = box.cellCount() / extent[d];
  double total = 0;
  for (double p : planes) total += p;
  // The particles' span first, then the box's extent.
  const long preference = span(planes) * 4096L + extent[d];
  if (total <= 0) {
    // No particles: the middle, the ranks halved, if each half has a cell per rank.
    const int left = ranks / 2;
    const int cut =
        std::max(1, static_cast<int>(std::lround(static_cast<double>(extent[d]) * left / ranks)));
    if (cut * across >= left && (extent[d] - cut) * across >= ranks - left)
      best = {cut, left, 1.0, preference};
    return best;
  }
  double below = 0;
  for (int k = 1; k < extent[d]; ++k) {
    below += planes[k - 1];
    const RankShares shares =
        sharesOfRanks(below, total, ranks, k * across, (extent[d] - k) * across, false);
    for (int i = 0; i < shares.count; ++i) {
      const int left = shares.left[i];
      const double load =
          std::max(below / left, (total - below) / (ranks - left)) / (total / ranks);
      const Candidate c{k, left, load, preference};
      if (better(c, best, ranks)) best = c;
    }
  }
  return best;
}

}  // namespace

RankShares sharesOfRanks(double below, double total, int ranks, long cellsBelow, long cellsAbove,
                         bool further) {
  const double share = below / total * ranks;
  const int down = static_cast<int>(std::floor(share)), up = static_cast<int>(std::ceil(share));
  int tried[5] = {ranks / 2, down, up, down - 1, up + 1};
  const int candidates = further ? 5 : 3;
  std::sort(tried, tried + candidates);
  RankShares out;
  for (int t = 0; t < candidates; ++t) {
    const int left = tried[t];
    if ((t > 0 && left == tried[t - 1]) || left < 1 || left >= ranks) continue;
    if (cellsBelow < left || cellsAbove < ranks - left) continue;
    out.left[out.count++] = left;
  }
  return out;
}

BisectionCut bisectionCut(const CellBox& box, const std::array<std::vector<double>, 3>& planes,
                          int ranks) {
  BisectionCut chosen;
  Candidate best;
  for (int d = 0; d < 3; ++d) {
    const Candidate c = cutAlong(box, planes[d], d, ranks);
    if (std::isinf(c.load)) continue;
    if (chosen.axis < 0 || better(c, best, ranks)) {
      best = c;
      chosen = {d, box.lower[d] + c.cut, c.left};
    }
  }
  if (chosen.axis < 0)
    throw std::runtime_error("recursive bisection: a box of " + std::to_string(box.cellCount()) +
                             " cells cannot hold " + std::to_string(ranks) + " ranks");
  return chosen;
}

std::vector<std::array<std::vector<double>, 3>> planesOfBoxes(const Vec3i& cells,
                                                              const std::vector<double>& perCell,
                                                              const std::vector<CellBox>& boxes) {
  std::vector<std::array<std::vector<double>, 3>> out;
  for (const CellBox& b : boxes) {
    std::array<std::vector<double>, 3> planes;
    for (int d = 0; d < 3; ++d) planes[d].assign(b.upper[d] - b.lower[d], 0.0);
    for (int k = b.lower.z(); k < b.upper.z(); ++k)
      for (int j = b.lower.y(); j < b.upper.y(); ++j)
        for (int i = b.lower.x(); i < b.upper.x(); ++i) {
          const double n = perCell[(static_cast<size_t>(k) * cells.y() + j) * cells.x() + i];
          planes[0][i - b.lower.x()] += n;
          planes[1][j - b.lower.y()] += n;
          planes[2][k - b.lower.z()] += n;
        }
    out.push_back(std::move(planes));
  }
  return out;
}

std::vector<double> particlesPerBox(const Vec3i& cells, const std::vector<CellBox>& boxes,
                                    const std::vector<double>& perCell) {
  std::vector<double> sums;
  for (const CellBox& b : boxes) {
    double sum = 0;
    for (int k = b.lower.z(); k < b.upper.z(); ++k)
      for (int j = b.lower.y(); j < b.upper.y(); ++j)
        for (int i = b.lower.x(); i < b.upper.x(); ++i)
          sum += perCell[(static_cast<size_t>(k) * cells.y() + j) * cells.x() + i];
    sums.push_back(sum);
  }
  return sums;
}

}  // namespace anode
