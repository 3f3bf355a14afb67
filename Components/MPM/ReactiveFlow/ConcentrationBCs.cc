#include "Components/MPM/ReactiveFlow/ConcentrationBCs.h"

namespace anode {

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
        Vec3i from = g.firstNode(), to = g.lastNode();
        // A rank's window holds a face plane and its inward neighbour, or neither.
        if (plane < from[bc.axis] || plane > to[bc.axis] || plane + inward < from[bc.axis] ||
            plane + inward > to[bc.axis])
          continue;
        from[bc.axis] = to[bc.axis] = plane;
        for (int k = from.z(); k <= to.z(); ++k)
          for (int j = from.y(); j <= to.y(); ++j)
            for (int i = from.x(); i <= to.x(); ++i)
              field[g.nodeIndex(i, j, k)] =
                  field[g.nodeIndex(i + offset.x(), j + offset.y(), k + offset.z())] -
                  bc.value * g.dx[bc.axis];
      }
    }
  }
}

std::vector<std::vector<double>> dirichletNodeMasks(const Grid& g, const std::vector<FaceBC>& bcs,
                                                    size_t materials) {
  std::vector<FaceBC> dirichlet;
  for (FaceBC b : bcs)
    if (b.kind == FaceBC::Kind::ConcentrationDirichlet) {
      b.value = 1.0;
      dirichlet.push_back(b);
    }
  if (dirichlet.empty()) return {};
  std::vector<std::vector<double>> masks(materials, std::vector<double>(g.numNodes(), 0.0));
  for (size_t m = 0; m < materials; ++m)
    applyConcentrationBCs(g, dirichlet, static_cast<int>(m), masks[m]);
  return masks;
}

}  // namespace anode
