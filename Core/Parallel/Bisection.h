// Recursive coordinate bisection of the grid's cells (docs/parallel.md, "How the boxes are
// chosen"): a box of cells and its ranks are cut in two along the axis its particles span most,
// at the plane that shares the particles as the ranks are shared, and each half is cut again, so
// that bodies whose particles are not separable along the axes (a disk on a square substrate)
// are balanced. Measured by `sus --decompose` beside the tensor-product cuts runs use.
#pragma once

#include <vector>

#include "Core/Parallel/Decomposition.h"

namespace anode {

// `ranks` boxes over `cells`, every box at least one cell, from the particles per cell
// (perCell[(k * cells.y() + j) * cells.x() + i]); throws std::runtime_error when a box cannot be
// cut for its ranks (fewer cells than ranks; or halves of ranks that fit no cut, as 8 ranks on
// 3x3x1 cells).
std::vector<CellBox> bisectCells(const Vec3i& cells, int ranks, const std::vector<double>& perCell);

// Particles per box: the sum of perCell over each box.
std::vector<double> particlesPerBox(const Vec3i& cells, const std::vector<CellBox>& boxes,
                                    const std::vector<double>& perCell);

}  // namespace anode
