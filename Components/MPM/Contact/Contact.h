// Contact between materials on the grid (UINTAH_UPS.md §10): null or single_velocity.
#pragma once

#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/GridFields.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

struct Contact {
  enum class Type { Null, SingleVelocity } type = Type::Null;
  std::vector<int> materials;        // materials that share one velocity field
  int excluded = -1;                 // ExcludeMaterial: no sharing at nodes where it has mass
  bool exchangeInterpolated = true;  // OneOrTwoStep = 2: also after P2G, not only after integration

  static Contact fromInput(const PSNode& mpmMaterials, int numMaterials);

  // Replaces each member's nodal velocity by the centre-of-mass velocity sum(m v)/sum(m), on
  // the nodes of `nodes` where the excluded material (if any) has no mass, as Uintah does.
  void exchange(std::vector<GridFields>& fields, std::vector<Vec3> GridFields::*velocity,
                const std::vector<NodeRange>& nodes) const;
};

}  // namespace anode
