// Pins the cell means the swelling of <swelling_strain>cell_mean takes (Components/MPM/Implicit/
// CellMeanSwelling.h): a uniform value is left as it is, the sum of V times the value is kept to
// round-off, the particles of one cell share its volume-weighted mean, and a particle whose
// domain lies across a face takes each cell's mean by its share.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "Components/MPM/Implicit/CellMeanSwelling.h"

namespace anode {
namespace {

// A grid of 4 x 4 x 4 cells of edge 0.5 and the arrays the cell means read.
Grid fourCells() {
  Grid g;
  g.cells = Vec3i(4, 4, 4);
  g.dx = Vec3(0.5, 0.5, 0.5);
  g.upper = g.lower + g.dx.cwiseProduct(g.cells.cast<double>());
  g.extra = Vec3i(1, 1, 1);
  return g;
}

ParticleSet particlesAt(const std::vector<Vec3>& x, const std::vector<double>& volume,
                        double sizeInCells) {
  ParticleSet p;
  p.resize(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    p.x[i] = x[i];
    p.volume[i] = volume[i];
    p.size[i] = sizeInCells * Mat3::Identity();
  }
  return p;
}

std::vector<double> cellMeans(const Grid& g, const ParticleSet& p, const std::vector<double>& c) {
  std::vector<double> mean;
  cellMeanOf(Communicator::everyRank(), g, nullptr, p, c, mean);
  return mean;
}

TEST(CellMeanSwelling, UniformValueIsLeftAndTheSumOfVolumeTimesValueKept) {
  const Grid g = fourCells();
  std::mt19937 random(3);
  std::uniform_real_distribution<double> inside(0.05, 1.95), volume(0.5, 2), shear(-0.3, 0.3);
  std::vector<Vec3> x;
  std::vector<double> v, c;
  for (int i = 0; i < 200; ++i) {
    x.push_back(Vec3(inside(random), inside(random), inside(random)));
    v.push_back(volume(random));
    c.push_back(inside(random) - 1);
  }
  ParticleSet p = particlesAt(x, v, 0.5);
  for (Mat3& F : p.F) F = Mat3::Identity() + Mat3::NullaryExpr([&] { return shear(random); });
  const std::vector<double> uniform = cellMeans(g, p, std::vector<double>(x.size(), 0.0375));
  for (double s : uniform) EXPECT_NEAR(s, 0.0375, 1e-15);
  const std::vector<double> mean = cellMeans(g, p, c);
  double before = 0, after = 0, changed = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    before += v[i] * c[i];
    after += v[i] * mean[i];
    changed = std::max(changed, std::abs(mean[i] - c[i]));
  }
  EXPECT_NEAR(after, before, 1e-12 * std::abs(before) + 1e-13);
  EXPECT_GT(changed, 0.1);  // the means differ from the particles' own values
}

TEST(CellMeanSwelling, ParticlesOfOneCellShareItsMeanAndOneAcrossAFaceTakesBoth) {
  const Grid g = fourCells();
  // Two particles inside cell (1, 1, 1) (domains of a tenth of a cell), two inside cell (2, 1, 1),
  // and one of half a cell centred on the face x = 1 between them.
  const std::vector<Vec3> x = {Vec3(0.6, 0.7, 0.7), Vec3(0.9, 0.8, 0.7), Vec3(1.1, 0.7, 0.7),
                               Vec3(1.4, 0.7, 0.7), Vec3(1.0, 0.75, 0.75)};
  const std::vector<double> v = {1, 3, 2, 2, 4};
  const std::vector<double> c = {0.1, 0.3, -0.2, 0.2, 0.5};
  ParticleSet p = particlesAt(x, v, 0.1);
  p.size[4] = 0.5 * Mat3::Identity();
  const std::vector<double> s = cellMeans(g, p, c);
  // Each cell: its two particles, and half the volume of the one across the face.
  const double lower = (1 * 0.1 + 3 * 0.3 + 2 * 0.5) / (1 + 3 + 2);
  const double upper = (2 * -0.2 + 2 * 0.2 + 2 * 0.5) / (2 + 2 + 2);
  EXPECT_NEAR(s[0], lower, 1e-15);
  EXPECT_NEAR(s[1], lower, 1e-15);
  EXPECT_NEAR(s[2], upper, 1e-15);
  EXPECT_NEAR(s[3], upper, 1e-15);
  EXPECT_NEAR(s[4], 0.5 * (lower + upper), 1e-15);
}

}  // namespace
}  // namespace anode
