// MPM's part in a distributed run (docs/parallel.md) beside RankLayout's: setup per box (each
// rank creates only the particles of its own box, and those flagging the flux particles needs
// around it), the ghost sums that complete P2G on the nodes shared with other ranks, and
// sus --decompose's description of the boxes.
#include <algorithm>
#include <cmath>
#include <string>

#include "Components/MPM/MPM.h"
#include "Components/MPM/ParticleMigration.h"
#include "Components/MPM/ProblemSize.h"
#include "Core/Parallel/DecompositionReport.h"
#include "Core/Util/Errors.h"
#include "Core/Util/MemoryBudget.h"

namespace anode {

Decomposition::ParticleCounts MPM::seedCounts() const {
  return {[this](const std::function<void(const Vec3i&, double)>& add) {
            for (const MaterialSeeds& s : seeds_) s.forEachOccupiedCell(layout_.problemGrid(), add);
          },
          nullptr};
}

void MPM::checkParticlesOfRank(const CellBox& region) const {
  const double limit = std::floor(maxParticles(problem_.flags));
  double n = 0;
  for (const MaterialSeeds& s : seeds_)
    for (const MaterialSeeds::Object& object : s.objects) {
      n += static_cast<double>(object.countIn(layout_.problemGrid(), region));
      if (n > limit)
        object.sizeNode.fail("the <geom_object>s up to this one lay out " + formatCount(n) +
                             " particles" +
                             (Communicator::size() > 1 ? " in this rank's part of the grid" : "") +
                             ", beyond " + describeMemoryBudget() + " at about " +
                             std::to_string(static_cast<long>(bytesPerParticle(problem_.flags))) +
                             " bytes per particle");
    }
}

void MPM::keepParticlesOfBox(const CellBox& box) {
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    std::vector<long> keep;
    for (MaterialSeeds::Object& object : seeds_[m].objects) {
      const size_t first = keep.size();
      std::vector<Vec3> faceAreas;
      for (size_t i = object.first; i < object.first + object.count; ++i)
        if (box.contains(layout_.problemGrid().interiorCell(p.x[i]))) {
          keep.push_back(static_cast<long>(i));
          if (object.smooth) faceAreas.push_back(object.faceAreaOf(i));
        }
      object.first = first;
      object.count = keep.size() - first;
      object.smoothFaceAreas = std::move(faceAreas);
    }
    keepParticles(p, keep);
  }
}

std::vector<NodeArray> MPM::ghostSumArrays(bool concentrationOnly) {
  std::vector<NodeArray> sums;
  if (!concentrationOnly)  // the rest of P2G's sums stand in a concentration-only P2G
    for (GridFields& g : step_.fields) {
      sums.push_back({g.mass.data(), 1});
      sums.push_back({g.momentum.data()->data(), 3});
      sums.push_back({g.internalForce.data()->data(), 3});
    }
  if (step_.concentration)
    for (ConcentrationGridFields& g : *step_.concentration) g.addScatteredArrays(sums);
  return sums;
}

void MPM::sumGhostNodes(Collective every, bool concentrationOnly) {
  layout_.ghosts()->sumOverRanks(every, ghostSumArrays(concentrationOnly));
}

std::string MPM::describeDecomposition(int ranks) {
  // From the particles the geom_objects lay out per cell, none of them created (problemSetup
  // without particles): the counts setup draws a run's boxes from.
  const Grid& whole = layout_.problemGrid();
  const Vec3i& cells = whole.cells;
  DecompositionProblem problem{
      cells, std::vector<double>(static_cast<size_t>(cells.cast<long>().prod()), 0.0),
      seedCounts()};
  double reach = 0;  // of a CPDI domain at the start (F = I), in cells
  for (const MaterialSeeds& seeds : seeds_) {
    seeds.forEachOccupiedCell(whole, [&](const Vec3i& c, double count) {
      problem.perCell[(static_cast<size_t>(c.z()) * cells.y() + c.y()) * cells.x() + c.x()] +=
          count;
    });
    for (const MaterialSeeds::Object& object : seeds.objects) {
      if (!object.smooth)
        reach = std::max(reach, domainReach(object.res.cast<double>().cwiseInverse().asDiagonal()));
      for (const SmoothParticle& p : object.smoothLayout)
        reach = std::max(reach, domainReach(p.size));
    }
  }
  problem.ghostWidth = layout_.ghostWidthFor(reach);
  // The values a ghost sum carries per node, from the grid fields laid out on one cell (the
  // whole grid's would take a rank's memory many times over).
  layout_.useWindow(Decomposition::fromCuts(
                        {std::vector<int>{0, 1, cells.x()}, {0, 1, cells.y()}, {0, 1, cells.z()}})
                        .window(whole, 0, 0));
  for (const NodeArray& a : ghostSumArrays()) problem.valuesPerNode += a.width;
  return anode::describeDecomposition(problem, ranks);
}

}  // namespace anode
