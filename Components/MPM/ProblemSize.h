// The memory a problem needs, estimated before it is allocated, against the budget of
// Core/Util/MemoryBudget.h: setup refuses a particle count or grid beyond it with an InputError
// at the tag responsible instead of failing an allocation (or exhausting the machine) later.
#pragma once

#include <cstddef>

#include "Components/MPM/MPMFlags.h"
#include "Core/Grid/Grid.h"
#include "Core/ProblemSpec/ProblemSpec.h"

namespace anode {

// Bytes per particle: the particle arrays, the interpolation weights (the interpolator's most
// nodes per particle) and the step's scratch.
double bytesPerParticle(const MPMFlags& flags);
// Bytes per grid node: the nodal fields of every material and the per-thread scatter buffers.
double bytesPerGridNode(const MPMFlags& flags, size_t materials, int threads);
// The most particles the budget holds beside nothing else.
double maxParticles(const MPMFlags& flags);

// Throws an InputError at the grid's <resolution> (or <spacing>) when the particles and the
// nodal arrays together exceed the budget.
void checkProblemSize(const PSNode& gridNode, const Grid& grid, const MPMFlags& flags,
                      size_t materials, size_t particles, int threads);

}  // namespace anode
