#include "Components/MPM/ProblemSize.h"

#include <algorithm>
#include <string>

#include "Core/Util/MemoryBudget.h"

namespace anode {

double bytesPerParticle(const MPMFlags& flags) {
  // id, x, velocity, displacement, mass, volume, F, stress, size, plastic strain and its rate.
  double bytes = 8 + 3 * 24 + 2 * 8 + 3 * 72 + 2 * 8;
  // Concentration, its gradient, diffusivity; flux rate, load curve ids, areas; setup's surface.
  if (flags.doScalarDiffusion) bytes += 8 + 24 + 8 + 8 + 12 + 24 + 1 + 2 * 24;
  // Weights: count, offset, and per node an index, a weight and a gradient.
  bytes += 1 + 8 + maxNodesPerParticle(flags.interpolator) * (4 + 8 + 24);
  // Scratch of the step: velocity gradient, new F, concentration increment.
  return bytes + 2 * 72 + 8;
}

double bytesPerGridNode(const MPMFlags& flags, size_t materials, int threads) {
  // Diffusion (ReactiveFlow/DiffusionGridFields.h): 6 fields, 5 more and the source marks for a
  // material with flux BCs (counted for every material: an upper bound).
  const double perMaterial = Grid::kMinBytesPerNode + (flags.doScalarDiffusion ? 11 * 8 + 1 : 0);
  // The scatter buffer of each thread after the first: mass, momentum, force (and the 5
  // diffusion sums).
  const double perBuffer = 8 + 2 * 24 + (flags.doScalarDiffusion ? 5 * 8 : 0);
  return perMaterial * static_cast<double>(materials) + perBuffer * std::max(threads - 1, 0);
}

double maxParticles(const MPMFlags& flags) {
  return static_cast<double>(memoryBudget()) / bytesPerParticle(flags);
}

void checkProblemSize(const PSNode& gridNode, const Grid& grid, const MPMFlags& flags,
                      size_t materials, size_t particles, int threads) {
  const double nodes = static_cast<double>(grid.numNodes());
  const double particleBytes = static_cast<double>(particles) * bytesPerParticle(flags);
  const double gridBytes = nodes * bytesPerGridNode(flags, materials, threads);
  if (particleBytes + gridBytes <= static_cast<double>(memoryBudget())) return;
  const PSNode level = gridNode.child("Level");
  const PSNode box = level ? level.child("Box") : PSNode();
  PSNode where = box ? box.child("resolution") : PSNode();
  if (!where && level) where = level.child("spacing");
  if (!where) where = box ? box : gridNode;
  where.fail("the grid's " + formatCount(nodes) + " nodes (" + formatBytes(gridBytes) + " for " +
             std::to_string(materials) + " material(s) and " + std::to_string(threads) +
             " thread(s)) and " + formatCount(static_cast<double>(particles)) + " particles (" +
             formatBytes(particleBytes) + ") exceed " + describeMemoryBudget());
}

}  // namespace anode
