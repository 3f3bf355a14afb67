// Face boundary conditions applied to nodal vectors (UINTAH_UPS.md §2.10): Symmetric zeroes the
// normal component, Velocity Dirichlet prescribes the vector, on the face nodes and the extra
// nodes beyond them.
#pragma once

#include <vector>

#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"

namespace anode {

void applySymmetry(const Grid& g, const std::vector<FaceBC>& bcs, int matl, std::vector<Vec3>& field);
void applyVelocityDirichlet(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                            std::vector<Vec3>& field);
// SD-Type (UINTAH_UPS.md §5.3): Dirichlet sets the face nodes and the extra nodes beyond them to
// the value; Neumann sets them to their inward neighbour minus value*dx.
void applyConcentrationBCs(const Grid& g, const std::vector<FaceBC>& bcs, int matl,
                           std::vector<double>& field);

}  // namespace anode
