#include "Components/MPM/GridBoundaryConditions.h"

namespace anode {

namespace {

// Calls f(node) for every node on the face of `bc` or outside it.
template <class Fn>
void forFaceNodes(const Grid& g, const FaceBC& bc, Fn f) {
  Vec3i lo = -g.extra, hi = g.cells + g.extra;
  if (bc.side == 0)
    hi[bc.axis] = 0;
  else
    lo[bc.axis] = g.cells[bc.axis];
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) f(g.nodeIndex(i, j, k));
}

}  // namespace

void applySymmetry(const Grid& g, const std::vector<FaceBC>& bcs, int matl, std::vector<Vec3>& field) {
  for (const FaceBC& bc : bcs)
    if (bc.kind == FaceBC::Kind::Symmetric && bc.appliesTo(matl))
      forFaceNodes(g, bc, [&](int n) { field[n][bc.axis] = 0.0; });
}

void applyVelocityDirichlet(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                            std::vector<Vec3>& field) {
  for (const FaceBC& bc : bcs)
    if (bc.kind == FaceBC::Kind::VelocityDirichlet && bc.appliesTo(matl))
      forFaceNodes(g, bc, [&](int n) { field[n] = bc.velocity; });
}

void applyConcentrationBCs(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                           std::vector<double>& field) {
  for (const FaceBC& bc : bcs) {
    if (!bc.appliesTo(matl)) continue;
    if (bc.kind == FaceBC::Kind::ConcentrationDirichlet) {
      forFaceNodes(g, bc, [&](int n) { field[n] = bc.value; });
    } else if (bc.kind == FaceBC::Kind::ConcentrationNeumann) {
      // Outermost layer last, so each node copies an already-updated inward neighbour.
      const int inward = bc.side == 0 ? 1 : -1;
      Vec3i offset = Vec3i::Zero();
      offset[bc.axis] = inward;
      const int lo = bc.side == 0 ? 0 : g.cells[bc.axis];
      const int layers = g.extra[bc.axis] + 1;
      for (int layer = 0; layer < layers; ++layer) {
        const int plane = lo - inward * layer;
        Vec3i from = -g.extra, to = g.cells + g.extra;
        from[bc.axis] = to[bc.axis] = plane;
        for (int k = from.z(); k <= to.z(); ++k)
          for (int j = from.y(); j <= to.y(); ++j)
            for (int i = from.x(); i <= to.x(); ++i)
              field[g.nodeIndex(i, j, k)] =
                  field[g.nodeIndex(i + offset.x(), j + offset.y(), k + offset.z())] - bc.value * g.dx[bc.axis];
      }
    }
  }
}

}  // namespace anode
