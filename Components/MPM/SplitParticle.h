// One particle split in four by particle splitting (ParticleSplitting.h): what a subcomponent
// that keeps per-particle geometry of its own (the flux faces of ReactiveFlow) needs to share it
// among the children.
#pragma once

#include <cstddef>

#include "Core/Math/Types.h"

namespace anode {

struct SplitParticle {
  size_t child[4];  // the parent's index (now the first child's), then its 3 appended children
  Vec3 offset[4];   // each child's position less the parent's, before the split
  Vec3 direction;   // the unit edge the parent split along
};

}  // namespace anode
