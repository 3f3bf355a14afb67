// The mechanics conditions of <Grid><BoundaryConditions> (UINTAH_UPS.md §2.10), applied to nodal
// vectors: Symmetric zeroes the normal component, Velocity Dirichlet prescribes the vector, on the
// face nodes and the extra nodes beyond them. Symmetric visits only the face nodes within a box,
// the step's active nodes: no particle reads a node outside them, where the fields are zero but
// for the values Dirichlet conditions set. The SD-Type conditions on concentration belong to the
// diffusion subcomponent (ReactiveFlow/ConcentrationBCs.h): the reader hands them to its caller,
// which passes them on (ReactiveFlow::fromInput).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"

namespace anode {

struct VelocityBC {
  BCFace face;
  Vec3 velocity = Vec3::Zero();
};

struct GridBoundaryConditions {
  std::vector<BCFace> symmetric;
  std::vector<VelocityBC> velocity;  // Dirichlet

  // Per face (2 axis + side): whether a Symmetric condition applies to material matl.
  std::array<bool, 6> symmetryPlanes(int matl) const;
};

// Reads every <BCType> in file order: Symmetric, Velocity and Temperature (inert) here, SD-Type
// handed to readConcentration; any other label is an error.
GridBoundaryConditions readGridBoundaryConditions(
    const PSNode& gridNode, int numMaterials,
    const std::function<void(const BCType&)>& readConcentration);

void applySymmetry(const Grid& g, const std::vector<BCFace>& symmetric, int matl,
                   const NodeBox& nodes, std::vector<Vec3>& field);
void applyVelocityDirichlet(const Grid& g, const std::vector<VelocityBC>& velocity, int matl,
                            std::vector<Vec3>& field);

}  // namespace anode
