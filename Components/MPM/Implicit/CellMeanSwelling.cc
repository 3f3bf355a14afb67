#include "Components/MPM/Implicit/CellMeanSwelling.h"

#include <algorithm>
#include <cmath>

namespace anode {

namespace {

// The cells [first, last] of one axis a particle's box [a, b] (index space) overlaps, among the
// cells whose lowest node is stored here ([lowest, highest]), and its share in each. A box of no
// width lies in one cell.
struct AxisOverlap {
  int first = 0, last = -1;
  double a = 0, b = 0;
  double share(int cell) const {
    if (first == last) return 1;
    return std::max(0.0, std::min(b, cell + 1.0) - std::max(a, double(cell))) / (b - a);
  }
};

AxisOverlap overlapOnAxis(double centre, double half, int lowest, int highest) {
  AxisOverlap o;
  o.a = centre - half;
  o.b = centre + half;
  o.first = std::clamp(static_cast<int>(std::floor(o.a)), lowest, highest);
  o.last = std::clamp(static_cast<int>(std::floor(o.b)), lowest, highest);
  // A box reaching past the stored cells (the grid's outer layers) shares what lies within them.
  if (o.first < o.last) {
    o.a = std::max(o.a, double(o.first));
    o.b = std::min(o.b, o.last + 1.0);
  }
  return o;
}

struct Overlap {
  AxisOverlap axis[3];
  template <class F>
  void forEachCell(F f) const {
    for (int k = axis[2].first; k <= axis[2].last; ++k)
      for (int j = axis[1].first; j <= axis[1].last; ++j)
        for (int i = axis[0].first; i <= axis[0].last; ++i)
          f(i, j, k, axis[0].share(i) * axis[1].share(j) * axis[2].share(k));
  }
};

Overlap overlapOf(const Grid& grid, const ParticleSet& p, size_t q) {
  const Mat3 A = p.F[q] * p.size[q];  // the domain's edges in index space (CpdiCorners.h)
  const Vec3 centre = grid.indexCoordinate(p.x[q]);
  const Vec3i lowest = grid.firstNode(), highest = grid.lastNode() - Vec3i::Ones();
  Overlap o;
  for (int a = 0; a < 3; ++a)
    o.axis[a] = overlapOnAxis(centre[a], 0.5 * A.row(a).cwiseAbs().sum(), lowest[a], highest[a]);
  return o;
}

}  // namespace

void cellMeanOf(Collective every, const Grid& grid, GhostNodes* ghosts, const ParticleSet& p,
                const std::vector<double>& values, std::vector<double>& mean) {
  // Per cell, at its lowest node: sum w V value and sum w V, in the particles' order (the same
  // sums on every run).
  std::vector<double> sums(2 * static_cast<size_t>(grid.numNodes()), 0.0);
  const long n = static_cast<long>(p.count());
  for (long q = 0; q < n; ++q)
    overlapOf(grid, p, q).forEachCell([&](int i, int j, int k, double share) {
      double* cell = &sums[2 * static_cast<size_t>(grid.nodeIndex(i, j, k))];
      cell[0] += share * p.volume[q] * values[q];
      cell[1] += share * p.volume[q];
    });
  if (ghosts) ghosts->sumOverRanks(every, {{sums.data(), 2}});
  mean.resize(n);
#pragma omp parallel for schedule(static)
  for (long q = 0; q < n; ++q) {
    double sum = 0;
    overlapOf(grid, p, q).forEachCell([&](int i, int j, int k, double share) {
      const double* cell = &sums[2 * static_cast<size_t>(grid.nodeIndex(i, j, k))];
      if (share > 0) sum += share * cell[0] / cell[1];
    });
    mean[q] = sum;
  }
}

}  // namespace anode
