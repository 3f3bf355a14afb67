// Recursive coordinate bisection of the grid's cells (docs/parallel.md, "How the boxes are
// chosen"): a box of cells and its ranks are cut in two along the axis whose best cell plane
// shares its particles most nearly as its ranks are shared, and each half is cut again
// (Decomposition::bisected, level by level), so that bodies whose particles are not separable
// along the axes (a disk on a square substrate) are balanced.
#pragma once

#include <array>
#include <vector>

#include "Core/Grid/Grid.h"

namespace anode {

// Where a box is cut: cells with index below `at` along `axis` form the first part, which gets
// `left` of the box's ranks.
struct BisectionCut {
  int axis = -1, at = 0, left = 0;
};

// The shares of a box's `ranks` ranks a cut may give its first part, which holds `below` of the
// box's `total` > 0 particles in `cellsBelow` of its cells (`cellsAbove` in the other): the ranks
// halved, or shared as the cut shares the particles, rounded either way, and with `further` one
// rank beyond each rounding too; each part at least a cell per rank. In ascending order.
struct RankShares {
  int left[5];
  int count = 0;
};
RankShares sharesOfRanks(double below, double total, int ranks, long cellsBelow, long cellsAbove,
                         bool further);

// The cut of `box` (planes[d]: its particles per cell plane along axis d, from box.lower[d]) and
// its `ranks` ranks in two parts, each at least a cell per rank, that loads the busier part least
// (particles per rank): the ranks halved, or shared as the cut shares the particles; throws
// std::runtime_error when no axis has such a cut (fewer cells than ranks, or parts that fit no
// cut, as 8 ranks on 3x3x1 cells).
BisectionCut bisectionCut(const CellBox& box, const std::array<std::vector<double>, 3>& planes,
                          int ranks);

// Per box, its particles per cell plane along each axis from the particles per cell of the grid
// (perCell[(k * cells.y() + j) * cells.x() + i]).
std::vector<std::array<std::vector<double>, 3>> planesOfBoxes(const Vec3i& cells,
                                                              const std::vector<double>& perCell,
                                                              const std::vector<CellBox>& boxes);

// Particles per box: the sum of perCell over each box.
std::vector<double> particlesPerBox(const Vec3i& cells, const std::vector<CellBox>& boxes,
                                    const std::vector<double>& perCell);

}  // namespace anode
