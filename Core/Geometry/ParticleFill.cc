#include "Core/Geometry/ParticleFill.h"

#include <algorithm>
#include <cmath>

namespace anode {

namespace {

// Interior cells [first, last] per axis that can hold a point of the piece (one cell of margin
// for round-off); first > last when none can.
void cellRange(const Grid& grid, const GeometryPiece& piece, Vec3i& first, Vec3i& last) {
  const Bounds b = piece.bounds();
  for (int d = 0; d < 3; ++d) {
    const double lo = std::floor((b.lo[d] - grid.lower[d]) / grid.dx[d]) - 1;
    const double hi = std::floor((b.hi[d] - grid.lower[d]) / grid.dx[d]) + 1;
    // Clamped in floating point first: a far or unbounded piece must not overflow an int.
    first[d] = static_cast<int>(std::clamp(lo, 0.0, static_cast<double>(grid.cells[d])));
    last[d] = static_cast<int>(std::clamp(hi, -1.0, static_cast<double>(grid.cells[d] - 1)));
    if (!(b.lo[d] <= b.hi[d])) last[d] = first[d] - 1;
  }
}

}  // namespace

double fillCandidates(const Grid& grid, const GeometryPiece& piece, const Vec3i& res) {
  Vec3i first, last;
  cellRange(grid, piece, first, last);
  double n = res.cast<double>().prod();
  for (int d = 0; d < 3; ++d) n *= std::max(0, last[d] - first[d] + 1);
  return n;
}

bool placesParticlesOutside(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                            const std::array<bool, 6>& mirror) {
  // Cell indices allowed per axis, [allowedLo, allowedHi); the cells of the bounding box (with
  // fillParticles' margin), unclamped, in floating point: a far or unbounded piece must not
  // overflow an integer.
  const Bounds box = piece.bounds();
  Vec3 allowedLo, allowedHi, first, count;
  double all = res.cast<double>().prod(), allowed = all;
  for (int d = 0; d < 3; ++d) {
    if (!(box.lo[d] <= box.hi[d])) return false;
    allowedLo[d] = mirror[2 * d] ? -HUGE_VAL : 0.0;
    allowedHi[d] = mirror[2 * d + 1] ? HUGE_VAL : static_cast<double>(grid.cells[d]);
    first[d] = std::floor((box.lo[d] - grid.lower[d]) / grid.dx[d]) - 1;
    count[d] = std::floor((box.hi[d] - grid.lower[d]) / grid.dx[d]) + 2 - first[d];
    all *= count[d];
    allowed *= std::max(
        0.0, std::min(first[d] + count[d], allowedHi[d]) - std::max(first[d], allowedLo[d]));
  }
  const double outside = all - allowed;
  if (outside == 0) return false;
  if (!(outside <= kMaxOutsideCandidates)) return true;
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  // Per axis, the box's allowed cells as offsets [lo, hi) within [0, count).
  Vec3 lo, hi;
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::clamp(allowedLo[d] - first[d], 0.0, count[d]);
    hi[d] = std::clamp(allowedHi[d] - first[d], 0.0, count[d]);
  }
  const bool xOutside = lo.x() > 0 || hi.x() < count.x();
  const bool yOutside = lo.y() > 0 || hi.y() < count.y();
  const auto placesInside = [&](long i, long j, long k) {
    const Vec3 cell = grid.lower + (first + Vec3(i, j, k)).cwiseProduct(grid.dx);
    for (int c = 0; c < res.z(); ++c)
      for (int b = 0; b < res.y(); ++b)
        for (int a = 0; a < res.x(); ++a)
          if (piece.inside(cell +
                           Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z())))
            return true;
    return false;
  };
  // Only the rows of cells (j, k) with a cell outside are visited, and in them only those cells,
  // so the work is bounded by `outside` however far the box reaches.
  const auto rowPlacesOutside = [&](long j, long k, bool rowAllowed) {
    for (long i = 0; i < static_cast<long>(count.x()); ++i) {
      if (rowAllowed && i == static_cast<long>(lo.x())) i = static_cast<long>(hi.x());
      if (i < static_cast<long>(count.x()) && placesInside(i, j, k)) return true;
    }
    return false;
  };
  for (long k = 0; k < static_cast<long>(count.z()); ++k) {
    const bool kAllowed = k >= static_cast<long>(lo.z()) && k < static_cast<long>(hi.z());
    if (kAllowed && !xOutside && !yOutside) {
      k = static_cast<long>(hi.z()) - 1;
      continue;
    }
    for (long j = 0; j < static_cast<long>(count.y()); ++j) {
      const bool rowAllowed =
          kAllowed && j >= static_cast<long>(lo.y()) && j < static_cast<long>(hi.y());
      if (rowAllowed && !xOutside) {
        j = static_cast<long>(hi.y()) - 1;
        continue;
      }
      if (rowPlacesOutside(j, k, rowAllowed)) return true;
    }
  }
  return false;
}

