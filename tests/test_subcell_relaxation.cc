// Pins the sub-cell relaxation of the particles' concentration (Components/MPM/ReactiveFlow/
// SubcellRelaxation.h): it conserves the lithium to round-off, leaves a field the grid resolves
// exactly (linear) untouched, makes no new extremes, damps a particle's difference from its
// neighbours by sum S a, and smooths a quadratic field as the diffusivity eps D it states (one and
// two particles per cell and axis).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include "Components/MPM/ReactiveFlow/SubcellRelaxation.h"

namespace anode {
namespace {

// Particles of equal mass filling a 6 x 6 x 6 grid of cells of edge 0.5, `perAxis` per cell and
// axis, with linear weights, c from `field`, and the P2G of their mass and c.
struct Cloud {
  Grid grid;
  InterpolationWeights W;
  std::vector<Vec3> x;
  std::vector<double> mass, c, diffusivity, nodeMass, nodeConcentration;

  Cloud(int perAxis, const std::function<double(const Vec3&)>& field) {
    grid.lower = Vec3::Zero();
    grid.cells = Vec3i(6, 6, 6);
    grid.dx = Vec3(0.5, 0.5, 0.5);
    grid.upper = grid.lower + grid.dx.cwiseProduct(grid.cells.cast<double>());
    grid.extra = Vec3i(1, 1, 1);
    const int n = 6 * perAxis;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          x.push_back((Vec3(i, j, k) + Vec3::Constant(0.5)) * (0.5 / perAxis));
    W.layOut(std::vector<uint8_t>(x.size(), 8));
    for (size_t p = 0; p < x.size(); ++p) {
      const size_t b = W.offset[p];
      W.count[p] =
          static_cast<uint8_t>(linearWeights(grid, x[p], &W.node[b], &W.weight[b], &W.gradient[b]));
      mass.push_back(1.0);
      c.push_back(field(x[p]));
      diffusivity.push_back(1.0);
    }
    interpolate();
  }
  void interpolate() {
    nodeMass.assign(grid.numNodes(), 0.0);
    nodeConcentration.assign(grid.numNodes(), 0.0);
    for (size_t p = 0; p < x.size(); ++p)
      for (int e = 0; e < W.count[p]; ++e) {
        const size_t b = W.offset[p] + e;
        nodeMass[W.node[b]] += W.weight[b] * mass[p];
        nodeConcentration[W.node[b]] += W.weight[b] * mass[p] * c[p];
      }
    for (size_t k = 0; k < nodeMass.size(); ++k)
      if (nodeMass[k] > 0) nodeConcentration[k] /= nodeMass[k];
  }
  // One relaxation over dt; returns each particle's change.
  std::vector<double> relax(double dt) {
    std::vector<double> nodeMD, change(x.size(), 0.0);
    scatterMassDiffusivity(mass, diffusivity, W, nodeMass.size(), nodeMD);
    std::vector<double> nodeMassConcentration(nodeMass.size());
    for (size_t k = 0; k < nodeMass.size(); ++k)
      nodeMassConcentration[k] = nodeMass[k] * nodeConcentration[k];
    relaxSubcellDifferences(c, W, nodeMassConcentration, nodeMass, nodeMD,
                            subcellRelaxationPerDiffusivity(dt, grid.dx.maxCoeff()), change);
    return change;
  }
  double lithium() const { return std::inner_product(mass.begin(), mass.end(), c.begin(), 0.0); }
  bool interior(size_t p) const { return (x[p].array() > 1.0).all() && (x[p].array() < 2.0).all(); }
};

TEST(SubcellRelaxation, ConservesLithiumAndMakesNoNewExtremes) {
  // A step in c (a front) and a varying D: every node draws with its own a_i.
  Cloud cloud(2, [](const Vec3& x) { return x.x() + 0.3 * x.y() > 1.4 ? 0.9 : 0.05; });
  for (size_t p = 0; p < cloud.x.size(); ++p) cloud.diffusivity[p] = 1 + 5 * cloud.x[p].z();
  const double before = cloud.lithium();
  cloud.relax(2.0);
  EXPECT_NEAR(cloud.lithium(), before, 1e-13 * before);
  const auto [low, high] = std::minmax_element(cloud.c.begin(), cloud.c.end());
  EXPECT_GE(*low, 0.05 - 1e-15);
  EXPECT_LE(*high, 0.9 + 1e-15);
  // The particles beside the front moved towards each other.
  EXPECT_GT(std::count_if(cloud.c.begin(), cloud.c.end(),
                          [](double c) { return c > 0.051 && c < 0.899; }),
            0);
}

TEST(SubcellRelaxation, LeavesALinearFieldInsideTheBody) {
  Cloud cloud(2, [](const Vec3& x) { return 0.1 + 0.2 * x.x() - 0.05 * x.y() + 0.1 * x.z(); });
  const std::vector<double> change = cloud.relax(1.0);
  int checked = 0;
  for (size_t p = 0; p < cloud.x.size(); ++p) {
    if (!cloud.interior(p)) continue;
    EXPECT_NEAR(change[p], 0.0, 1e-15) << "particle " << p;
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST(SubcellRelaxation, DampsAParticlesDifferenceFromItsNeighbours) {
  // A uniform field with one particle 0.1 below: it rises by a (0.1 - its share of the nodes'
  // dip); with D dt large, a = 1.
  for (double dt : {0.5, 1e6}) {
    Cloud cloud(2, [](const Vec3&) { return 0.5; });
    size_t low = 0;
    while (!cloud.interior(low)) ++low;
    cloud.c[low] = 0.4;
    cloud.interpolate();
    const double interpolated = [&] {
      double s = 0;
      for (int e = 0; e < cloud.W.count[low]; ++e) {
        const size_t b = cloud.W.offset[low] + e;
        s += cloud.W.weight[b] * cloud.nodeConcentration[cloud.W.node[b]];
      }
      return s;
    }();
    const double a = std::min(1.0, subcellRelaxationPerDiffusivity(dt, 0.5));
    const std::vector<double> change = cloud.relax(dt);
    EXPECT_NEAR(change[low], a * (interpolated - 0.4), 1e-15) << "dt " << dt;
    EXPECT_GT(change[low], 0.0);
    if (dt > 1) {
      EXPECT_GT(change[low], 0.09);  // nearly all of the difference
    }
  }
}

TEST(SubcellRelaxation, SmoothsAQuadraticFieldAsItsStatedDiffusivity) {
  // c = x^2: lap c = 2, so an interior particle's change over dt is D_added dt 2; the header
  // states D_added = eps D with one particle per cell and axis and 3/4 of it with two.
  const double dt = 0.01;  // a = 4 eps D dt / dx^2 < 1
  for (const auto& [perAxis, share] : {std::pair{1, 1.0}, std::pair{2, 0.75}}) {
    Cloud cloud(perAxis, [](const Vec3& x) { return x.x() * x.x(); });
    const std::vector<double> change = cloud.relax(dt);
    for (size_t p = 0; p < cloud.x.size(); ++p) {
      if (!cloud.interior(p)) continue;
      EXPECT_NEAR(change[p] / (2 * dt), share * kSubcellRelaxationShare,
                  1e-12 * kSubcellRelaxationShare)
          << perAxis << " per axis, particle " << p;
    }
  }
}

}  // namespace
}  // namespace anode
