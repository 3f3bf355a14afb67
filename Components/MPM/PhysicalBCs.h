// <PhysicalBC><MPM> (UINTAH_UPS.md §2.9), the conditions on particles: each child goes to its
// reader. The <scalar_flux> blocks go to the diffusion subcomponent (ReactiveFlow/ScalarFluxBC.h);
// pressure, force, heat_flux and arches_heat_flux are unsupported; any other tag is an error.
#pragma once

#include <vector>

#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct PhysicalBCs {
  PSNode node;                     // <PhysicalBC>; empty when the input has none
  std::vector<PSNode> scalarFlux;  // in file order
};

PhysicalBCs readPhysicalBCs(const PSNode& root);

}  // namespace anode
