#include "Core/Grid/Grid.h"

#include <cmath>
#include <string>

#include "Core/Util/MemoryBudget.h"

namespace anode {

Grid Grid::fromInput(const PSNode& gridNode) {
  const PSNode level = gridNode.requireChild("Level");
  const auto boxes = level.children("Box");
  if (boxes.empty()) level.fail("<Level> requires a <Box> with <lower>, <upper> and <resolution>");
  if (boxes.size() > 1)
    boxes[1].fail("several <Box> in one <Level> are not supported; use one box");
  if (gridNode.children("Level").size() > 1)
    gridNode.children("Level")[1].fail("several grid levels (AMR) are not supported");
  if (const PSNode periodic = level.child("periodic")) {
    if (periodic.value<Vec3i>() != Vec3i::Zero()) periodic.unsupported("periodic grid boundaries");
  }
  const PSNode box = boxes[0];
  Grid g;
  g.lower = box.require<Vec3>("lower");
  g.upper = box.require<Vec3>("upper");
  for (int d = 0; d < 3; ++d)
    if (!(g.upper[d] > g.lower[d]))
      box.requireChild("upper").fail("<upper> must exceed <lower> in every direction");
    else if (!std::isfinite(g.upper[d] - g.lower[d]))
      box.requireChild("upper").fail("<upper> - <lower> overflows a double");
  const PSNode resolution = box.child("resolution");
  const PSNode spacing = level.child("spacing");
  if (resolution && spacing)
    spacing.fail("give either <Box><resolution> or <Level><spacing>, not both");
  if (resolution) {
    g.cells = resolution.value<Vec3i>();
    if ((g.cells.array() < 1).any())
      resolution.fail("<resolution> needs at least one cell in each direction, found [" +
                      std::to_string(g.cells.x()) + "," + std::to_string(g.cells.y()) + "," +
                      std::to_string(g.cells.z()) + "]");
  } else if (spacing) {
    const Vec3 h = spacing.value<Vec3>();
    for (int d = 0; d < 3; ++d) {
      if (!(h[d] > 0)) spacing.fail("<spacing> must be positive in each direction");
      const double n = (g.upper[d] - g.lower[d]) / h[d];
      if (!(n < kMaxCellsPerAxis))
        spacing.fail("<spacing> gives more than " + std::to_string(kMaxCellsPerAxis) +
                     " cells along an axis");
      if (std::abs(n - std::round(n)) > 1e-6 * n)
        spacing.fail("<spacing> must divide the box into a whole number of cells");
      g.cells[d] = static_cast<int>(std::round(n));
    }
  } else {
    box.fail("<Box> requires <resolution> (or <Level><spacing>)");
  }
  if (const PSNode extra = box.child("extraCells")) {
    g.extra = extra.value<Vec3i>();
    if ((g.extra.array() < 0).any() || (g.extra.array() > 2).any())
      extra.fail("<extraCells> must be 0, 1 or 2 in each direction");
  }
  if (const PSNode patches = box.child("patches")) {
    if ((patches.value<Vec3i>().array() < 1).any()) patches.fail("<patches> must be >= 1");
  }
  // Node indices are 32-bit, and every node holds at least one material's fields.
  const PSNode size = resolution ? resolution : spacing;
  double nodes = 1;
  for (int d = 0; d < 3; ++d) {
    if (g.cells[d] > kMaxCellsPerAxis)
      size.fail("the grid has " + std::to_string(g.cells[d]) + " cells along an axis; at most " +
                std::to_string(kMaxCellsPerAxis) + " are supported");
    nodes *= g.cells[d] + 1.0 + 2.0 * g.extra[d];
  }
  if (nodes > 2147483647.0)
    size.fail("the grid has " + formatCount(nodes) +
              " nodes; at most 2147483647 are supported (32-bit node indices)");
  if (nodes * kMinBytesPerNode > static_cast<double>(memoryBudget()))
    size.fail("the grid's " + formatCount(nodes) + " nodes need at least " +
              formatBytes(nodes * kMinBytesPerNode) + ", beyond " + describeMemoryBudget());
  g.dx = (g.upper - g.lower).cwiseQuotient(g.cells.cast<double>());
  return g;
}

}  // namespace anode
