// The cuts of a small box of cells for its few ranks, searched (docs/parallel.md, "How the boxes
// are chosen"): where a box holds a few cells per rank, a cut at a cell plane moves many
// particles at once, and the cut that shares a level most evenly can leave its parts no even
// cut below. The search looks at the whole subtree: of the cuts near the even share, the one
// whose parts, cut in turn the same way, leave the busiest rank the fewest particles.
#pragma once

#include <map>
#include <tuple>
#include <vector>

#include "Core/Grid/Grid.h"
#include "Core/Parallel/Bisection.h"

namespace anode {

// The particles per cell of a region of the grid, summed over any box in O(1) (a prefix sum).
class RegionCounts {
 public:
  // perCell[((k - lower.z) * n.y + (j - lower.y)) * n.x + (i - lower.x)] for the region's cells
  // (n its extent); read here, not kept.
  RegionCounts(const CellBox& region, const double* perCell);
  // The particles of `box`'s cells inside the region.
  double in(const CellBox& box) const;

 private:
  CellBox region_;
  Vec3i n_ = Vec3i::Zero();
  std::vector<double> prefix_;  // (n + 1)^3: particles of the cells below each corner
};

class BisectionSearch {
 public:
  // Searches at most `budget` subtrees in all; beyond it, each box takes the most even cut whose
  // parts can be cut in turn, so the search is the same on every rank and bounded.
  explicit BisectionSearch(const RegionCounts& counts, long budget = 10'000);
  // The cut of `box` for `ranks` > 1 ranks, each part at least a cell per rank, after which the
  // busiest rank of the subtree holds the fewest particles. Throws std::runtime_error when it
  // finds no tree of such cuts (it finds one wherever cutting level by level does).
  BisectionCut cut(const CellBox& box, int ranks);
  // The particles the busiest of `ranks` ranks holds when `box` is cut as `cut` chooses.
  double busiest(const CellBox& box, int ranks) { return best(box, ranks).busiest; }

 private:
  struct Choice {
    double busiest = 0;
    BisectionCut cut;
  };
  Choice best(const CellBox& box, int ranks);

  const RegionCounts& counts_;
  long budget_;
  std::map<std::tuple<int, int, int, int, int, int, int>, Choice> known_;
};

}  // namespace anode
