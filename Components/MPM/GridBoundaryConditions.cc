#include "Components/MPM/GridBoundaryConditions.h"

namespace anode {

void applySymmetry(const Grid& g, const std::vector<FaceBC>& bcs, int matl, const NodeBox& nodes,
                   std::vector<Vec3>& field) {
  for (const FaceBC& bc : bcs)
    if (bc.kind == FaceBC::Kind::Symmetric && bc.appliesTo(matl))
      forFaceNodesWithin(g, bc, nodes.first, nodes.last, [&](int n) { field[n][bc.axis] = 0.0; });
}

void applyVelocityDirichlet(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                            std::vector<Vec3>& field) {
  for (const FaceBC& bc : bcs)
    if (bc.kind == FaceBC::Kind::VelocityDirichlet && bc.appliesTo(matl))
      forFaceNodes(g, bc, [&](int n) { field[n] = bc.velocity; });
}

}  // namespace anode
