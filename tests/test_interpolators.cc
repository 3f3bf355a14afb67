// Pins the shape functions: partition of unity, gradients summing to zero, exact reproduction of
// a linear field and of its gradient, for linear, GIMP and CPDI (also rotated and sheared).
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "Components/MPM/Interpolator.h"

namespace anode {
namespace {

Grid testGrid() {
  Grid g;
  g.lower = Vec3(-1, 0.5, 2);
  g.cells = Vec3i(8, 6, 10);
  g.dx = Vec3(0.5, 1.0, 0.25);  // non-cubic cells catch index/space mix-ups
  g.upper = g.lower + g.dx.cwiseProduct(g.cells.cast<double>());
  g.extra = Vec3i(1, 1, 1);
  return g;
}

struct Weights {
  int count;
  int32_t node[64];
  double w[64];
  Vec3 grad[64];
};

// Checks sum S = 1, sum grad S = 0, sum S x_i = x_p and sum x_i (grad S)^T = I.
void checkReproduction(const Grid& g, const Vec3& x, const Weights& W, double tol) {
  ASSERT_GT(W.count, 0);
  double sum = 0;
  Vec3 gradSum = Vec3::Zero(), position = Vec3::Zero();
  Mat3 gradOfX = Mat3::Zero();
  for (int e = 0; e < W.count; ++e) {
    const Vec3i ijk = g.nodeOf(W.node[e]);
    const Vec3 xi = g.nodePosition(ijk.x(), ijk.y(), ijk.z());
    sum += W.w[e];
    gradSum += W.grad[e];
    position += W.w[e] * xi;
    gradOfX += xi * W.grad[e].transpose();
    EXPECT_GT(W.w[e], 0.0);
  }
  EXPECT_NEAR(sum, 1.0, tol);
  EXPECT_LT(gradSum.norm(), tol);
  EXPECT_LT((position - x).norm(), tol);
  EXPECT_LT((gradOfX - Mat3::Identity()).norm(), tol);
}

std::vector<Vec3> interiorPoints(const Grid& g, int n) {
  std::mt19937 rng(7);
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    Vec3 u;
    for (int d = 0; d < 3; ++d) u[d] = std::uniform_real_distribution<double>(0.3, 0.7)(rng);
    out.push_back(g.lower + (g.upper - g.lower).cwiseProduct(u));
  }
  return out;
}

TEST(Interpolators, LinearReproducesLinearFields) {
  const Grid g = testGrid();
  for (const Vec3& x : interiorPoints(g, 50)) {
    Weights W;
    W.count = linearWeights(g, x, W.node, W.w, W.grad);
    EXPECT_LE(W.count, 8);
    checkReproduction(g, x, W, 1e-12);
  }
}

TEST(Interpolators, GimpReproducesLinearFields) {
  const Grid g = testGrid();
  for (const Mat3& size :
       {Mat3(Vec3(0.5, 0.5, 0.5).asDiagonal()), Mat3(Vec3(1.0, 0.5, 1.0 / 3).asDiagonal())}) {
    for (const Vec3& x : interiorPoints(g, 50)) {
      Weights W;
      W.count = gimpWeights(g, x, size, W.node, W.w, W.grad);
      EXPECT_LE(W.count, 27);
      checkReproduction(g, x, W, 1e-12);
    }
  }
}

TEST(Interpolators, GimpMatchesTheClosedFormAtANode) {
  // A particle of half-width l centred on a node: S = 1 - l/2 there (per axis).
  const Grid g = testGrid();
  const Vec3 x = g.nodePosition(3, 2, 4);
  Weights W;
  W.count = gimpWeights(g, x, Mat3(Vec3(0.5, 0.5, 0.5).asDiagonal()), W.node, W.w, W.grad);
  const int center = g.nodeIndex(3, 2, 4);
  bool found = false;
  for (int e = 0; e < W.count; ++e)
    if (W.node[e] == center) {
      EXPECT_NEAR(W.w[e], std::pow(1 - 0.25 / 2, 3), 1e-14);
      EXPECT_LT(W.grad[e].norm(), 1e-14);
      found = true;
    }
  EXPECT_TRUE(found);
}

TEST(Interpolators, CpdiReproducesLinearFieldsForRotatedAndShearedDomains) {
  const Grid g = testGrid();
  const Mat3 size = Vec3(0.5, 0.5, 0.5).asDiagonal();
  const Mat3 rotation = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  Mat3 shear = Mat3::Identity();
  shear(0, 1) = 0.6;
  shear(2, 0) = -0.3;
  const Mat3 stretch = Vec3(1.8, 0.6, 1.2).asDiagonal();
  for (const Mat3& F : {Mat3(Mat3::Identity()), rotation, Mat3(rotation * shear * stretch)}) {
    for (const Vec3& x : interiorPoints(g, 50)) {
      Weights W;
      W.count = cpdiWeights(g, x, size, F, W.node, W.w, W.grad);
      EXPECT_LE(W.count, 64);
      checkReproduction(g, x, W, 1e-12);
    }
  }
}

// The nodes of the cells the 8 corners of a CPDI domain fall in, at most 64 (cpdiWeights' span,
// with its floor: a conversion after adding 1024, which rounds a corner within 1e-13 below a
// node plane onto the plane).
int cornerSpan(const Grid& g, const Vec3& x, const Mat3& size, const Mat3& F) {
  const Mat3 A = F * size;
  const Vec3 xi = g.indexCoordinate(x);
  long span = 1;
  for (int d = 0; d < 3; ++d) {
    int lo = 1 << 30, hi = -(1 << 30);
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner = xi + ((c & 1) ? 0.5 : -0.5) * A.col(0) +
                          ((c & 2) ? 0.5 : -0.5) * A.col(1) + ((c & 4) ? 0.5 : -0.5) * A.col(2);
      const int floor = static_cast<int>(corner[d] + 1024.0) - 1024;
      lo = std::min(lo, floor);
      hi = std::max(hi, floor + 1);
    }
    span *= hi - lo + 1;
  }
  return static_cast<int>(std::min(span, 64L));
}

