// sus --decompose N: the boxes N ranks would draw for a problem, beside those of tensor-product
// cuts, with what each layout costs (docs/parallel.md, "Setup per box").
#pragma once

#include <string>
#include <vector>

#include "Core/Parallel/Decomposition.h"

namespace anode {

// What the problem needs to be described: its cells, the particles per cell (x fastest) and the
// same as counts for recursive bisection, the ghost layers of its interpolator and the values a
// ghost sum carries per node.
struct DecompositionProblem {
  Vec3i cells;
  std::vector<double> perCell;
  Decomposition::ParticleCounts counts;
  int ghostWidth = 0;
  int valuesPerNode = 0;
};

// Per layout: particles per box, imbalance, and the nodes a box stores beyond its own cells (its
// box grown by the ghost layers within the grid) times the values of a ghost sum.
std::string describeDecomposition(const DecompositionProblem& problem, int ranks);

}  // namespace anode
