// The decomposition of the grid's cells into one box per rank (DESIGN.md §5, docs/parallel.md):
// the ranks factored over the axes and, along each axis, cuts placed at the quantiles of the
// particle counts per cell plane, so that a body on a large grid is shared evenly. It knows the
// boxes and each rank's window of stored nodes (box and ghost layers); it does not talk MPI.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "Core/Grid/Grid.h"
#include "Core/Util/BinaryStream.h"

namespace anode {

class Decomposition {
 public:
  // One box holding the whole grid.
  explicit Decomposition(const Vec3i& cells = Vec3i::Ones());
  // `ranks` boxes over `cells`. The rank count is factored into primes and the larger factors go
  // to the axes the particles span most cells of (per rank), only to axes with a cell per box;
  // along each axis the cuts sit at the quantiles of planeCounts[d] (particles per cell plane,
  // cells[d] of them), every box at least one cell wide. When the factors fit no axis that way,
  // the boxes per axis of `earlier` (the boxes drawn before, which fit: boxes redrawn mid-run
  // never fail where setup succeeded); without it, throws std::runtime_error (the grid has too
  // few cells for that many boxes).
  static Decomposition balanced(const Vec3i& cells, int ranks,
                                const std::array<std::vector<double>, 3>& planeCounts,
                                const Decomposition* earlier = nullptr);

  // The particles per cell the boxes are drawn from: `forEach(add)` calls add(cell, particles)
  // for the cells this rank counts; `sumOverRanks` sums a vector over the ranks in place, the
  // same on every rank (null when every rank counts every particle): a collective its maker
  // binds to its own Collective tag, so that bisected is collective only with it.
  struct ParticleCounts {
    std::function<void(const std::function<void(const Vec3i&, double)>&)> forEach;
    std::function<void(std::vector<double>&)> sumOverRanks;
  };
  // Parts of at most kSearchedRanks ranks whose particles lie within kSearchedCellsPerRank cells
  // per rank are cut by BisectionSearch, their subtree searched whole (where a rank holds more
  // cells, a cell plane moves few of its particles), as long as the searched parts of a level
  // hold at most kSearchedCells cells: every rank counts them all while it draws the boxes
  // (8 bytes a cell, and 8 more for the part being searched).
  static constexpr int kSearchedRanks = 16;
  static constexpr long kSearchedCellsPerRank = 4096;
  static constexpr long kSearchedCells = 1L << 22;
  // `ranks` boxes by recursive coordinate bisection (Core/Parallel/Bisection.h): the grid and
  // its ranks cut in two, each half again, level by level, from the counts per cell plane of
  // each level's boxes (one pass over `counts` and one sum per level); a part of few ranks and
  // cells (above) is cut as BisectionSearch finds from its particles per cell (one more pass and
  // sum). Throws std::runtime_error when a box cannot be cut for its ranks.
  static Decomposition bisected(const Vec3i& cells, int ranks, const ParticleCounts& counts);

  // The boxes `cuts` (per axis: the first cell of each box and, last, the cell count) draw.
  static Decomposition fromCuts(const std::array<std::vector<int>, 3>& cuts);
  // For a checkpoint: the boxes, as save writes them and load reads them back.
  void save(BinaryWriter& out) const;
  static Decomposition load(BinaryReader& in);

  int ranks() const {
    return tree_.empty() ? ranksPerAxis_.prod() : static_cast<int>(boxes_.size());
  }
  const Vec3i& cells() const { return cells_; }
  // Tensor-product boxes: per axis (`cuts` along axis d: the first cell of each box and, last,
  // cells[d]); of bisected ones, 1 1 1 and the grid's.
  const Vec3i& ranksPerAxis() const { return ranksPerAxis_; }
  const std::vector<int>& cuts(int d) const { return cuts_[d]; }
  CellBox box(int rank) const;
  // The rank owning a cell; a cell outside the interior counts as the nearest interior one.
  int ownerOfCell(const Vec3i& cell) const;
  // The rank owning the cell holding the point at index coordinate xi (Grid::indexCoordinate),
  // any distance outside the grid counting as the nearest cell; `otherwise` for a point that is
  // not finite (a NaN position stays where the state checks find it, as on one rank).
  int ownerOfPoint(const Vec3& xi, int otherwise) const;
  // The grid as rank `rank` stores it: its box, `ghost` node layers around it and, on the
  // grid's faces, the extra nodes.
  Grid window(const Grid& whole, int rank, int ghost) const;
  // The ranks whose windows share nodes with rank `rank`'s, in rank order, itself excluded.
  std::vector<int> neighbours(const Grid& whole, int rank, int ghost) const;
  // "2x1x1 boxes, cuts x [0 16 40] ..." or "4 boxes by recursive bisection: [0 0 0]-[12 40 45],
  // ..." for the setup report.
  std::string describe() const;

 private:
  // A cut of a bisected decomposition: cells with index below `at` along `axis` go to `low`, the
  // others to `high`; a child >= 0 is a node, below 0 the box of rank -child - 1.
  struct Cut {
    int axis = 0, at = 0, low = 0, high = 0;
  };
  // The boxes the tree's leaves hold, walked from the whole grid.
  void boxesFromTree();

  Vec3i cells_ = Vec3i::Ones();
  Vec3i ranksPerAxis_ = Vec3i::Ones();
  std::array<std::vector<int>, 3> cuts_;
  std::vector<Cut> tree_;       // bisected: its cuts, tree_[0] the root; empty: tensor product
  std::vector<CellBox> boxes_;  // bisected: per rank
};

}  // namespace anode
