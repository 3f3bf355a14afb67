#include "Core/Geometry/ParticleFill.h"

namespace anode {

std::vector<Vec3> fillParticles(const Grid& grid, const GeometryPiece& piece, const Vec3i& res) {
  std::vector<Vec3> out;
  const Vec3 dxp = grid.dx.cwiseQuotient(res.cast<double>());
  for (int k = 0; k < grid.cells.z(); ++k)
    for (int j = 0; j < grid.cells.y(); ++j)
      for (int i = 0; i < grid.cells.x(); ++i) {
        const Vec3 cell = grid.nodePosition(i, j, k);
        for (int c = 0; c < res.z(); ++c)
          for (int b = 0; b < res.y(); ++b)
            for (int a = 0; a < res.x(); ++a) {
              const Vec3 x = cell + Vec3((a + 0.5) * dxp.x(), (b + 0.5) * dxp.y(), (c + 0.5) * dxp.z());
              if (piece.inside(x)) out.push_back(x);
            }
      }
  return out;
}

}  // namespace anode
