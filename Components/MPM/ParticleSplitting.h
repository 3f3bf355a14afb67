// Particle splitting (<refine_particles>true, UINTAH_UPS.md §9): a particle whose physical domain
// F*size*diag(dx) is stretched beyond the stretch ratio splits into 4 along its longest edge,
// conserving mass, volume, lithium and momentum. Each particle splits at most once.
#pragma once

#include <functional>
#include <vector>

#include "Components/MPM/ParticleSet.h"
#include "Components/MPM/SplitParticle.h"
#include "Core/Grid/Grid.h"

namespace anode {

// The edge (0, 1, 2: a column of F*size*diag(dx)) a particle splits along, or -1 if none:
// squared length ratios against ratio^2 in Uintah's order (edge 3 tested only when ndim = 3).
int splitAxis(const Mat3& domain, double ratio, int ndim);

// Splits every stretched particle not yet refined, in index order; returns those that split, in
// order: each one's 3 children are appended in that order, and get the IDs
// firstChildId(parent's ID) + 0, 1, 2.
std::vector<SplitParticle> splitStretchedParticles(
    ParticleSet& p, const Grid& grid, double ratio,
    const std::function<int64_t(int64_t)>& firstChildId);
// The same with IDs handed out from nextId on, in index order.
std::vector<SplitParticle> splitStretchedParticles(ParticleSet& p, const Grid& grid, double ratio,
                                                   int64_t& nextId);
// The IDs of the particles splitStretchedParticles would split now, in index order.
std::vector<int64_t> stretchedParticleIds(const ParticleSet& p, const Grid& grid, double ratio);

}  // namespace anode
