#include "Core/Parallel/DecompositionReport.h"

#include <algorithm>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "Core/Parallel/Bisection.h"

namespace anode {

std::string describeDecomposition(const DecompositionProblem& problem, int ranks) {
  const Vec3i& cells = problem.cells;
  const Decomposition cuts = Decomposition::balanced(
      cells, ranks, planesOfBoxes(cells, problem.perCell, {CellBox{Vec3i::Zero(), cells}})[0]);
  std::vector<CellBox> tensor;
  for (int r = 0; r < ranks; ++r) tensor.push_back(cuts.box(r));
  // The boxes a run of `ranks` ranks draws.
  std::optional<Decomposition> bisected;
  std::string bisectionError;
  try {
    bisected = Decomposition::bisected(cells, ranks, problem.counts);
  } catch (const std::runtime_error& e) {
    bisectionError = e.what();
  }
  const int ghost = problem.ghostWidth;
  std::ostringstream s;
  s << "sus --decompose " << ranks << ": "
    << (bisected ? bisected->describe() : "no boxes: " + bisectionError) << "\n";
  const auto describe = [&](const char* name, const std::vector<CellBox>& boxes) {
    const std::vector<double> particles = particlesPerBox(cells, boxes, problem.perCell);
    const double total = std::accumulate(particles.begin(), particles.end(), 0.0);
    const auto [fewest, most] = std::minmax_element(particles.begin(), particles.end());
    double ghostNodes = 0, mostGhostNodes = 0;
    for (const CellBox& b : boxes) {
      double stored = 1;
      for (int d = 0; d < 3; ++d)
        stored *= std::min(b.upper[d] + ghost, cells[d]) - std::max(b.lower[d] - ghost, 0) + 1;
      ghostNodes += stored - static_cast<double>(b.cellCount());
      mostGhostNodes = std::max(mostGhostNodes, stored - static_cast<double>(b.cellCount()));
    }
    s << "  " << name << ": particles per box fewest " << *fewest << ", mean " << total / ranks
      << ", most " << *most << "; imbalance (most / mean) " << *most / (total / ranks) << "; "
      << ghostNodes << " ghost nodes (at most " << mostGhostNodes << " a box), about "
      << 8.0 * problem.valuesPerNode * ghostNodes << " bytes of ghost sums a step\n";
  };
  if (bisected) {
    std::vector<CellBox> boxes;
    for (int r = 0; r < ranks; ++r) boxes.push_back(bisected->box(r));
    describe("recursive bisection (what runs use)", boxes);
  }
  describe("tensor-product cuts (measured only)", tensor);
  s << "  ghost layers " << ghost << " cells, " << problem.valuesPerNode << " values a node\n";
  return s.str();
}

}  // namespace anode
