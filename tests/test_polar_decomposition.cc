// Pins the polar decomposition F = R U (paper Eq. 26, Core/Math/PolarDecomposition.h): R proper
// orthogonal and U = R^T F symmetric positive definite, for random and for known factors.
#include <gtest/gtest.h>

#include <random>

#include "Core/Math/PolarDecomposition.h"

namespace anode {
namespace {

TEST(PolarDecomposition, RecoversRotationAndSymmetricStretch) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  int tested = 0;
  while (tested < 200) {
    Mat3 F = Mat3::Identity();
    for (int i = 0; i < 9; ++i) F(i / 3, i % 3) += 0.8 * u(rng);
    if (F.determinant() < 0.05) continue;
    ++tested;
    const Mat3 R = rotationOf(F), U = R.transpose() * F;
    EXPECT_LT((R * R.transpose() - Mat3::Identity()).norm(), 1e-13);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-13);
    EXPECT_LT((U - U.transpose()).norm(), 1e-13 * U.norm());
    EXPECT_GT(
        Eigen::SelfAdjointEigenSolver<Mat3>(0.5 * (U + U.transpose())).eigenvalues().minCoeff(),
        0.0);
  }
}

TEST(PolarDecomposition, KnownRotationTimesStretch) {
  const Mat3 R = Eigen::AngleAxisd(1.1, Vec3(0.2, -1, 0.5).normalized()).toRotationMatrix();
  Mat3 U;
  U << 2.0, 0.3, 0.1, 0.3, 0.5, -0.2, 0.1, -0.2, 1.4;
  const Mat3 found = rotationOf(R * U);
  EXPECT_LT((found - R).norm(), 1e-13);
  EXPECT_LT((found.transpose() * R * U - U).norm(), 1e-13);
}

TEST(PolarDecomposition, PureStretchAndPureRotation) {
  // A symmetric positive definite F has R = I; a rotation has R = F.
  EXPECT_LT((rotationOf(Vec3(3, 0.5, 1.2).asDiagonal().toDenseMatrix()) - Mat3::Identity()).norm(),
            1e-15);
  const Mat3 Q = Eigen::AngleAxisd(2.5, Vec3(1, 1, 0).normalized()).toRotationMatrix();
  EXPECT_LT((rotationOf(Q) - Q).norm(), 1e-14);
}

TEST(PolarDecomposition, SimpleShearHasTheClosedFormRotation) {
  // F = I + g e1 e2^T: R is the rotation about z by theta with tan(theta) = -g/2 (a standard
  // result: R = [[c, s, 0], [-s, c, 0], [0, 0, 1]], c = 2/sqrt(4 + g^2), s = g/sqrt(4 + g^2)).
  const double g = 0.8;
  Mat3 F = Mat3::Identity();
  F(0, 1) = g;
  const double c = 2 / std::sqrt(4 + g * g), s = g / std::sqrt(4 + g * g);
  Mat3 R;
  R << c, s, 0, -s, c, 0, 0, 0, 1;
  EXPECT_LT((rotationOf(F) - R).norm(), 1e-14);
}

}  // namespace
}  // namespace anode
