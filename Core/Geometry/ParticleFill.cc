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

std::vector<Vec3> fillParticles(const Grid& grid, const GeometryPiece& piece, const Vec3i& res, size_t maxParticles) {
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
              const Vec3 x = cell + Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z());
              if (!piece.inside(x)) continue;
              out.push_back(x);
              if (out.size() > maxParticles) return out;
            }
      }
  return out;
}

}  // namespace anode
