// Uintah's particle placement (UINTAH_UPS.md §3.1): in every interior cell, res.x*res.y*res.z
// candidate points at X_cell + dxp*(i + 1/2), kept when inside the piece. Only the cells that
// meet the piece's bounding box are visited (the same points, in the same order).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

// Candidate points fillParticles tests: the cells it visits times res.x*res.y*res.z.
double fillCandidates(const Grid& grid, const GeometryPiece& piece, const Vec3i& res);

// Whether a candidate point of the same lattice continued beyond the interior cells lies inside
// the piece: a particle Uintah (and fillParticles) would silently drop. Beyond a face marked in
// `mirror` (index 2 axis + side, side 1 the plus face), a symmetry plane, points do not count: a
// piece crossing it is the idiom for half of a symmetric body. A piece whose bounding box meets
// more than kMaxOutsideCandidates points that count is outside without testing them.
constexpr double kMaxOutsideCandidates = 1e8;
bool placesParticlesOutside(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                            const std::array<bool, 6>& mirror);

// The points of one piece, counted cell by cell before any is stored, so that a rank can fill
// only its region of the grid and number the points as a fill of the whole grid would
// (docs/parallel.md, "Setup per box"). Holds the count of every cell in the piece's bounding
// box (4 bytes each): check fillCandidates first.
class PieceLattice {
 public:
  PieceLattice(const Grid& grid, GeometryPieceP piece, const Vec3i& res);

  // Points inside the piece, in all and in the cells of `region`.
  int64_t count() const { return total_; }
  int64_t countIn(const CellBox& region) const;
  // The points in the cells of `region` in the order of a fill of the whole grid (cells z, y, x
  // slowest to fastest, then the points of a cell likewise), with each one's place in that order.
  void fill(const CellBox& region, std::vector<Vec3>& x, std::vector<int64_t>& place) const;
  // Calls visit(cell, points) for each cell holding points.
  void forEachOccupiedCell(const std::function<void(const Vec3i&, double)>& visit) const;
  // Calls visit(x, place) for each of those points, in that order, storing none.
  void forEachPoint(const CellBox& region,
                    const std::function<void(const Vec3&, int64_t)>& visit) const;

 private:
  // The parts (of a union, or the piece) whose bounds meet the cells of row (j, k): only they
  // can hold a point there.
  using Parts = std::vector<int>;  // indices into parts_
  Parts partsMeetingRow(int j, int k) const;
  // Calls inside(x) for each candidate point of cell (i, j, k) inside the piece, in order;
  // `row`: partsMeetingRow(j, k).
  template <class Visit>
  void visitCell(int i, int j, int k, const Parts& row, Visit&& inside) const;
  size_t cellIndex(int i, int j, int k) const;

  const Grid& grid_;
  GeometryPieceP piece_;
  std::vector<std::pair<Bounds, const GeometryPiece*>> parts_;
  Vec3i res_;
  Vec3 dxp_;
  Vec3i first_, last_;              // the cells counted, inclusive (first > last: none)
  std::vector<uint32_t> perCell_;   // x fastest
  std::vector<int64_t> beforeRow_;  // points before each row (j, k) of cells
  int64_t total_ = 0;
};

}  // namespace anode
