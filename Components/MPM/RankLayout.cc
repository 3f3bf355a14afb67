#include "Components/MPM/RankLayout.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "Components/MPM/ParticleMigration.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

void putInIdOrder(std::vector<MPMMaterial>& materials) {
  for (MPMMaterial& mat : materials) {
    ParticleSet& p = mat.particles;
    std::vector<long> order(p.count());
    std::iota(order.begin(), order.end(), 0L);
    std::sort(order.begin(), order.end(), [&p](long a, long b) { return p.id[a] < p.id[b]; });
    reorderParticles(p, order);
  }
}

}  // namespace

RankLayout::RankLayout(std::vector<MPMMaterial>& materials, std::function<void()> windowChanged)
    : materials_(materials), windowChanged_(std::move(windowChanged)) {}

void RankLayout::setProblemGrid(const Grid& whole, InterpolatorKind interpolator) {
  whole_ = whole;
  window_ = whole;
  interpolator_ = interpolator;
  distributed_ = Communicator::size() > 1;
}

int RankLayout::ownerOf(const ParticleSet& p, size_t i) const {
  return decomposition_.ownerOfPoint(whole_.indexCoordinate(p.x[i]), Communicator::rank());
}

CellBox RankLayout::drawSetupBoxes(const Decomposition::ParticleCounts& seeds) {
  const int ranks = Communicator::size();
  if (ranks == 1) return {Vec3i::Zero(), whole_.cells};
  // Counted before any particle is stored: the same on every rank, and the same boxes a fill of
  // everything gives.
  decomposition_ = drawBoxes(seeds, nullptr);
  return decomposition_.box(Communicator::rank());
}

void RankLayout::completeSetup(Collective every) {
  if (Communicator::size() == 1) {
    decompose(every, true);
    return;
  }
  // Setup drew the boxes and placed each rank's particles in its own.
  ++generation_;
  ghostWidth_ = computeGhostWidth(every, false);
  layOutWindow(every);
}

Decomposition::ParticleCounts RankLayout::particleCounts(Collective every, bool allHere) const {
  Decomposition::ParticleCounts counts;
  counts.forEach = [this](const std::function<void(const Vec3i&, double)>& add) {
    for (const MPMMaterial& mat : materials_)
      for (const Vec3& x : mat.particles.x) add(whole_.interiorCell(x), 1.0);
  };
  // The counts of every rank's particles: one sum over the ranks.
  if (!allHere)
    counts.sumOverRanks = [every](std::vector<double>& v) {
      collective::sum(every, v.data(), static_cast<int>(v.size()));
    };
  return counts;
}

Decomposition RankLayout::drawBoxes(const Decomposition::ParticleCounts& counts,
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

int RankLayout::ghostWidthFor(double reach) const {
  if (interpolator_ != InterpolatorKind::CPDI)
    return interpolator_ == InterpolatorKind::Linear ? 1 : 2;
  // CPDI: as far as a domain reaches (its half extent F size / 2 along an axis, in cells), and a
  // cell more for the domains to stretch until the next decomposition.
  return std::max(2, static_cast<int>(std::ceil(reach)) + 1);
}

int RankLayout::computeGhostWidth(Collective every, bool allHere) const {
  double reach = 0;
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static) reduction(max : reach)
    for (long i = 0; i < n; ++i) reach = std::max(reach, domainReach(p.F[i] * p.size[i]));
  }
  if (!allHere) reach = collective::maximum(every, reach);
  return ghostWidthFor(reach);
}

void RankLayout::decompose(Collective every, bool allHere) {
  ++generation_;
  const int ranks = Communicator::size(), me = Communicator::rank();
  if (ranks == 1) {
    decomposition_ = Decomposition(whole_.cells);
    useWindow(whole_);
    return;
  }
  const Decomposition earlier = decomposition_;
  // The boxes drawn before (for this rank count once set up) are the fallback.
  decomposition_ = drawBoxes(particleCounts(every, allHere), &earlier);
  ghostWidth_ = computeGhostWidth(every, allHere);
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
    const std::vector<std::string> received = collective::exchangeWithAll(every, send);
    for (int r = 0; r < ranks; ++r) {
      if (r == me) continue;
      const char* in = received[r].data();
      for (MPMMaterial& mat : materials_) unpackParticles(in, mat.particles);
    }
  }
  layOutWindow(every);
}

void RankLayout::layOutWindow(Collective every) {
  const int me = Communicator::rank();
  window_ = decomposition_.window(whole_, me, ghostWidth_);
  ghosts_ = GhostNodes(every, decomposition_, whole_, window_, me, ghostWidth_);
  windowChanged_();
}

void RankLayout::useWindow(const Grid& window) {
  window_ = window;
  windowChanged_();
}

void RankLayout::redistributeParticles(Collective every) {
  decompose(every, false);
}

double RankLayout::imbalance(Collective every) const {
  const double mine = static_cast<double>(countParticles(materials_));
  const double most = collective::maximum(every, mine), total = collective::sum(every, mine);
  return total > 0 ? most / (total / Communicator::size()) : 1.0;
}

void RankLayout::migrateParticles(Collective every, std::vector<ParticleReordering>& reordering) {
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
  collective::stopTogether(every, [&] {
    if (stray >= 0)
      throw SimulationError(describeParticle(materials_[strayMaterial], strayMaterial, stray) +
                            " moved in one step from rank " + std::to_string(me) +
                            "'s box to rank " + std::to_string(strayOwner) +
                            "'s, beyond the boxes next to it");
  });
  std::vector<std::string> received;
  collective::exchangeWithNeighbours(every, ghosts_.neighbourhood(), send, received);
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    ParticleReordering& r = reordering[m];
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
    ParticleReordering& r = reordering[m];
    r.arrived = materials_[m].particles.count() - r.kept.size();
    r.migrated = r.migrated || r.arrived > 0;
  }
}

void RankLayout::save(BinaryWriter& out) const {
  decomposition_.save(out);
  out.value<int32_t>(ghostWidth_);
}

RankLayout::Saved RankLayout::read(BinaryReader& in) {
  Saved saved;
  saved.boxes = Decomposition::load(in);
  saved.ghostWidth = in.value<int32_t>();
  return saved;
}

void RankLayout::adopt(Collective every, const Saved& saved) {
  ghostWidth_ = saved.ghostWidth;
  if (saved.boxes.cells() != whole_.cells || saved.boxes.ranks() != Communicator::size())
    throw std::runtime_error("the checkpoint's boxes are for another grid or rank count");
  decomposition_ = saved.boxes;
  layOutWindow(every);
}

void RankLayout::keepOwnShare(Collective every) {
  putInIdOrder(materials_);
  decompose(every, true);
}

void RankLayout::shareOutAnew(Collective every) {
  decompose(every, false);
  putInIdOrder(materials_);
}

}  // namespace anode
