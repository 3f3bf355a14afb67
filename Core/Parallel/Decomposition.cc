#include "Core/Parallel/Decomposition.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "Core/Parallel/Bisection.h"
#include "Core/Parallel/BisectionSearch.h"

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

// Per box of a level, its particles per cell plane along each axis (planes[b][d][i]: plane
// box.lower[d] + i), summed over the ranks.
std::vector<std::array<std::vector<double>, 3>> planesOfLevel(
    const std::vector<CellBox>& boxes, const std::function<int(const Vec3i&)>& partOf,
    const Decomposition::ParticleCounts& counts) {
  std::vector<std::array<std::vector<double>, 3>> planes(boxes.size());
  for (size_t b = 0; b < boxes.size(); ++b)
    for (int d = 0; d < 3; ++d) planes[b][d].assign(boxes[b].upper[d] - boxes[b].lower[d], 0.0);
  counts.forEach([&](const Vec3i& cell, double n) {
    const int b = partOf(cell);
    if (b >= 0)
      for (int d = 0; d < 3; ++d) planes[b][d][cell[d] - boxes[b].lower[d]] += n;
  });
  if (counts.sumOverRanks) {
    std::vector<double> flat;
    for (const auto& box : planes)
      for (const std::vector<double>& axis : box) flat.insert(flat.end(), axis.begin(), axis.end());
    counts.sumOverRanks(flat);
    size_t k = 0;
    for (auto& box : planes)
      for (std::vector<double>& axis : box)
        for (double& v : axis) v = flat[k++];
  }
  return planes;
}

// The cells of `box` between its first and last cell plane holding particles along each axis
// (none when it holds none).
CellBox occupiedRegion(const CellBox& box, const std::array<std::vector<double>, 3>& planes) {
  if (std::none_of(planes[0].begin(), planes[0].end(), [](double n) { return n > 0; }))
    return CellBox{};
  CellBox region = box;
  for (int d = 0; d < 3; ++d) {
    const auto [first, last] = occupiedPlanes(planes[d]);
    region.lower[d] = box.lower[d] + first;
    region.upper[d] = box.lower[d] + last + 1;
  }
  return region;
}

// The particles per cell of each region (regions[b] lies in the box partOf names b), summed
// over the ranks, one after another in RegionCounts' order: region b's from offset[b].
std::vector<double> cellsOfRegions(const std::vector<CellBox>& regions,
                                   const std::function<int(const Vec3i&)>& partOf,
                                   const Decomposition::ParticleCounts& counts,
                                   std::vector<size_t>& offset) {
  offset.assign(regions.size() + 1, 0);
  for (size_t b = 0; b < regions.size(); ++b)
    offset[b + 1] = offset[b] + static_cast<size_t>(regions[b].cellCount());
  if (offset.back() == 0) return {};
  std::vector<double> flat(offset.back(), 0.0);
  counts.forEach([&](const Vec3i& cell, double n) {
    const int b = partOf(cell);
    if (b < 0 || !regions[b].contains(cell)) return;
    const Vec3i e = regions[b].upper - regions[b].lower, c = cell - regions[b].lower;
    flat[offset[b] + (static_cast<size_t>(c.z()) * e.y() + c.y()) * e.x() + c.x()] += n;
  });
  if (counts.sumOverRanks) counts.sumOverRanks(flat);
  return flat;
}

}  // namespace

Decomposition::Decomposition(const Vec3i& cells) : cells_(cells) {
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
  Decomposition out(Vec3i(cuts[0].back(), cuts[1].back(), cuts[2].back()));
  out.cuts_ = cuts;
  for (int d = 0; d < 3; ++d) out.ranksPerAxis_[d] = static_cast<int>(cuts[d].size()) - 1;
  return out;
}

