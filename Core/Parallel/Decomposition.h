// The decomposition of the grid's cells into one box per rank (DESIGN.md §5, docs/parallel.md):
// the ranks factored over the axes and, along each axis, cuts placed at the quantiles of the
// particle counts per cell plane, so that a body on a large grid is shared evenly. It knows the
// boxes and each rank's window of stored nodes (box and ghost layers); it does not talk MPI.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "Core/Grid/Grid.h"

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

  // The boxes `cuts` (per axis: the first cell of each box and, last, the cell count) draw.
  static Decomposition fromCuts(const std::array<std::vector<int>, 3>& cuts);

  int ranks() const { return ranksPerAxis_.prod(); }
  const Vec3i& ranksPerAxis() const { return ranksPerAxis_; }
  // Along axis d: the first cell of each box and, last, cells[d].
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
  // "2x1x1 boxes, cuts x [0 16 40] ..." for the setup report.
  std::string describe() const;

 private:
  Vec3i ranksPerAxis_ = Vec3i::Ones();
  std::array<std::vector<int>, 3> cuts_;
};

}  // namespace anode
