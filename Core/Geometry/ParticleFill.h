// Uintah's particle placement (UINTAH_UPS.md §3.1): in every interior cell, res.x*res.y*res.z
// candidate points at X_cell + dxp*(i + 1/2), kept when inside the piece. Only the cells that
// meet the piece's bounding box are visited (the same points, in the same order).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "Core/Geometry/GeometryPiece.h"
#include "Core/Grid/Grid.h"

namespace anode {

// Candidate points fillParticles tests: the cells it visits times res.x*res.y*res.z.
double fillCandidates(const Grid& grid, const GeometryPiece& piece, const Vec3i& res);

// Whether a candidate point of the same lattice continued beyond the interior cells lies inside
// the piece: a particle Uintah (and fillParticles) would silently drop. Beyond a face marked in
// `mirror` (index 2 axis + side, side 1 the plus face), a symmetry plane, points do not count: a
// piece crossing it is the idiom for half of a symmetric body. A piece whose bounding box meets
// more than kMaxOutsideCandidates points that count is outside without testing them.
constexpr double kMaxOutsideCandidates = 1e8;
bool placesParticlesOutside(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                            const std::array<bool, 6>& mirror);

// The points inside the piece; stops after maxParticles + 1 (the caller refuses that many).
std::vector<Vec3> fillParticles(const Grid& grid, const GeometryPiece& piece, const Vec3i& res,
                                size_t maxParticles = static_cast<size_t>(-1));

}  // namespace anode
