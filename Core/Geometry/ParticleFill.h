// Uintah's particle placement (UINTAH_UPS.md §3.1): in every interior cell, res.x*res.y*res.z
// candidate points at X_cell + dxp*(i + 1/2), kept when inside the piece.
#pragma once

#include <vector>

#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

std::vector<Vec3> fillParticles(const Grid& grid, const GeometryPiece& piece, const Vec3i& res);

}  // namespace anode
