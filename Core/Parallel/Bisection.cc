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

// A cut after `cut` planes along an axis, how far its first part's particles are from the share
// of its ranks (relative to the box's), and the axis' preference when two share alike.
struct Candidate {
  int cut = 0;
  double gap = INFINITY;
  long preference = 0;
};

// The best cut along axis d leaving each part a cell per rank (gap infinite when none can).
Candidate cutAlong(const CellBox& box, const std::vector<double>& planes, int d, int left,
                   int ranks) {
  Candidate best;
  const Vec3i extent = box.upper - box.lower;
  if (extent[d] < 2) return best;
  const long across = box.cellCount() / extent[d];
  // Each part needs at least as many cells as ranks: its planes times the cells across.
  const int minLeft = static_cast<int>((left + across - 1) / across);
  const int minRight = static_cast<int>((ranks - left + across - 1) / across);
  if (minLeft + minRight > extent[d]) return best;
  double total = 0;
  for (double p : planes) total += p;
  // The particles' span first, then the box's extent.
  best.preference = span(planes) * 4096L + extent[d];
  best.cut =
      std::clamp(static_cast<int>(std::lround(static_cast<double>(extent[d]) * left / ranks)),
                 minLeft, extent[d] - minRight);
  if (total <= 0) {
    best.gap = 0;
    return best;
  }
  const double target = total * left / ranks;
  double sum = 0;
  for (int k = 1; k < extent[d]; ++k) {
    sum += planes[k - 1];
    if (k < minLeft || k > extent[d] - minRight) continue;
    const double gap = std::abs(sum - target) / total;
    if (gap < best.gap) best.gap = gap, best.cut = k;
  }
  return best;
}

}  // namespace

BisectionCut bisectionCut(const CellBox& box, const std::array<std::vector<double>, 3>& planes,
                          int left, int ranks) {
  // Of the axes that can take a cut, the one whose best cut shares the particles most nearly as
  // the ranks (gaps within 1e-3 of the box's particles alike: the preferred axis).
  BisectionCut chosen;
  Candidate best;
  for (int d = 0; d < 3; ++d) {
    const Candidate c = cutAlong(box, planes[d], d, left, ranks);
    if (std::isinf(c.gap)) continue;
    if (chosen.axis < 0 || c.gap < best.gap - 1e-3 ||
        (std::abs(c.gap - best.gap) <= 1e-3 && c.preference > best.preference)) {
      best = c;
      chosen = {d, box.lower[d] + c.cut};
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
