#include "Core/Parallel/Decomposition.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace anode {

namespace {

std::vector<int> primeFactorsDescending(int n) {
  std::vector<int> f;
  for (int p = 2; p * p <= n; ++p)
    while (n % p == 0) {
      f.push_back(p);
      n /= p;
    }
  if (n > 1) f.push_back(n);
  std::sort(f.rbegin(), f.rend());
  return f;
}

// The planes [first, last] holding particles (all planes when none does).
std::pair<int, int> occupiedPlanes(const std::vector<double>& counts) {
  int first = -1, last = -1;
  for (int c = 0; c < static_cast<int>(counts.size()); ++c)
    if (counts[c] > 0) {
      if (first < 0) first = c;
      last = c;
    }
  if (first < 0) return {0, static_cast<int>(counts.size()) - 1};
  return {first, last};
}

// Cuts of `cells` planes into `boxes` pieces at the quantiles of `counts`, each at least one
// plane wide.
std::vector<int> quantileCuts(const std::vector<double>& counts, int cells, int boxes) {
  std::vector<double> prefix(cells + 1, 0.0);  // prefix[c]: particles in planes below c
  for (int c = 0; c < cells; ++c)
    prefix[c + 1] = prefix[c] + (c < static_cast<int>(counts.size()) ? counts[c] : 0.0);
  const double total = prefix[cells];
  std::vector<int> cuts(boxes + 1);
  cuts[0] = 0;
  cuts[boxes] = cells;
  for (int k = 1; k < boxes; ++k) {
    int c;
    if (total > 0) {
      const double target = total * k / boxes;
      c = static_cast<int>(std::lower_bound(prefix.begin(), prefix.end(), target) - prefix.begin());
      if (c > 0 && target - prefix[c - 1] < prefix[c] - target) --c;  // the nearer plane
    } else {
      c = static_cast<int>(static_cast<long>(cells) * k / boxes);
    }
    // At least one plane per box on either side.
    c = std::max(c, cuts[k - 1] + 1);
    c = std::min(c, cells - (boxes - k));
    cuts[k] = c;
  }
  return cuts;
}

}  // namespace

Decomposition::Decomposition(const Vec3i& cells) {
  for (int d = 0; d < 3; ++d) cuts_[d] = {0, cells[d]};
}

Decomposition Decomposition::balanced(const Vec3i& cells, int ranks,
                                      const std::array<std::vector<double>, 3>& planeCounts,
                                      const Decomposition* earlier) {
  Decomposition out(cells);
  Vec3 span;
  for (int d = 0; d < 3; ++d) {
    const auto [first, last] = occupiedPlanes(planeCounts[d]);
    span[d] = last - first + 1;
  }
  for (int p : primeFactorsDescending(ranks)) {
    int best = -1;
    for (int d = 0; d < 3; ++d) {
      if (out.ranksPerAxis_[d] * p > cells[d]) continue;
      if (best < 0 || span[d] / out.ranksPerAxis_[d] > span[best] / out.ranksPerAxis_[best])
        best = d;
    }
    if (best < 0 && earlier && earlier->ranks() == ranks) {
      out.ranksPerAxis_ = earlier->ranksPerAxis_;
      break;
    }
    if (best < 0)
      throw std::runtime_error("the grid (" + std::to_string(cells.x()) + "x" +
                               std::to_string(cells.y()) + "x" + std::to_string(cells.z()) +
                               " cells) cannot be split into " + std::to_string(ranks) +
                               " boxes of at least one cell");
    out.ranksPerAxis_[best] *= p;
  }
  for (int d = 0; d < 3; ++d)
    out.cuts_[d] = quantileCuts(planeCounts[d], cells[d], out.ranksPerAxis_[d]);
  return out;
}

Decomposition Decomposition::fromCuts(const std::array<std::vector<int>, 3>& cuts) {
  Decomposition out;
  out.cuts_ = cuts;
  for (int d = 0; d < 3; ++d) out.ranksPerAxis_[d] = static_cast<int>(cuts[d].size()) - 1;
  return out;
}

CellBox Decomposition::box(int rank) const {
  const Vec3i& n = ranksPerAxis_;
  const Vec3i k(rank % n.x(), (rank / n.x()) % n.y(), rank / (n.x() * n.y()));
  CellBox b;
  for (int d = 0; d < 3; ++d) {
    b.lower[d] = cuts_[d][k[d]];
    b.upper[d] = cuts_[d][k[d] + 1];
  }
  return b;
}

int Decomposition::ownerOfCell(const Vec3i& cell) const {
  Vec3i k;
  for (int d = 0; d < 3; ++d) {
    const std::vector<int>& c = cuts_[d];
    const int clamped = std::clamp(cell[d], 0, c.back() - 1);
    k[d] = static_cast<int>(std::upper_bound(c.begin(), c.end(), clamped) - c.begin()) - 1;
  }
  return (k.z() * ranksPerAxis_.y() + k.y()) * ranksPerAxis_.x() + k.x();
}

int Decomposition::ownerOfPoint(const Vec3& xi, int otherwise) const {
  if (!xi.allFinite()) return otherwise;
  Vec3i cell;
  for (int d = 0; d < 3; ++d)  // clamped as a double: a cast of one beyond int's range is undefined
    cell[d] = static_cast<int>(std::clamp(std::floor(xi[d]), -1.0, double(cuts_[d].back())));
  return ownerOfCell(cell);
}

Grid Decomposition::window(const Grid& whole, int rank, int ghost) const {
  const CellBox b = box(rank);
  Grid g = whole.whole();
  for (int d = 0; d < 3; ++d) {
    const int first =
        b.lower[d] == 0 ? -whole.extra[d] : std::max(b.lower[d] - ghost, -whole.extra[d]);
    const int last = b.upper[d] == whole.cells[d]
                         ? whole.cells[d] + whole.extra[d]
                         : std::min(b.upper[d] + ghost, whole.cells[d] + whole.extra[d]);
    g.trimLower[d] = first + whole.extra[d];
    g.trimUpper[d] = whole.cells[d] + whole.extra[d] - last;
  }
  return g;
}

std::vector<int> Decomposition::neighbours(const Grid& whole, int rank, int ghost) const {
  const Grid mine = window(whole, rank, ghost);
  std::vector<int> out;
  for (int r = 0; r < ranks(); ++r) {
    if (r == rank) continue;
    const Grid other = window(whole, r, ghost);
    if ((mine.firstNode().array() <= other.lastNode().array()).all() &&
        (other.firstNode().array() <= mine.lastNode().array()).all())
      out.push_back(r);
  }
  return out;
}

std::string Decomposition::describe() const {
  std::ostringstream s;
  s << ranksPerAxis_.x() << "x" << ranksPerAxis_.y() << "x" << ranksPerAxis_.z() << " boxes";
  const char* axis = "xyz";
  for (int d = 0; d < 3; ++d) {
    if (ranksPerAxis_[d] == 1) continue;
    s << ", cuts " << axis[d] << " [";
    for (size_t i = 0; i < cuts_[d].size(); ++i) s << (i ? " " : "") << cuts_[d][i];
    s << "]";
  }
  return s.str();
}

}  // namespace anode
