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

}  // namespace anode