Decomposition Decomposition::bisected(const Vec3i& cells, int ranks, const ParticleCounts& counts) {
  Decomposition out(cells);
  if (ranks == 1) return out;
  out.boxes_.assign(ranks, CellBox{});
  // The parts of a level: a box, its ranks [first, first + ranks), and where the tree points
  // to it (the cut above and which side; -1 for the root).
  struct Part {
    CellBox box;
    int ranks, first, parent, side;
  };
  const auto link = [&out](const Part& p, int child) {
    if (p.parent >= 0) (p.side == 0 ? out.tree_[p.parent].low : out.tree_[p.parent].high) = child;
  };
  const auto addLeaf = [&](const Part& p) {
    out.boxes_[p.first] = p.box;
    link(p, -p.first - 1);
  };
  // The cut of a part as a node of the tree below its parent; the two parts it makes.
  const auto addCut = [&](const Part& p, const BisectionCut& cut) {
    const int node = static_cast<int>(out.tree_.size());
    out.tree_.push_back({cut.axis, cut.at, 0, 0});
    link(p, node);
    CellBox low = p.box, high = p.box;
    low.upper[cut.axis] = high.lower[cut.axis] = cut.at;
    return std::array<Part, 2>{Part{low, cut.left, p.first, node, 0},
                               Part{high, p.ranks - cut.left, p.first + cut.left, node, 1}};
  };
  // A part's whole subtree as `search` cuts it.
  const std::function<void(const Part&, BisectionSearch&)> addSearched =
      [&](const Part& p, BisectionSearch& search) {
        if (p.ranks == 1) return addLeaf(p);
        for (const Part& half : addCut(p, search.cut(p.box, p.ranks))) addSearched(half, search);
      };
  std::vector<Part> level{{CellBox{Vec3i::Zero(), cells}, ranks, 0, -1, 0}};
  // While a level is cut, a child below -ranks points to the part -child - ranks - 1 of the
  // level's parts to cut.
  const auto pending = [ranks](int k) { return -ranks - 1 - k; };
  while (!level.empty()) {
    std::vector<CellBox> toCut;
    std::vector<Part> parts;
    for (Part& p : level) {
      if (p.ranks == 1) {
        addLeaf(p);
        continue;
      }
      link(p, pending(static_cast<int>(toCut.size())));
      toCut.push_back(p.box);
      parts.push_back(p);
    }
    if (toCut.empty()) break;
    const auto partOf = [&](const Vec3i& cell) {
      if (out.tree_.empty()) return 0;
      int node = 0;
      for (;;) {
        const Cut& c = out.tree_[node];
        const int child = cell[c.axis] < c.at ? c.low : c.high;
        if (child >= 0) {
          node = child;
        } else {
          return child < -ranks ? -child - ranks - 1 : -1;
        }
      }
    };
    const std::vector<std::array<std::vector<double>, 3>> planes =
        planesOfLevel(toCut, partOf, counts);
    // The parts of few ranks and cells: the cells their particles occupy, counted.
    std::vector<CellBox> regions(toCut.size());
    std::vector<bool> search(toCut.size(), false);
    long searchedCells = 0;
    for (size_t k = 0; k < toCut.size(); ++k) {
      if (parts[k].ranks > kSearchedRanks) continue;
      const CellBox region = occupiedRegion(toCut[k], planes[k]);
      search[k] = region.cellCount() <= kSearchedCellsPerRank * parts[k].ranks &&
                  searchedCells + region.cellCount() <= kSearchedCells;
      if (!search[k]) continue;
      regions[k] = region;
      searchedCells += region.cellCount();
    }
    std::vector<size_t> offset;
    const std::vector<double> perCell = cellsOfRegions(regions, partOf, counts, offset);
    std::vector<Part> next;
    for (size_t k = 0; k < parts.size(); ++k) {
      if (search[k]) {
        const RegionCounts region(regions[k], perCell.data() + offset[k]);
        BisectionSearch searcher(region);
        addSearched(parts[k], searcher);
        continue;
      }
      for (const Part& half :
           addCut(parts[k], bisectionCut(parts[k].box, planes[k], parts[k].ranks)))
        next.push_back(half);
    }
    level.swap(next);
  }
  out.ranksPerAxis_ = Vec3i::Ones();
  return out;
}

