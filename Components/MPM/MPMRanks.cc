// MPM's part in a distributed run (docs/parallel.md): drawing the boxes and laying out this
// rank's window, the nodes its particles reach, the ghost sums after P2G and the migration of
// particles after the step. The decomposition itself is Core/Parallel/Decomposition, the talking
// Core/Parallel/Communicator; on one rank only decompose() runs, once, and lays out the whole grid.
#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>

#include "Components/MPM/MPM.h"
#include "Components/MPM/ParticleMigration.h"
#include "Components/MPM/ProblemSize.h"
#include "Core/Parallel/Bisection.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"
#include "Core/Util/MemoryBudget.h"

namespace anode {

namespace {

// How far a CPDI domain of edge vectors `Fsize` (F times the particle's size, in cells) reaches
// from its particle along an axis: half its extent.
double domainReach(const Mat3& Fsize) {
  return 0.5 * Fsize.cwiseAbs().rowwise().sum().maxCoeff();
}

}  // namespace

int MPM::ownerOf(const ParticleSet& p, size_t i) const {
  return decomposition_.ownerOfPoint(whole_.indexCoordinate(p.x[i]), Communicator::rank());
}

CellBox MPM::setupBox() {
  const int ranks = Communicator::size();
  if (ranks == 1) return {Vec3i::Zero(), whole_.cells};
  // The boxes from the particles the geom_objects lay out per cell, counted before any particle
  // is stored: the same on every rank, and the same boxes a fill of everything gives.
  decomposition_ = drawBoxes(seedCounts(), nullptr);
  return decomposition_.box(Communicator::rank());
}

Decomposition::ParticleCounts MPM::seedCounts() const {
  return {[this](const std::function<void(const Vec3i&, double)>& add) {
            for (const MaterialSeeds& s : seeds_) s.forEachOccupiedCell(whole_, add);
          },
          nullptr};
}

CellBox MPM::grownBySetupReach(const CellBox& box) const {
  if (Communicator::size() == 1 || !diffusion_ || !diffusion_->sharesSurfacesAtSetup()) return box;
  // A sample of a BC's surface goes to the nearest flagged particle within 1.5 particle spacings
  // (FluxSurfaceArea.h): the samples a particle of the box can get lie within 1.5 spacings of
  // it, and the particles they can go to within 3.
  Vec3 spacing = Vec3::Zero();
  for (const MaterialSeeds& s : seeds_)
    for (const MaterialSeeds::Object& object : s.objects)
      spacing = spacing.cwiseMax(object.spacing);
  const int reach = static_cast<int>(std::ceil(3 * spacing.norm() / whole_.dx.minCoeff())) + 1;
  return {(box.lower.array() - reach).max(0),
          (box.upper.array() + reach).min(whole_.cells.array())};
}

void MPM::checkParticlesOfRank(const CellBox& region) const {
  const double limit = std::floor(maxParticles(flags_));
  double n = 0;
  for (const MaterialSeeds& s : seeds_)
    for (const MaterialSeeds::Object& object : s.objects) {
      n += static_cast<double>(object.countIn(whole_, region));
      if (n > limit)
        object.sizeNode.fail(
            "the <geom_object>s up to this one lay out " + formatCount(n) + " particles" +
            (Communicator::size() > 1 ? " in this rank's part of the grid" : "") + ", beyond " +
            describeMemoryBudget() + " at about " +
            std::to_string(static_cast<long>(bytesPerParticle(flags_))) + " bytes per particle");
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
        if (box.contains(whole_.interiorCell(p.x[i]))) {
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

Decomposition::ParticleCounts MPM::particleCounts(bool allHere) const {
  Decomposition::ParticleCounts counts;
  counts.forEach = [this](const std::function<void(const Vec3i&, double)>& add) {
    for (const MPMMaterial& mat : materials_)
      for (const Vec3& x : mat.particles.x) add(whole_.interiorCell(x), 1.0);
  };
  // The counts of every rank's particles: one sum over the ranks.
  if (!allHere)
    counts.sumOverRanks = [](std::vector<double>& v) {
      collective::sum(v.data(), static_cast<int>(v.size()));
    };
  return counts;
}

Decomposition MPM::drawBoxes(const Decomposition::ParticleCounts& counts,
                             const Decomposition* earlier) const {
  // Recursive bisection; where a box cannot be cut for its ranks, the boxes drawn before (boxes
  // redrawn mid-run never fail where setup succeeded).
  try {
    return Decomposition::bisected(whole_.cells, Communicator::size(), counts);
  } catch (const std::runtime_error&) {
    if (earlier && earlier->ranks() == Communicator::size()) return *earlier;
    throw;
  }
}

int MPM::ghostWidthFor(double reach) const {
  if (flags_.interpolator != InterpolatorKind::CPDI)
    return flags_.interpolator == InterpolatorKind::Linear ? 1 : 2;
  // CPDI: as far as a domain reaches (its half extent F size / 2 along an axis, in cells), and a
  // cell more for the domains to stretch until the next decomposition.
  return std::max(2, static_cast<int>(std::ceil(reach)) + 1);
}

int MPM::computeGhostWidth(bool allHere) const {
  double reach = 0;
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static) reduction(max : reach)
    for (long i = 0; i < n; ++i) reach = std::max(reach, domainReach(p.F[i] * p.size[i]));
  }
  if (!allHere) reach = collective::maximum(reach);
  return ghostWidthFor(reach);
}

void MPM::decompose(bool allHere) {
  ++layoutGeneration_;
  const int ranks = Communicator::size(), me = Communicator::rank();
  if (ranks == 1) {
    decomposition_ = Decomposition(whole_.cells);
    grid_ = whole_;
    layOutGrid();
    return;
  }
  const Decomposition earlier = decomposition_;
  // The boxes drawn before (for this rank count once set up) are the fallback.
  decomposition_ = drawBoxes(particleCounts(allHere), &earlier);
  ghostWidth_ = computeGhostWidth(allHere);
  std::vector<std::string> send(ranks);
  for (MPMMaterial& mat : materials_) {
    ParticleSet& p = mat.particles;
    std::vector<std::vector<long>> to(ranks);
    for (size_t i = 0; i < p.count(); ++i) to[ownerOf(p, i)].push_back(static_cast<long>(i));
    if (!allHere)
      for (int r = 0; r < ranks; ++r)
        if (r != me) packParticles(p, to[r], send[r]);
    keepParticles(p, to[me]);
  }
  if (!allHere) {
    const std::vector<std::string> received = collective::exchangeWithAll(send);
    for (int r = 0; r < ranks; ++r) {
      if (r == me) continue;
      const char* in = received[r].data();
      for (MPMMaterial& mat : materials_) unpackParticles(in, mat.particles);
    }
  }
  layOutWindow();
}

void MPM::layOutWindow() {
  const int me = Communicator::rank();
  grid_ = decomposition_.window(whole_, me, ghostWidth_);
  ghosts_ = GhostNodes(Collective{}, decomposition_, whole_, grid_, me, ghostWidth_);
  layOutGrid();
}

void MPM::redistributeParticles(Collective) {
  decompose(false);
}

double MPM::imbalance(Collective) const {
  const double mine = static_cast<double>(numParticles());
  const double most = collective::maximum(mine), total = collective::sum(mine);
  return total > 0 ? most / (total / Communicator::size()) : 1.0;
}

std::vector<NodeArray> MPM::ghostSumArrays(bool concentrationOnly) {
  std::vector<NodeArray> sums;
  if (!concentrationOnly)  // the rest of P2G's sums stand in a concentration-only P2G
    for (GridFields& g : fields_) {
      sums.push_back({g.mass.data(), 1});
      sums.push_back({g.momentum.data()->data(), 3});
      sums.push_back({g.internalForce.data()->data(), 3});
    }
  if (diffusion_) diffusion_->addScatteredArrays(sums);
  return sums;
}

void MPM::sumGhostNodes(bool concentrationOnly) {
  ghosts_.sumOverRanks(Collective{}, ghostSumArrays(concentrationOnly));
}

std::string MPM::describeDecomposition(int ranks) {
  // From the particles the geom_objects lay out per cell, none of them created (problemSetup
  // without particles): the counts setup draws a run's boxes from.
  const Vec3i& cells = whole_.cells;
  std::vector<double> perCell(static_cast<size_t>(cells.cast<long>().prod()), 0.0);
  double reach = 0;  // of a CPDI domain at the start (F = I), in cells
  for (const MaterialSeeds& seeds : seeds_) {
    seeds.forEachOccupiedCell(whole_, [&](const Vec3i& c, double count) {
      perCell[(static_cast<size_t>(c.z()) * cells.y() + c.y()) * cells.x() + c.x()] += count;
    });
    for (const MaterialSeeds::Object& object : seeds.objects) {
      if (!object.smooth)
        reach = std::max(reach, domainReach(object.res.cast<double>().cwiseInverse().asDiagonal()));
      for (const SmoothParticle& p : object.smoothLayout)
        reach = std::max(reach, domainReach(p.size));
    }
  }
  const Decomposition cuts = Decomposition::balanced(
      cells, ranks, planesOfBoxes(cells, perCell, {CellBox{Vec3i::Zero(), cells}})[0]);
  std::vector<CellBox> tensor;
  for (int r = 0; r < ranks; ++r) tensor.push_back(cuts.box(r));
  // The boxes a run of `ranks` ranks draws.
  std::optional<Decomposition> bisected;
  std::string bisectionError;
  try {
    bisected = Decomposition::bisected(cells, ranks, seedCounts());
  } catch (const std::runtime_error& e) {
    bisectionError = e.what();
  }
  // The values a ghost sum carries per node, from the grid fields laid out on one cell (the
  // whole grid's would take a rank's memory many times over).
  grid_ = Decomposition::fromCuts(
              {std::vector<int>{0, 1, cells.x()}, {0, 1, cells.y()}, {0, 1, cells.z()}})
              .window(whole_, 0, 0);
  layOutGrid();
  int valuesPerNode = 0;
  for (const NodeArray& a : ghostSumArrays()) valuesPerNode += a.width;
  const int ghost = ghostWidthFor(reach);
  std::ostringstream s;
  s << "sus --decompose " << ranks << ": "
    << (bisected ? bisected->describe() : "no boxes: " + bisectionError) << "\n";
  // Per layout: particles per box, imbalance, and the nodes a box stores beyond its own cells
  // (its box grown by the ghost layers within the grid) times the values of a ghost sum.
  const auto describe = [&](const char* name, const std::vector<CellBox>& boxes) {
    const std::vector<double> particles = particlesPerBox(cells, boxes, perCell);
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
      << 8.0 * valuesPerNode * ghostNodes << " bytes of ghost sums a step\n";
  };
  if (bisected) {
    std::vector<CellBox> boxes;
    for (int r = 0; r < ranks; ++r) boxes.push_back(bisected->box(r));
    describe("recursive bisection (what runs use)", boxes);
  }
  describe("tensor-product cuts (measured only)", tensor);
  s << "  ghost layers " << ghost << " cells, " << valuesPerNode << " values a node\n";
  return s.str();
}

void MPM::migrateParticles() {
  const int me = Communicator::rank();
  const std::vector<int>& neighbours = ghosts_.neighbours();
  std::vector<std::string> send(neighbours.size());
  std::vector<std::vector<long>> keep(materials_.size());
  long strayMaterial = -1, stray = -1;
  int strayOwner = -1;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    const long n = static_cast<long>(p.count());
    std::vector<int> owner(n);
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) owner[i] = ownerOf(p, i);
    std::vector<std::vector<long>> leaving(neighbours.size());
    for (long i = 0; i < n; ++i) {
      if (owner[i] == me) {
        keep[m].push_back(i);
        continue;
      }
      const auto q = std::lower_bound(neighbours.begin(), neighbours.end(), owner[i]);
      if (q == neighbours.end() || *q != owner[i]) {
        if (stray < 0) strayMaterial = static_cast<long>(m), stray = i, strayOwner = owner[i];
        keep[m].push_back(i);
        continue;
      }
      leaving[q - neighbours.begin()].push_back(i);
    }
    for (size_t q = 0; q < neighbours.size(); ++q) packParticles(p, leaving[q], send[q]);
  }
  collective::stopTogether([&] {
    if (stray >= 0)
      throw SimulationError(describeParticle(materials_[strayMaterial], strayMaterial, stray) +
                            " moved in one step from rank " + std::to_string(me) +
                            "'s box to rank " + std::to_string(strayOwner) +
                            "'s, beyond the boxes next to it");
  });
  std::vector<std::string> received;
  collective::exchangeWithNeighbours(ghosts_.neighbourhood(), send, received);
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    Reordering& r = reordering_[m];
    r.beforeMigration = p.count();
    r.migrated = keep[m].size() != p.count();
    keepParticles(p, keep[m]);
    r.kept = std::move(keep[m]);
  }
  for (size_t q = 0; q < neighbours.size(); ++q) {
    const char* in = received[q].data();
    for (MPMMaterial& mat : materials_) unpackParticles(in, mat.particles);
  }
  for (size_t m = 0; m < materials_.size(); ++m) {
    Reordering& r = reordering_[m];
    r.arrived = materials_[m].particles.count() - r.kept.size();
    r.migrated = r.migrated || r.arrived > 0;
  }
}

}  // namespace anode
