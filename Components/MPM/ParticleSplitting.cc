#include "Components/MPM/ParticleSplitting.h"

#include <omp.h>

#include <cmath>
#include <type_traits>

namespace anode {

int splitAxis(const Mat3& domain, double ratio, int ndim) {
  const double l1 = domain.col(0).squaredNorm(), l2 = domain.col(1).squaredNorm(),
               l3 = domain.col(2).squaredNorm(), s2 = ratio * ratio;
  if (l1 > s2 * l2) return 0;
  if (l2 > s2 * l1) return 1;
  if (ndim < 3) return -1;
  if (l1 > s2 * l3) return 0;
  if (l3 > s2 * l1) return 2;
  if (l2 > s2 * l3) return 1;
  if (l3 > s2 * l2) return 2;
  return -1;
}

namespace {

// The edge particle i splits along now, or -1.
int splitAxisOf(const ParticleSet& p, size_t i, const Grid& grid, double ratio) {
  return p.refined[i] ? -1
                      : splitAxis(p.F[i] * p.size[i] * grid.dx.asDiagonal(), ratio, grid.ndim());
}

}  // namespace

std::vector<int64_t> stretchedParticleIds(const ParticleSet& p, const Grid& grid, double ratio) {
  std::vector<int64_t> ids;
  for (size_t i = 0; i < p.count(); ++i)
    if (splitAxisOf(p, i, grid, ratio) >= 0) ids.push_back(p.id[i]);
  return ids;
}

std::vector<SplitParticle> splitStretchedParticles(ParticleSet& p, const Grid& grid, double ratio,
                                                   int64_t& nextId) {
  return splitStretchedParticles(p, grid, ratio, [&nextId](int64_t) {
    const int64_t first = nextId;
    nextId += 3;
    return first;
  });
}

std::vector<SplitParticle> splitStretchedParticles(
    ParticleSet& p, const Grid& grid, double ratio,
    const std::function<int64_t(int64_t)>& firstChildId) {
  const long n = static_cast<long>(p.count());
  // The particles that split and along which edge. Each thread lists those of its own block of
  // indices, and the blocks follow in index order. Most steps list none.
  std::vector<std::vector<std::pair<long, int>>> found(omp_get_max_threads());
#pragma omp parallel
  {
    // The team may be smaller than asked for (OMP_DYNAMIC, a thread limit): its size splits.
    const int t = omp_get_thread_num(), threads = omp_get_num_threads();
    for (long i = n * t / threads; i < n * (t + 1) / threads; ++i)
      if (const int axis = splitAxisOf(p, i, grid, ratio); axis >= 0)
        found[t].emplace_back(i, axis);
  }
  std::vector<std::pair<long, int>> splits;
  for (const auto& f : found) splits.insert(splits.end(), f.begin(), f.end());
  if (splits.empty()) return {};
  // Each array grows at most once per step, with 1/16 to spare: splits come a few at a time over
  // many steps, and growing each time to the exact size would copy every array at each of them.
  const size_t needed = n + 3 * splits.size();
  p.forEachArray([&](auto& v) {
    if (!v.empty() && v.capacity() < needed) v.reserve(needed + needed / 16);
  });
  std::vector<SplitParticle> done(splits.size());
  for (size_t k = 0; k < splits.size(); ++k) {
    const auto [i, axis] = splits[k];
    const Vec3 edge = (p.F[i] * p.size[i] * grid.dx.asDiagonal()).col(axis);
    const Vec3 x = p.x[i];
    p.forEachField([i](auto& v, const auto& field) {
      if constexpr (std::is_same_v<typename std::decay_t<decltype(v)>::value_type, double>)
        if (field.split == OnSplit::Quarter) v[i] *= 0.25;
    });
    p.size[i].col(axis) *= 0.25;
    p.refined[i] = 1;
    // Children at x -/+ 0.375 and 0.125 of the edge; the parent becomes the first.
    static const double offsets[4] = {-0.375, -0.125, 0.125, 0.375};
    size_t* child = done[k].child;
    Vec3* offset = done[k].offset;
    child[0] = static_cast<size_t>(i);
    const int64_t firstId = firstChildId(p.id[i]);
    for (int c = 1; c < 4; ++c) {
      child[c] = p.duplicate(i);
      p.id[child[c]] = firstId + c - 1;
    }
    for (int c = 0; c < 4; ++c) {
      offset[c] = offsets[c] * edge;
      p.x[child[c]] = x + offset[c];
    }
    done[k].direction = edge.normalized();
  }
  return done;
}

}  // namespace anode
