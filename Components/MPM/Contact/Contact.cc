#include "Components/MPM/Contact/Contact.h"

#include <algorithm>
#include <string>

#include "Components/MPM/ActiveNodes.h"

namespace anode {

namespace {
// Uintah's SingleVelContact: the excluded material is present at a node with this much mass.
constexpr double kExcludedMassPresent = 1e-99;
}  // namespace

Contact Contact::fromInput(const PSNode& mpmMaterials, int numMaterials) {
  Contact c;
  const auto blocks = mpmMaterials.children("contact");
  if (blocks.size() > 1) blocks[1].fail("only one <contact> block is supported");
  for (int m = 0; m < numMaterials; ++m) c.materials.push_back(m);
  if (blocks.empty()) return c;
  const PSNode contact = blocks[0];
  const std::string type = contact.get<std::string>("type", "null");
  if (type != "null" && type != "single_velocity")
    contact.requireChild("type").fail("contact type \"" + type +
                                      "\" is not supported; accepted: null, single_velocity");
  const std::string existing = ", but there are " + std::to_string(numMaterials) +
                               " material(s), indices 0 to " + std::to_string(numMaterials - 1);
  if (const PSNode list = contact.child("materials")) {
    c.materials.clear();
    for (int m : list.value<std::vector<int>>()) {
      if (m < 0) list.fail("<materials> holds a negative material index");
      if (m < numMaterials) {
        c.materials.push_back(m);
        continue;
      }
      // Uintah's own inputs list [0,1] with one material under null contact, which acts on none.
      if (type != "null") list.fail("<materials> names material " + std::to_string(m) + existing);
    }
  }
  if (type == "null") return c;
  c.type = Type::SingleVelocity;
  c.exchangeInterpolated = contact.get<int>("OneOrTwoStep", 2) == 2;
  const int exclude = contact.get<int>("ExcludeMaterial", -999);
  if (exclude != -999 && (exclude < 0 || exclude >= numMaterials))
    contact.requireChild("ExcludeMaterial")
        .fail("<ExcludeMaterial> names material " + std::to_string(exclude) + existing);
  if (exclude != -999) {
    c.excluded = exclude;
    c.materials.erase(std::remove(c.materials.begin(), c.materials.end(), exclude),
                      c.materials.end());
  }
  return c;
}

void Contact::exchange(std::vector<GridFields>& fields, std::vector<Vec3> GridFields::*velocity,
                       const std::vector<NodeRange>& nodes) const {
  if (type == Type::Null || materials.size() < 2) return;
  forEachNode(nodes, [&](long n) {
    if (excluded >= 0 && fields[excluded].mass[n] >= kExcludedMassPresent) return;
    double mass = 0;
    Vec3 momentum = Vec3::Zero();
    for (int m : materials) {
      mass += fields[m].mass[n];
      momentum += fields[m].mass[n] * (fields[m].*velocity)[n];
    }
    if (mass <= 0) return;
    const Vec3 common = momentum / mass;
    for (int m : materials) (fields[m].*velocity)[n] = common;
  });
}

}  // namespace anode
