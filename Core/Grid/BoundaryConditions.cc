#include "Core/Grid/BoundaryConditions.h"

#include <string>

namespace anode {

namespace {

int materialId(const PSNode& bc, int numMaterials) {
  const std::string id = bc.requireAttribute("id");
  if (id == "all") return -1;
  int m = -1;
  try {
    m = parseValue<int>(id);
  } catch (const std::invalid_argument&) {
    bc.fail("<BCType id=\"" + id + "\">: id must be \"all\" or a material index");
  }
  if (m < 0 || m >= numMaterials)
    bc.fail("<BCType id=\"" + id + "\">: no material with that index (there are " +
            std::to_string(numMaterials) + ")");
  return m;
}

}  // namespace

std::vector<FaceBC> readFaceBCs(const PSNode& gridNode, int numMaterials, bool diffusion) {
  std::vector<FaceBC> out;
  const PSNode bcs = gridNode.child("BoundaryConditions");
  if (!bcs) return out;
  for (const PSNode& face : bcs.children()) {
    if (face.name() != "Face") face.fail("<BoundaryConditions> holds only <Face> tags");
    const auto side = face.attribute("side");
    if (!side) {
      if (face.attribute("circle") || face.attribute("rectangle") || face.attribute("annulus")) {
        face.unsupported("circle, rectangle and annulus sub-face boundary conditions");
        face.markSubtreeUsed();
        continue;
      }
      face.fail("<Face> requires side=\"x-|x+|y-|y+|z-|z+\"");
    }
    const std::string s = *side;
    if (s.size() != 2 || (s[0] != 'x' && s[0] != 'y' && s[0] != 'z') ||
        (s[1] != '-' && s[1] != '+'))
      face.fail("unknown face side \"" + s + "\"; accepted: x-, x+, y-, y+, z-, z+");
    for (const PSNode& bc : face.children()) {
      if (bc.name() != "BCType") bc.fail("<Face> holds only <BCType> tags");
      FaceBC f;
      f.axis = s[0] - 'x';
      f.side = s[1] == '+' ? 1 : 0;
      f.material = materialId(bc, numMaterials);
      const std::string label = bc.requireAttribute("label");
      const std::string var = bc.requireAttribute("var");
      if (label == "SD-Type") {
        if (!diffusion)
          bc.fail("label=\"SD-Type\" (concentration) needs <MPM><do_scalar_diffusion>true");
        if (var != "Dirichlet" && var != "Neumann")
          bc.fail("SD-Type var=\"" + var + "\": accepted Dirichlet, Neumann");
        f.kind = var == "Dirichlet" ? FaceBC::Kind::ConcentrationDirichlet
                                    : FaceBC::Kind::ConcentrationNeumann;
        if (auto attr = bc.attribute("value")) {
          try {
            f.value = parseValue<double>(*attr);
          } catch (const std::invalid_argument& e) {
            bc.fail(std::string("<BCType value=...>: ") + e.what());
          }
        } else {
          f.value = bc.require<double>("value");
        }
        out.push_back(f);
      } else if (label == "Symmetric" && var != "symmetry") {
        // Uintah's MPM applies a Symmetric condition only when its var is "symmetry".
        bc.warn("label=\"Symmetric\" var=\"" + var +
                "\": Uintah applies symmetry only with var=\"symmetry\"; this face is left "
                "free for this material, as there");
      } else if (label == "Symmetric") {
        f.kind = FaceBC::Kind::Symmetric;
        out.push_back(f);
      } else if (label == "Velocity" && var == "Dirichlet") {
        f.kind = FaceBC::Kind::VelocityDirichlet;
        if (auto attr = bc.attribute("value")) {
          try {
            f.velocity = parseValue<Vec3>(*attr);
          } catch (const std::invalid_argument& e) {
            bc.fail(std::string("<BCType value=...>: ") + e.what());
          }
        } else {
          f.velocity = bc.require<Vec3>("value");
        }
        out.push_back(f);
      } else if (label == "Velocity" && var == "Neumann") {
        bc.markSubtreeUsed();  // Uintah's MPM ignores velocity Neumann conditions
      } else if (label == "Temperature") {
        bc.markSubtreeUsed();  // sets only Uintah's nodal temperature, which isothermal MPM never
                               // reads
      } else {
        bc.fail("unknown boundary condition label=\"" + label + "\" var=\"" + var +
                "\"; accepted: Symmetric, Velocity (Dirichlet), SD-Type, Temperature (ignored)");
      }
    }
  }
  return out;
}

}  // namespace anode
