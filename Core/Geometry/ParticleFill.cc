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

std::vector<Vec3> fillParticles(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                                size_t maxParticles) {
  std::vector<Vec3> out;
  Vec3i first, last;
  cellRange(grid, piece, first, last);
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  for (int k = first.z(); k <= last.z(); ++k)
    for (int j = first.y(); j <= last.y(); ++j)
      for (int i = first.x(); i <= last.x(); ++i) {
        const Vec3 cell = grid.nodePosition(i, j, k);
        for (int c = 0; c < res.z(); ++c)
          for (int b = 0; b < res.y(); ++b)
            for (int a = 0; a < res.x(); ++a) {
              const Vec3 x =
                  cell + Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z());
              if (!piece.inside(x)) continue;
              out.push_back(x);
              if (out.size() > maxParticles) return out;
            }
      }
  return out;
}

}  // namespace anode