TEST(Interpolators, CpdiCapacityIsTheSpanOfTheCorners) {
  // The storage laid out per particle (cpdiCapacity) is never below the entries cpdiWeights
  // writes and not above the nodes of the cells its corners fall in: random rotated, sheared
  // and stretched domains, and axis-aligned ones with corners exactly on node planes (a grid
  // fill's particles), where a bound with a margin would lay out 27 entries for 8.
  const Grid g = testGrid();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int onPlanes = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    Mat3 F = Mat3::Identity();
    for (int k = 0; k < 9; ++k) F(k) += 0.6 * u(rng);
    if (F.determinant() < 0.2) continue;
    const Mat3 size = Vec3(0.5, 0.25, 1.0 / 3).asDiagonal();
    Vec3 x = 0.5 * (g.lower + g.upper) + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(g.dx);
    if (trial % 2 == 0) {
      F = Mat3::Identity();
      x = g.nodePosition(4, 3, 5) + 0.5 * size.diagonal().cwiseProduct(g.dx);
      x[trial % 3] += g.dx[trial % 3] * (trial % 7) / 4.0;
      ++onPlanes;
    }
    Weights W;
    std::fill_n(W.node, 64, -7);  // cpdiWeights may write past its count, never past capacity
    W.count = cpdiWeights(g, x, size, F, W.node, W.w, W.grad);
    ASSERT_GT(W.count, 0);
    const int capacity = cpdiCapacity(g, x, size, F);
    ASSERT_GE(capacity, W.count) << "trial " << trial;
    ASSERT_EQ(capacity, cornerSpan(g, x, size, F)) << "trial " << trial;
    for (int e = capacity; e < 64; ++e) ASSERT_EQ(W.node[e], -7) << "trial " << trial;
  }
  EXPECT_GT(onPlanes, 1000);
  // Half a cell wide, inside one cell: its 8 nodes; across a node plane on every axis: 27.
  const Mat3 size = Vec3(0.5, 0.5, 0.5).asDiagonal();
  EXPECT_EQ(cpdiCapacity(g, g.nodePosition(4, 3, 5) + 0.5 * g.dx, size, Mat3::Identity()), 8);
  EXPECT_EQ(cpdiCapacity(g, g.nodePosition(4, 3, 5) + 0.25 * g.dx, size, Mat3::Identity()), 8);
  EXPECT_EQ(cpdiCapacity(g, g.nodePosition(4, 3, 5), size, Mat3::Identity()), 27);
}

