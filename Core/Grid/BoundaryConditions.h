// Grid-face boundary conditions of <Grid><BoundaryConditions> (UINTAH_UPS.md §2.10).
#pragma once

#include <algorithm>
#include <optional>
#include <vector>

#include "Core/Grid/Grid.h"
#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct FaceBC {
  int axis = 0;       // 0, 1, 2 for x, y, z
  int side = 0;       // 0 for the minus face, 1 for the plus face
  int material = -1;  // -1 for id="all"
  enum class Kind { Symmetric, VelocityDirichlet, ConcentrationDirichlet, ConcentrationNeumann };
  Kind kind = Kind::Symmetric;
  Vec3 velocity = Vec3::Zero();  // VelocityDirichlet
  double value = 0;              // SD-Type: concentration (Dirichlet) or gradient (Neumann)

  bool appliesTo(int matl) const { return material < 0 || material == matl; }
};

// Calls f(node) for every stored node on the face of `bc` or outside it (the extra nodes beyond)
// that lies within grid indices [first, last].
template <class Fn>
void forFaceNodesWithin(const Grid& g, const FaceBC& bc, const Vec3i& first, const Vec3i& last,
                        Fn f) {
  Vec3i lo = g.firstNode().cwiseMax(first), hi = g.lastNode().cwiseMin(last);
  if (bc.side == 0)
    hi[bc.axis] = std::min(hi[bc.axis], 0);
  else
    lo[bc.axis] = std::max(lo[bc.axis], g.cells[bc.axis]);
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) f(g.nodeIndex(i, j, k));
}

// The same on every stored node of the face.
template <class Fn>
void forFaceNodes(const Grid& g, const FaceBC& bc, Fn f) {
  forFaceNodesWithin(g, bc, g.firstNode(), g.lastNode(), f);
}

// Reads every <Face>; `numMaterials` bounds the id attribute; SD-Type (concentration) conditions
// need `diffusion`.
std::vector<FaceBC> readFaceBCs(const PSNode& gridNode, int numMaterials, bool diffusion);

}  // namespace anode
