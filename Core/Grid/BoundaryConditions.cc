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

template <class T>
T BCType::value() const {
  const auto attr = node.attribute("value");
  if (!attr) return node.require<T>("value");
  try {
    return parseValue<T>(*attr);
  } catch (const std::invalid_argument& e) {
    node.fail(std::string("<BCType value=...>: ") + e.what());
  }
}

template double BCType::value<double>() const;
template Vec3 BCType::value<Vec3>() const;

void forEachBCType(const PSNode& gridNode, int numMaterials,
                   const std::function<void(const BCType&)>& read) {
  const PSNode bcs = gridNode.child("BoundaryConditions");
  if (!bcs) return;
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
    for (const PSNode& node : face.children()) {
      if (node.name() != "BCType") node.fail("<Face> holds only <BCType> tags");
      BCType bc;
      bc.node = node;
      bc.face.axis = s[0] - 'x';
      bc.face.side = s[1] == '+' ? 1 : 0;
      bc.face.material = materialId(node, numMaterials);
      bc.label = node.requireAttribute("label");
      bc.var = node.requireAttribute("var");
      read(bc);
    }
  }
}

}  // namespace anode