TEST(Interpolators, CpdiCornersOfAPackAreEachParticlesOwn) {
  // The corners computed for Pack::size() particles at once are bit for bit those of each one
  // alone, so the weights do not depend on the pack a particle is in.
  const Grid g = testGrid();
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  constexpr int lanes = static_cast<int>(Pack::size());
  for (int trial = 0; trial < 200; ++trial) {
    Vec3 x[lanes];
    Mat3 size[lanes], F[lanes];
    for (int l = 0; l < lanes; ++l) {
      F[l] = Mat3::Identity();
      for (int k = 0; k < 9; ++k) F[l](k) += 0.6 * u(rng);
      size[l] = Vec3(0.5 + u(rng), 0.5 + u(rng), 0.5 + u(rng)).asDiagonal();
      x[l] = 0.5 * (g.lower + g.upper) + Vec3(u(rng), u(rng), u(rng)).cwiseProduct(g.dx);
    }
    CpdiCorners pack[lanes];
    cpdiCornersOfPack(g, x, size, F, pack);
    for (int l = 0; l < lanes; ++l) {
      CpdiCorners one;
      cpdiCorners(g, x[l], size[l], F[l], one);
      for (int c = 0; c < 8; ++c)
        for (int d = 0; d < 3; ++d) {
          ASSERT_EQ(pack[l].cell[c][d], one.cell[c][d]);
          ASSERT_EQ(pack[l].inCell[c][d], one.inCell[c][d]);
          ASSERT_EQ(pack[l].alpha[c][d], one.alpha[c][d]);
        }
      for (int d = 0; d < 3; ++d) {
        ASSERT_EQ(pack[l].lowest[d], one.lowest[d]);
        ASSERT_EQ(pack[l].highest[d], one.highest[d]);
      }
      Weights a, b;
      a.count = cpdiWeights(g, pack[l], a.node, a.w, a.grad);
      b.count = cpdiWeights(g, x[l], size[l], F[l], b.node, b.w, b.grad);
      ASSERT_EQ(a.count, b.count);
      for (int e = 0; e < a.count; ++e) {
        ASSERT_EQ(a.node[e], b.node[e]);
        ASSERT_EQ(a.w[e], b.w[e]);
        ASSERT_EQ(a.grad[e], b.grad[e]);
      }
    }
  }
}

TEST(Interpolators, CpdiStretchedOverManyCellsStillPartitionsUnity) {
  // A domain spanning more than three cells per axis takes the unmerged path.
  const Grid g = testGrid();
  const Mat3 size = Vec3(0.5, 0.5, 0.5).asDiagonal();
  const Mat3 F = Vec3(9.0, 1.0, 1.0).asDiagonal();
  const Vec3 x = 0.5 * (g.lower + g.upper);
  Weights W;
  W.count = cpdiWeights(g, x, size, F, W.node, W.w, W.grad);
  checkReproduction(g, x, W, 1e-12);
}

TEST(Interpolators, CpdiGradientIsTheFaceDifferenceForAnAxisAlignedBox) {
  // For an axis-aligned domain the gradient is (mean over +face - mean over -face)/edge.
  const Grid g = testGrid();
  const Mat3 size = Vec3(0.5, 0.5, 0.5).asDiagonal();
  const Vec3 x = g.nodePosition(4, 3, 5) + Vec3(0.1, 0.2, 0.05);
  Weights W;
  W.count = cpdiWeights(g, x, size, Mat3::Identity(), W.node, W.w, W.grad);
  // Check one node against direct evaluation of linear shape functions at the corners.
  const int node = g.nodeIndex(4, 3, 5);
  const Vec3 xi = g.indexCoordinate(x);
  auto hat = [&](const Vec3& p) {
    const Vec3 r = p - Vec3(4, 3, 5);
    return std::max(0.0, 1 - std::abs(r.x())) * std::max(0.0, 1 - std::abs(r.y())) *
           std::max(0.0, 1 - std::abs(r.z()));
  };
  double plus = 0, minus = 0;
  for (int b = 0; b < 2; ++b)
    for (int c = 0; c < 2; ++c) {
      const Vec3 off(0, (b - 0.5) * 0.5, (c - 0.5) * 0.5);
      plus += hat(xi + Vec3(0.25, 0, 0) + off) / 4;
      minus += hat(xi - Vec3(0.25, 0, 0) + off) / 4;
    }
  bool found = false;
  for (int e = 0; e < W.count; ++e) {
    if (W.node[e] != node) continue;
    EXPECT_NEAR(W.grad[e].x(), (plus - minus) / (0.5 * g.dx.x()), 1e-12);
    found = true;
  }
  EXPECT_TRUE(found);
}

TEST(Interpolators, ReportParticlesBeyondTheGrid) {
  const Grid g = testGrid();
  Weights W;
  const Vec3 outside = g.upper + Vec3(0.9, 0, 0);
  EXPECT_EQ(linearWeights(g, outside, W.node, W.w, W.grad), -1);
  EXPECT_EQ(gimpWeights(g, outside, Mat3::Identity() * 0.5, W.node, W.w, W.grad), -1);
  EXPECT_EQ(cpdiWeights(g, outside, Mat3::Identity() * 0.5, Mat3::Identity(), W.node, W.w, W.grad),
            -1);
}

}  // namespace
}  // namespace anode
