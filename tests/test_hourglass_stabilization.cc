// Pins the implicit step's hourglass stabilization (Components/MPM/Implicit/
// HourglassStabilization.h): the energy is symmetric positive semi-definite, zero for every
// displacement field linear over the particle's support (linear, GIMP and a sheared CPDI domain),
// and positive for the checkerboard (hourglass) field that one-point sampling cannot see; the
// memory adds up the steps' non-affine displacements and turns with the particle.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "Components/MPM/Implicit/HourglassStabilization.h"

namespace anode {
namespace {

Grid testGrid() {
  Grid g;
  g.lower = Vec3(-1, 0.5, 2);
  g.cells = Vec3i(8, 6, 10);
  g.dx = Vec3(0.5, 1.0, 0.25);  // non-cubic cells
  g.upper = g.lower + g.dx.cwiseProduct(g.cells.cast<double>());
  g.extra = Vec3i(1, 1, 1);
  return g;
}

// One particle's weights as InterpolationWeights.
InterpolationWeights weightsOf(const Grid& g, InterpolatorKind kind, const Vec3& x) {
  InterpolationWeights W;
  W.layOut({64});
  const Mat3 size = 0.5 * Mat3::Identity();  // 2 particles per cell and axis
  Mat3 F = Mat3::Identity();
  F(0, 1) = 0.3;  // sheared
  F(2, 2) = 1.2;
  int n = 0;
  switch (kind) {
    case InterpolatorKind::Linear:
      n = linearWeights(g, x, W.node.data(), W.weight.data(), W.gradient.data());
      break;
    case InterpolatorKind::GIMP:
      n = gimpWeights(g, x, size, W.node.data(), W.weight.data(), W.gradient.data());
      break;
    case InterpolatorKind::CPDI:
      n = cpdiWeights(g, x, size, F, W.node.data(), W.weight.data(), W.gradient.data());
      break;
  }
  W.count[0] = static_cast<uint8_t>(n);
  return W;
}

Vec3 nodeAt(const Grid& g, int32_t node) {
  const Vec3i ijk = g.nodeOf(node);
  return g.nodePosition(ijk.x(), ijk.y(), ijk.z());
}

TEST(HourglassStabilization, EnergyIsZeroForLinearFieldsAndPositiveForHourglassModes) {
  const Grid g = testGrid();
  const Vec3 x(0.63, 2.71, 3.12);
  for (InterpolatorKind kind :
       {InterpolatorKind::Linear, InterpolatorKind::GIMP, InterpolatorKind::CPDI}) {
    SCOPED_TRACE(interpolatorName(kind));
    const InterpolationWeights W = weightsOf(g, kind, x);
    const int n = W.count[0];
    ASSERT_GE(n, 8);
    const Eigen::MatrixXd M = hourglassMatrix(g, W, 0, x);
    ASSERT_EQ(M.rows(), n);
    EXPECT_LE((M - M.transpose()).cwiseAbs().maxCoeff(), 1e-14 * M.cwiseAbs().maxCoeff());
    const Eigen::VectorXd lambda = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues();
    EXPECT_GE(lambda.minCoeff(), -1e-12 * lambda.maxCoeff());
    // A linear field (one displacement component): a + b . x_i.
    Eigen::VectorXd linear(n), checkerboard(n);
    for (int e = 0; e < n; ++e) {
      const Vec3 xi = nodeAt(g, W.node[e]);
      linear[e] = 0.7 - 1.3 * xi.x() + 2.1 * xi.y() + 0.4 * xi.z();
      const Vec3i ijk = g.nodeOf(W.node[e]);
      checkerboard[e] = (ijk.x() + ijk.y() + ijk.z()) % 2 ? 1.0 : -1.0;
    }
    EXPECT_LE((M * linear).cwiseAbs().maxCoeff(), 1e-12 * linear.cwiseAbs().maxCoeff());
    // The checkerboard's energy is a sizeable share of its weighted square (sum S u^2 = 1).
    EXPECT_GT(checkerboard.dot(M * checkerboard), 0.1);
  }
}

// A particle at a cell's centre with linear weights, where the checkerboard field has no gradient:
// two steps of it leave twice its displacement in the memory, a rigid turn then turns it, and the
// memory's nodes outside its box read as zero.
TEST(HourglassStabilization, MemoryAddsTheStepsAndTurnsWithTheParticle) {
  const Grid g = testGrid();
  const Vec3 x = g.nodePosition(3, 2, 4) + 0.5 * g.dx;
  ParticleSet p;
  p.resize(1);
  p.enable(Physics::Hourglass);
  p.x[0] = x;
  const InterpolationWeights W = weightsOf(g, InterpolatorKind::Linear, x);
  const int n = W.count[0];
  ASSERT_EQ(n, 8);
  std::vector<Vec3> checkerboard(g.numNodes(), Vec3::Zero());
  const Vec3 amplitude(1e-3, -2e-3, 0.5e-3);
  for (int e = 0; e < n; ++e) {
    const Vec3i ijk = g.nodeOf(W.node[e]);
    checkerboard[W.node[e]] = ((ijk.x() + ijk.y() + ijk.z()) % 2 ? 1.0 : -1.0) * amplitude;
  }
  rememberNonAffineDisplacement(g, W, checkerboard, p);
  rememberNonAffineDisplacement(g, W, checkerboard, p);
  Eigen::Matrix3Xd m = weightedMemory(p, 0, g, W);
  for (int e = 0; e < n; ++e)
    EXPECT_LE((m.col(e) - 2 * W.weight[e] * checkerboard[W.node[e]]).norm(), 1e-15) << e;
  // A rigid turn about z: linear, so it adds nothing, and the memory turns with it.
  const double angle = 0.3;
  Mat3 turn = Mat3::Identity();
  turn.topLeftCorner<2, 2>() << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  std::vector<Vec3> rigid(g.numNodes(), Vec3::Zero());
  for (int e = 0; e < n; ++e)
    rigid[W.node[e]] = (turn - Mat3::Identity()) * (nodeAt(g, W.node[e]) - x);
  rememberNonAffineDisplacement(g, W, rigid, p);
  m = weightedMemory(p, 0, g, W);
  for (int e = 0; e < n; ++e)
    EXPECT_LE((m.col(e) - 2 * W.weight[e] * turn * checkerboard[W.node[e]]).norm(), 1e-14) << e;
  // The particle in the next cell along x: the nodes it shares keep their memory, the others read
  // zero.
  p.x[0] = x + Vec3(g.dx.x(), 0, 0);
  const InterpolationWeights moved = weightsOf(g, InterpolatorKind::Linear, p.x[0]);
  m = weightedMemory(p, 0, g, moved);
  for (int e = 0; e < moved.count[0]; ++e) {
    const bool shared = g.nodeOf(moved.node[e]).x() == g.nodeOf(W.node[0]).x() + 1;
    EXPECT_EQ(m.col(e).isZero(0), !shared) << e;
  }
}

}  // namespace
}  // namespace anode