PieceLattice::PieceLattice(const Grid& grid, GeometryPieceP piece, const Vec3i& res)
    : grid_(grid),
      piece_(std::move(piece)),
      res_(res),
      dxp_(grid.dx.cwiseQuotient(res.cast<double>())) {
  // A union (a geom_object's pieces, an array's pillars) is tested part by part, each only in
  // the cells its bounds meet: the same points, found without testing every part everywhere.
  if (const auto* u = dynamic_cast<const UnionPiece*>(piece_.get()))
    for (const GeometryPieceP& part : u->pieces) parts_.emplace_back(part->bounds(), part.get());
  else
    parts_.emplace_back(piece_->bounds(), piece_.get());
  cellRange(grid, *piece_, first_, last_);
  const Vec3i n = (last_ - first_ + Vec3i::Ones()).cwiseMax(0);
  perCell_.assign(static_cast<size_t>(n.cast<long>().prod()), 0);
  beforeRow_.assign(static_cast<size_t>(n.y()) * n.z() + 1, 0);
  const long rows = static_cast<long>(n.y()) * n.z();
#pragma omp parallel for schedule(dynamic, 16)
  for (long row = 0; row < rows; ++row) {
    const int j = first_.y() + static_cast<int>(row % n.y());
    const int k = first_.z() + static_cast<int>(row / n.y());
    const Parts parts = partsMeetingRow(j, k);
    for (int i = first_.x(); i <= last_.x(); ++i)
      visitCell(i, j, k, parts, [&](const Vec3&) { ++perCell_[cellIndex(i, j, k)]; });
  }
  for (long row = 0; row < rows; ++row) {
    int64_t inRow = 0;
    for (int i = 0; i < n.x(); ++i) inRow += perCell_[static_cast<size_t>(row) * n.x() + i];
    beforeRow_[row + 1] = beforeRow_[row] + inRow;
  }
  total_ = beforeRow_.back();
}

PieceLattice::Parts PieceLattice::partsMeetingRow(int j, int k) const {
  const Vec3 lo = grid_.nodePosition(0, j, k), hi = grid_.nodePosition(0, j + 1, k + 1);
  Parts parts;
  for (size_t p = 0; p < parts_.size(); ++p) {
    const Bounds& b = parts_[p].first;
    if (b.lo.y() <= hi.y() && b.hi.y() >= lo.y() && b.lo.z() <= hi.z() && b.hi.z() >= lo.z())
      parts.push_back(static_cast<int>(p));
  }
  return parts;
}

template <class Visit>
void PieceLattice::visitCell(int i, int j, int k, const Parts& row, Visit&& inside) const {
  const Vec3 cell = grid_.nodePosition(i, j, k);
  const double hi = grid_.nodePosition(i + 1, j, k).x();
  const GeometryPiece* parts[64];
  size_t count = 0;
  bool many = false;
  for (int p : row) {
    const Bounds& b = parts_[p].first;
    if (b.lo.x() <= hi && b.hi.x() >= cell.x()) {
      if (count == 64) {
        many = true;
        break;
      }
      parts[count++] = parts_[p].second;
    }
  }
  if (count == 0) return;
  // Beyond 64 parts in one cell, the piece itself (the same test, in one call).
  const auto holds = [&](const Vec3& x) {
    return many ? piece_->inside(x)
                : std::any_of(parts, parts + count,
                              [&](const GeometryPiece* part) { return part->inside(x); });
  };
  for (int c = 0; c < res_.z(); ++c)
    for (int b = 0; b < res_.y(); ++b)
      for (int a = 0; a < res_.x(); ++a) {
        const Vec3 x =
            cell + Vec3((a + 0.5) * dxp_.x(), (b + 0.5) * dxp_.y(), (c + 0.5) * dxp_.z());
        if (holds(x)) inside(x);
      }
}

size_t PieceLattice::cellIndex(int i, int j, int k) const {
  const Vec3i n = last_ - first_ + Vec3i::Ones();
  return (static_cast<size_t>(k - first_.z()) * n.y() + (j - first_.y())) * n.x() +
         (i - first_.x());
}

int64_t PieceLattice::countIn(const CellBox& region) const {
  int64_t n = 0;
  const Vec3i lo = region.lower.cwiseMax(first_), hi = region.upper.cwiseMin(last_ + Vec3i::Ones());
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i) n += perCell_[cellIndex(i, j, k)];
  return n;
}

void PieceLattice::fill(const CellBox& region, std::vector<Vec3>& x,
                        std::vector<int64_t>& place) const {
  const size_t n = static_cast<size_t>(countIn(region));
  x.reserve(x.size() + n);
  place.reserve(place.size() + n);
  forEachPoint(region, [&](const Vec3& point, int64_t at) {
    x.push_back(point);
    place.push_back(at);
  });
}

void PieceLattice::forEachOccupiedCell(
    const std::function<void(const Vec3i&, double)>& visit) const {
  for (int k = first_.z(); k <= last_.z(); ++k)
    for (int j = first_.y(); j <= last_.y(); ++j)
      for (int i = first_.x(); i <= last_.x(); ++i)
        if (const uint32_t n = perCell_[cellIndex(i, j, k)]; n > 0) visit(Vec3i(i, j, k), n);
}

void PieceLattice::forEachPoint(const CellBox& region,
                                const std::function<void(const Vec3&, int64_t)>& visit) const {
  const Vec3i lo = region.lower.cwiseMax(first_), hi = region.upper.cwiseMin(last_ + Vec3i::Ones());
  // A region beside the lattice in x has none of its points (and the count of the cells before
  // it would run past the row).
  if (lo.x() >= hi.x()) return;
  const size_t rowLength = static_cast<size_t>(last_.x() - first_.x() + 1);
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j) {
      const Parts parts = partsMeetingRow(j, k);
      // The points before this row's first cell in the region: the rows before and the cells
      // of this row before it.
      const size_t row =
          static_cast<size_t>(k - first_.z()) * (last_.y() - first_.y() + 1) + (j - first_.y());
      int64_t next = beforeRow_[row];
      for (int i = first_.x(); i < lo.x(); ++i)
        next += perCell_[row * rowLength + (i - first_.x())];
      for (int i = lo.x(); i < hi.x(); ++i)
        visitCell(i, j, k, parts, [&](const Vec3& point) { visit(point, next++); });
    }
}

}  // namespace anode