void Decomposition::boxesFromTree() {
  boxes_.clear();
  if (tree_.empty()) return;
  std::vector<std::pair<int, CellBox>> stack{{0, CellBox{Vec3i::Zero(), cells_}}};
  while (!stack.empty()) {
    const auto [node, box] = stack.back();
    stack.pop_back();
    const Cut& c = tree_[node];
    CellBox low = box, high = box;
    low.upper[c.axis] = high.lower[c.axis] = c.at;
    for (const auto& [child, part] : {std::pair{c.low, low}, std::pair{c.high, high}}) {
      if (child >= 0) {
        stack.push_back({child, part});
        continue;
      }
      const size_t rank = static_cast<size_t>(-child - 1);
      if (boxes_.size() <= rank) boxes_.resize(rank + 1);
      boxes_[rank] = part;
    }
  }
}

void Decomposition::save(BinaryWriter& out) const {
  out.value<int32_t>(tree_.empty() ? 0 : 1);
  for (int d = 0; d < 3; ++d) out.value<int32_t>(cells_[d]);
  if (tree_.empty()) {
    for (int d = 0; d < 3; ++d) out.array(cuts_[d]);
    return;
  }
  std::vector<int> flat;
  for (const Cut& c : tree_) flat.insert(flat.end(), {c.axis, c.at, c.low, c.high});
  out.array(flat);
}

Decomposition Decomposition::load(BinaryReader& in) {
  const int bisected = in.value<int32_t>();
  Vec3i cells;
  for (int d = 0; d < 3; ++d) cells[d] = in.value<int32_t>();
  Decomposition out(cells);
  if (!bisected) {
    std::array<std::vector<int>, 3> cuts;
    for (int d = 0; d < 3; ++d) {
      in.array(cuts[d]);
      if (cuts[d].size() < 2 || cuts[d].front() != 0 || cuts[d].back() != cells[d])
        throw std::runtime_error("the checkpoint's boxes do not tile its grid");
    }
    return fromCuts(cuts);
  }
  std::vector<int> flat;
  in.array(flat);
  if (flat.empty() || flat.size() % 4 != 0)
    throw std::runtime_error("the checkpoint's boxes are not a bisection");
  const int nodes = static_cast<int>(flat.size() / 4);
  for (size_t k = 0; k < flat.size(); k += 4) {
    const Cut c{flat[k], flat[k + 1], flat[k + 2], flat[k + 3]};
    // Children after their parent (the order bisected writes), ranks one per leaf.
    const int self = static_cast<int>(k / 4);
    if (c.axis < 0 || c.axis > 2 || c.low >= nodes || c.high >= nodes ||
        (c.low >= 0 && c.low <= self) || (c.high >= 0 && c.high <= self) || c.low < -(nodes + 1) ||
        c.high < -(nodes + 1))
      throw std::runtime_error("the checkpoint's boxes are not a bisection");
    out.tree_.push_back(c);
  }
  out.boxesFromTree();
  if (static_cast<int>(out.boxes_.size()) != nodes + 1)
    throw std::runtime_error("the checkpoint's boxes are not a bisection");
  return out;
}

CellBox Decomposition::box(int rank) const {
  if (!tree_.empty()) return boxes_[rank];
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
  if (!tree_.empty()) {
    int node = 0;
    for (;;) {
      const Cut& c = tree_[node];
      const int at = std::clamp(cell[c.axis], 0, cells_[c.axis] - 1);
      const int child = at < c.at ? c.low : c.high;
      if (child < 0) return -child - 1;
      node = child;
    }
  }
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
    cell[d] = static_cast<int>(std::clamp(std::floor(xi[d]), -1.0, double(cells_[d])));
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
  if (!tree_.empty()) {
    s << ranks() << " boxes by recursive bisection:";
    for (int r = 0; r < ranks() && r < 4; ++r)
      s << (r ? ", " : " ") << "[" << boxes_[r].lower.transpose() << "]-["
        << boxes_[r].upper.transpose() << "]";
    if (ranks() > 4) s << ", ...";
    return s.str();
  }
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
