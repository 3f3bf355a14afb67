// Face boundary conditions applied to nodal vectors (UINTAH_UPS.md §2.10): Symmetric zeroes the
// normal component, Velocity Dirichlet prescribes the vector, on the face nodes and the extra
// nodes beyond them. (The SD-Type conditions on concentration: ReactiveFlow/ConcentrationBCs.h.)
// Symmetric visits only the face nodes within a box, the step's active nodes: no particle reads
// a node outside them, where the fields are zero but for the values Dirichlet conditions set.
#pragma once

#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"

namespace anode {

void applySymmetry(const Grid& g, const std::vector<FaceBC>& bcs, int matl, const NodeBox& nodes,
                   std::vector<Vec3>& field);
void applyVelocityDirichlet(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                            std::vector<Vec3>& field);

}  // namespace anode
