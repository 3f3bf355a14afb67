#include "Core/Parallel/Bisection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace anode {

namespace {

struct Cells {
  const Vec3i& n;
  const std::vector<double>& count;
  double at(int i, int j, int k) const {
    return count[(static_cast<size_t>(k) * n.y() + j) * n.x() + i];
  }
};

// Particles per cell plane of `box` along axis d.
std::vector<double> planesOf(const Cells& c, const CellBox& box, int d) {
  std::vector<double> planes(box.upper[d] - box.lower[d], 0.0);
  for (int k = box.lower.z(); k < box.upper.z(); ++k)
    for (int j = box.lower.y(); j < box.upper.y(); ++j)
      for (int i = box.lower.x(); i < box.upper.x(); ++i)
        planes[Vec3i(i, j, k)[d] - box.lower[d]] += c.at(i, j, k);
  return planes;
}

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

// A cut of `box` along one axis after `cut` planes, and how far its left part's particles are
// from the share of its ranks.
struct Cut {
  int axis = -1, cut = 0;
  double gap = INFINITY;
  long span = 0;
};

// The best cut along axis d leaving each half a cell per rank (gap infinite when none can).
Cut cutAlong(const Cells& c, const CellBox& box, int d, int left, int ranks) {
  Cut best;
  const Vec3i extent = box.upper - box.lower;
  if (extent[d] < 2) return best;
  const long across = box.cellCount() / extent[d];
  // Each half needs at least as many cells as ranks: its planes times the cells across.
  const int minLeft = static_cast<int>((left + across - 1) / across);
  const int minRight = static_cast<int>((ranks - left + across - 1) / across);
  if (minLeft + minRight > extent[d]) return best;
  const std::vector<double> planes = planesOf(c, box, d);
  double total = 0;
  for (double p : planes) total += p;
  const double target = total * left / ranks;
  best.axis = d;
  best.span = span(planes) * 4096L + extent[d];
  best.cut =
      std::clamp(static_cast<int>(std::lround(static_cast<double>(extent[d]) * left / ranks)),
                 minLeft, extent[d] - minRight);
  if (total <= 0) {
    best.gap = 0;
    return best;
  }
  double sum = 0;
  for (int k = 1; k < extent[d]; ++k) {
    sum += planes[k - 1];
    if (k < minLeft || k > extent[d] - minRight) continue;
    const double gap = std::abs(sum - target) / total;
    if (gap < best.gap) best.gap = gap, best.cut = k;
  }
  return best;
}

void bisect(const Cells& c, const CellBox& box, int ranks, int first, std::vector<CellBox>& out) {
  if (ranks == 1) {
    out[first] = box;
    return;
  }
  const int left = ranks / 2, right = ranks - left;
  // Of the axes that can take a cut, the one whose best cut shares the particles most nearly as
  // the ranks are shared (within 1e-3 of the total: the one the particles span most, then the
  // box's longest).
  Cut best;
  for (int d = 0; d < 3; ++d) {
    const Cut cut = cutAlong(c, box, d, left, ranks);
    if (cut.axis < 0) continue;
    if (best.axis < 0 || cut.gap < best.gap - 1e-3 ||
        (std::abs(cut.gap - best.gap) <= 1e-3 && cut.span > best.span))
      best = cut;
  }
  if (best.axis < 0)
    throw std::runtime_error("recursive bisection: a box of " + std::to_string(box.cellCount()) +
                             " cells cannot hold " + std::to_string(ranks) + " ranks");
  CellBox low = box, high = box;
  low.upper[best.axis] = high.lower[best.axis] = box.lower[best.axis] + best.cut;
  bisect(c, low, left, first, out);
  bisect(c, high, right, first + left, out);
}

}  // namespace

std::vector<CellBox> bisectCells(const Vec3i& cells, int ranks,
                                 const std::vector<double>& perCell) {
  std::vector<CellBox> boxes(ranks);
  bisect(Cells{cells, perCell}, CellBox{Vec3i::Zero(), cells}, ranks, 0, boxes);
  return boxes;
}

std::vector<double> particlesPerBox(const Vec3i& cells, const std::vector<CellBox>& boxes,
                                    const std::vector<double>& perCell) {
  const Cells c{cells, perCell};
  std::vector<double> sums;
  for (const CellBox& b : boxes) {
    double sum = 0;
    for (int k = b.lower.z(); k < b.upper.z(); ++k)
      for (int j = b.lower.y(); j < b.upper.y(); ++j)
        for (int i = b.lower.x(); i < b.upper.x(); ++i) sum += c.at(i, j, k);
    sums.push_back(sum);
  }
  return sums;
}

}  // namespace anode
