// The faces of <Grid><BoundaryConditions> (UINTAH_UPS.md §2.10): where each <Face><BCType>
// applies. What a <BCType> prescribes belongs to the component its label names, which reads it
// (Components/MPM/GridBoundaryConditions.h).
#pragma once

#include <algorithm>
#include <functional>
#include <string>

#include "Core/Grid/Grid.h"
#include "Core/Math/Types.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

// One face of the grid, for one material or all.
struct BCFace {
  int axis = 0;       // 0, 1, 2 for x, y, z
  int side = 0;       // 0 for the minus face, 1 for the plus face
  int material = -1;  // -1 for id="all"

  bool appliesTo(int matl) const { return material < 0 || material == matl; }
};

// The name of face (axis, side) as the input writes it: "x-", "x+", ... "z+".
inline const char* faceName(int axis, int side) {
  static const char* names[3][2] = {{"x-", "x+"}, {"y-", "y+"}, {"z-", "z+"}};
  return names[axis][side];
}

// Distance of x from the grid face (axis, side), positive inside the grid.
inline double distanceToFace(const Grid& g, const Vec3& x, int axis, int side) {
  return side == 0 ? x[axis] - g.lower[axis] : g.upper[axis] - x[axis];
}

// One <BCType>: its element, its face, its label and var.
struct BCType {
  PSNode node;
  BCFace face;
  std::string label, var;

  // Its value: the value= attribute or the <value> child (T is double or Vec3).
  template <class T>
  T value() const;
};

// Calls f(node) for every stored node on `face` or outside it (the extra nodes beyond) that lies
// within grid indices [first, last].
template <class Fn>
void forFaceNodesWithin(const Grid& g, const BCFace& face, const Vec3i& first, const Vec3i& last,
                        Fn f) {
  Vec3i lo = g.firstNode().cwiseMax(first), hi = g.lastNode().cwiseMin(last);
  if (face.side == 0)
    hi[face.axis] = std::min(hi[face.axis], 0);
  else
    lo[face.axis] = std::max(lo[face.axis], g.cells[face.axis]);
  for (int k = lo.z(); k <= hi.z(); ++k)
    for (int j = lo.y(); j <= hi.y(); ++j)
      for (int i = lo.x(); i <= hi.x(); ++i) f(g.nodeIndex(i, j, k));
}

// The same on every stored node of the face.
template <class Fn>
void forFaceNodes(const Grid& g, const BCFace& face, Fn f) {
  forFaceNodesWithin(g, face, g.firstNode(), g.lastNode(), f);
}

// Calls read with every <BCType> of every <Face>, in file order; `numMaterials` bounds the id
// attribute.
void forEachBCType(const PSNode& gridNode, int numMaterials,
                   const std::function<void(const BCType&)>& read);

}  // namespace anode
