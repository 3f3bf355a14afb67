#include "Components/MPM/ReactiveFlow/DiffusionInterface.h"

#include <algorithm>
#include <string>
#include <vector>

#include "Components/MPM/ActiveNodes.h"

namespace anode {

DiffusionInterface DiffusionInterface::fromInput(const PSNode& mpmMaterials, bool diffusion,
                                                 size_t materials) {
  DiffusionInterface interface;
  const PSNode iface = mpmMaterials.child("diffusion_interface");
  if (!iface) return interface;
  const std::string type = iface.get<std::string>("type", "null");
  if (type == "common") {
    if (!diffusion) iface.fail("diffusion_interface \"common\" needs <do_scalar_diffusion>true");
    interface.common = materials > 1;
  } else if (type != "null") {
    iface.requireChild("type").fail("diffusion_interface type \"" + type +
                                    "\" is not supported; accepted: null, common");
  }
  // Uintah gives the common concentration only to the materials listed (no list: all).
  const PSNode list = iface.child("materials");
  if (type != "common" || !list) {
    iface.acceptInert("materials");
    return interface;
  }
  std::vector<bool> named(materials, false);
  for (int m : list.value<std::vector<int>>()) {
    if (m < 0 || static_cast<size_t>(m) >= materials)
      list.fail("<materials> names material " + std::to_string(m) + ", but there are " +
                std::to_string(materials) + " material(s)");
    named[m] = true;
  }
  if (std::find(named.begin(), named.end(), false) != named.end())
    list.unsupported(
        "a common diffusion interface between only some of the materials (<materials> "
        "must name all " +
        std::to_string(materials) + " or be left out)");
  return interface;
}

void DiffusionInterface::apply(const std::vector<GridFields>& mechanics,
                               std::vector<ConcentrationGridFields>& fields,
                               const std::vector<NodeRange>& nodes) const {
  if (!common) return;
  forEachNode(nodes, [&](long k) {
    double mass = 0, mc = 0;
    for (size_t m = 0; m < fields.size(); ++m) {
      mass += mechanics[m].mass[k];
      mc += mechanics[m].mass[k] * fields[m].concentration[k];
    }
    if (mass > 0)
      for (ConcentrationGridFields& g : fields) g.concentration[k] = mc / mass;
  });
}

}  // namespace anode
