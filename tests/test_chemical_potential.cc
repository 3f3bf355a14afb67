// The stress's part of the chemical potential (Components/MPM/ReactiveFlow/ChemicalPotential.h):
// phi = k tau_h of a particle, grad phi_0 + s_p grad c_0 from the nodes' mass-weighted
// projections, and the local response s_p a pass takes implicitly.
#include <gtest/gtest.h>

#include <vector>

#include "Components/MPM/ReactiveFlow/ChemicalPotential.h"

namespace anode {
namespace {

TEST(ChemicalPotential, StressPotentialIsKTimesTheKirchhoffMeanStress) {
  Mat3 stress;
  stress << 1, 5, 7, 5, 2, 11, 7, 11, 3;  // tr / 3 = 2
  Mat3 F = Mat3::Identity();
  F(0, 0) = 2;
  F(0, 1) = 0.3;  // det F = 2
  EXPECT_DOUBLE_EQ(stressPotential(0.25, stress, F), 0.25 * 2 * 2);
  EXPECT_DOUBLE_EQ(stressPotential(0.25, -stress, Mat3::Identity()), -0.5);  // compression
}

// Linear hats along x on cells of h = 0.5 (nodes 0..4), two particles of equal mass per cell at
// its quarter points, phi = a + b x at the particles: the projection is exact on the inner nodes
// (each sees a symmetric pair of particles on either side), so the particles of the inner cells
// get grad phi = (b, 0, 0); those of the end cells see a node biased by its one-sided particles.
// With c_0 = (c + change) / cmax linear as well, s_p grad c_0 adds s det F times its slope.
TEST(ChemicalPotential, GradientsOfLinearFieldsAreExactAwayFromTheEnds) {
  const double h = 0.5, a = 0.3, b = -1.7;
  const int cells = 4;
  std::vector<double> x, mass;
  for (int c = 0; c < cells; ++c)
    for (double q : {0.25, 0.75}) x.push_back((c + q) * h), mass.push_back(2.0);
  InterpolationWeights W;
  W.layOut(std::vector<uint8_t>(x.size(), 2));
  std::vector<Mat3> stress(x.size()), F(x.size(), Mat3::Identity());
  std::vector<double> c(x.size()), change(x.size());
  for (size_t i = 0; i < x.size(); ++i) {
    const int cell = static_cast<int>(x[i] / h);
    const double xi = x[i] / h - cell;
    const size_t o = W.offset[i];
    W.count[i] = 2;
    W.node[o] = cell, W.weight[o] = 1 - xi, W.gradient[o] = Vec3(-1 / h, 0, 0);
    W.node[o + 1] = cell + 1, W.weight[o + 1] = xi, W.gradient[o + 1] = Vec3(1 / h, 0, 0);
    stress[i] = (a + b * x[i]) * Mat3::Identity();  // phi = k tr(sigma)/3 with k = 1
    c[i] = 0.4 * x[i], change[i] = 0.2 * x[i];      // c_0 = 0.3 x with cmax = 2
    F[i](0, 0) = 1 + 0.1 * static_cast<double>(i);  // det F = J_p
  }
  std::vector<double> nodeMass(cells + 1, 0.0), nodeMassPotential, nodeMassConcentration;
  for (size_t i = 0; i < x.size(); ++i)
    for (size_t e = W.offset[i]; e < W.offset[i] + 2; ++e)
      nodeMass[W.node[e]] += W.weight[e] * mass[i];
  // phi alone (F = I for it): no c_0 part with s = 0.
  const std::vector<Mat3> unstretched(x.size(), Mat3::Identity());
  scatterStressPotential(1.0, 2.0, mass, stress, unstretched, c, &change, W, nodeMass.size(),
                         nodeMassPotential, nodeMassConcentration);
  for (int k = 1; k < cells; ++k) {
    EXPECT_NEAR(nodeMassPotential[k] / nodeMass[k], a + b * k * h, 1e-14) << k;
    EXPECT_NEAR(nodeMassConcentration[k] / nodeMass[k], 0.3 * k * h, 1e-14) << k;
  }
  std::vector<Vec3> gradient(x.size());
  gatherStressPotentialGradient(W, nodeMassPotential, nodeMassConcentration, nodeMass, 0.0, F,
                                gradient);
  for (size_t i = 2; i + 2 < x.size(); ++i) {
    EXPECT_NEAR(gradient[i].x(), b, 1e-13) << i;
    EXPECT_EQ(gradient[i].y(), 0.0);
  }
  // The end cells' nodes hold the mean of their nearer particles' phi: a smaller slope there.
  EXPECT_LT(std::abs(gradient[0].x()), std::abs(b));
  gatherStressPotentialGradient(W, nodeMassPotential, nodeMassConcentration, nodeMass, 3.0, F,
                                gradient);
  for (size_t i = 2; i + 2 < x.size(); ++i)
    EXPECT_NEAR(gradient[i].x(), b + 3.0 * F[i].determinant() * 0.3, 1e-13) << i;
}

TEST(ChemicalPotential, LocalResponseAndPassDiffusivity) {
  // 2 E eta / (3 (1 - nu)) from K and G: E = 9KG / (3K + G), nu = (3K - 2G) / (2 (3K + G)).
  const double K = 67, G = 31, eta = 0.1;
  const double E = 9 * K * G / (3 * K + G), nu = (3 * K - 2 * G) / (2 * (3 * K + G));
  EXPECT_NEAR(localSwellingPressure(eta, K, G), 2 * E * eta / (3 * (1 - nu)), 1e-12);
  EXPECT_DOUBLE_EQ(effectiveDiffusivity(2.0, 8.0, 1.5, 0.5), 2.0 * (1 + 8.0 * 1.5 * 0.25));
  EXPECT_DOUBLE_EQ(effectiveDiffusivity(2.0, 8.0, 1.5, 0.0), 2.0);
}

}  // namespace
}  // namespace anode
