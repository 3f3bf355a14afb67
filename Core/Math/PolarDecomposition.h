// Polar decomposition F = R U (paper Eq. 26): R proper orthogonal, U = R^T F symmetric positive
// definite. The stress update needs R only.
#pragma once

#include "Core/Math/Types.h"

namespace anode {

// Requires det F > 0. Scaled Newton iteration (Higham 1986), converged to round-off.
Mat3 rotationOf(const Mat3& F);

}  // namespace anode
