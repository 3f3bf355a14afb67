#include "Components/MPM/PhysicalBCs.h"

namespace anode {

PhysicalBCs readPhysicalBCs(const PSNode& root) {
  PhysicalBCs out;
  out.node = root.child("PhysicalBC");
  if (!out.node) return out;
  const PSNode mpm = out.node.child("MPM");
  if (!mpm) return out;
  for (const PSNode& bc : mpm.children()) {
    if (bc.name() == "scalar_flux") {
      out.scalarFlux.push_back(bc);
      continue;
    }
    if (bc.name() == "pressure" || bc.name() == "force" || bc.name() == "heat_flux" ||
        bc.name() == "arches_heat_flux")
      bc.unsupported("<" + bc.name() + "> boundary condition");
    else
      bc.fail("unknown physical boundary condition <" + bc.name() + ">");
    bc.markSubtreeUsed();
  }
  return out;
}

}  // namespace anode
