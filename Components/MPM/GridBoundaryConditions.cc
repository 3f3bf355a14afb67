#include "Components/MPM/GridBoundaryConditions.h"

namespace anode {

std::array<bool, 6> GridBoundaryConditions::symmetryPlanes(int matl) const {
  std::array<bool, 6> planes{};
  for (const BCFace& face : symmetric)
    if (face.appliesTo(matl)) planes[2 * face.axis + face.side] = true;
  return planes;
}

GridBoundaryConditions readGridBoundaryConditions(
    const PSNode& gridNode, int numMaterials,
    const std::function<void(const BCType&)>& readConcentration) {
  GridBoundaryConditions out;
  forEachBCType(gridNode, numMaterials, [&](const BCType& bc) {
    if (bc.label == "SD-Type") {
      readConcentration(bc);
    } else if (bc.label == "Symmetric" && bc.var != "symmetry") {
      // Uintah's MPM applies a Symmetric condition only when its var is "symmetry".
      bc.node.warn("label=\"Symmetric\" var=\"" + bc.var +
                   "\": Uintah applies symmetry only with var=\"symmetry\"; this face is left "
                   "free for this material, as there");
    } else if (bc.label == "Symmetric") {
      out.symmetric.push_back(bc.face);
    } else if (bc.label == "Velocity" && bc.var == "Dirichlet") {
      out.velocity.push_back({bc.face, bc.value<Vec3>()});
    } else if (bc.label == "Velocity" && bc.var == "Neumann") {
      bc.node.markSubtreeUsed();  // Uintah's MPM ignores velocity Neumann conditions
    } else if (bc.label == "Temperature") {
      bc.node.markSubtreeUsed();  // sets only Uintah's nodal temperature, which isothermal MPM
                                  // never reads
    } else {
      bc.node.fail("unknown boundary condition label=\"" + bc.label + "\" var=\"" + bc.var +
                   "\"; accepted: Symmetric, Velocity (Dirichlet), SD-Type, Temperature (ignored)");
    }
  });
  return out;
}

void applySymmetry(const Grid& g, const std::vector<BCFace>& symmetric, int matl,
                   const NodeBox& nodes, std::vector<Vec3>& field) {
  for (const BCFace& face : symmetric)
    if (face.appliesTo(matl))
      forFaceNodesWithin(g, face, nodes.first, nodes.last,
                         [&](int n) { field[n][face.axis] = 0.0; });
}

void applyVelocityDirichlet(const Grid& g, const std::vector<VelocityBC>& velocity, int matl,
                            std::vector<Vec3>& field) {
  for (const VelocityBC& bc : velocity)
    if (bc.face.appliesTo(matl)) forFaceNodes(g, bc.face, [&](int n) { field[n] = bc.velocity; });
}

}  // namespace anode
