// Face boundary conditions applied to nodal vectors (UINTAH_UPS.md §2.10): Symmetric zeroes the
// normal component, Velocity Dirichlet prescribes the vector, on the face nodes and the extra
// nodes beyond them. (The SD-Type conditions on concentration: ReactiveFlow/ConcentrationBCs.h.)
#pragma once

#include <vector>

#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"

namespace anode {

void applySymmetry(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                   std::vector<Vec3>& field);
void applyVelocityDirichlet(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                            std::vector<Vec3>& field);

}  // namespace anode
