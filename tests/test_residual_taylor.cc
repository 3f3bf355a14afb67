// The Taylor remainder of the residual EquilibriumSolver assembles (EquilibriumAssembly.cc) with
// the particles' algorithmic tangents: second order in the step along a direction, so the Jacobian
// is the residual's derivative.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "Components/MPM/Implicit/EquilibriumSolver.h"
#include "Components/MPM/Implicit/ParticleEquilibrium.h"
#include "tests/TangentClosedForms.h"

namespace anode {
namespace {

// A small body for the residual's Taylor remainder: a grid of 3^3 cells of side 1/3, 2^3 particles
// a cell (linear weights), the nodes of z = 0 held; rf_elastic_plastic below z = 1/2 (every other
// particle on the yield surface along its trial strain, the others inside it), comp_neo_hook
// above, in one velocity field; u and du smooth fields of gradients about 1e-3, zero at z = 0.
struct SmallBody {
  Grid grid;
  std::vector<MPMMaterial> materials;
  std::vector<InterpolationWeights> weights;
  std::vector<std::vector<double>> dc;
  std::vector<double> mass;
  std::vector<Vec3> prescribed, u, du;

  EquilibriumProblem problem() {
    return EquilibriumProblem{grid,    materials,    weights,      {0, 0},
                              {mass},  {prescribed}, Vec3::Zero(), {dc[0].data(), dc[1].data()},
                              nullptr, {},           {},           {},
                              {}};
  }
};

Vec3 displacementField(const Vec3& x, double phase) {
  return 1e-3 * x.z() *
         Vec3(std::sin(3 * x.x() + phase) + x.y(), std::cos(2 * x.y() - x.z() + phase),
              std::sin(x.x() + 2 * x.y() + phase) - 0.5 * x.z());
}

SmallBody smallBody() {
  SmallBody b;
  b.grid.lower = Vec3::Zero();
  b.grid.cells = Vec3i(3, 3, 3);
  b.grid.dx = Vec3::Constant(1.0 / 3);
  b.grid.upper = Vec3::Ones();
  const RadialReturnCase c = linearHardening();
  const NeoHookeanCase n;
  b.materials.resize(2);
  b.materials[0].model = std::make_unique<RFElasticPlastic>(c.K, c.G, c.flow, c.eta);
  b.materials[1].model = std::make_unique<CompNeoHookean>(n.K, n.G, n.eta);
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        ParticleSet& p = b.materials[k < 3 ? 0 : 1].particles;
        const size_t at = p.count();
        p.resize(at + 1);
        p.x[at] = (Vec3(i, j, k) + Vec3::Constant(0.5)) / 6;
        p.volume[at] = 1.0 / 216;
        p.mass[at] = 1000 * p.volume[at];
      }
  const int nodes = b.grid.numNodes();
  b.mass.assign(nodes, 0.0);
  b.u.resize(nodes);
  b.du.resize(nodes);
  b.prescribed.assign(nodes, Vec3::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (int k = 0; k < nodes; ++k) {
    const Vec3i ijk = b.grid.nodeOf(k);
    const Vec3 x = b.grid.nodePosition(ijk.x(), ijk.y(), ijk.z());
    if (ijk.z() == 0) b.prescribed[k] = Vec3::Zero();
    b.u[k] = displacementField(x, 0.3);
    b.du[k] = displacementField(x, 1.7);
  }
  for (MPMMaterial& m : b.materials) {
    ParticleSet& p = m.particles;
    m.model->initializeState(p);
    InterpolationWeights& W = b.weights.emplace_back();
    W.layOut(std::vector<uint8_t>(p.count(), 8));
    for (size_t i = 0; i < p.count(); ++i) {
      const size_t o = W.offset[i];
      W.count[i] = static_cast<uint8_t>(
          linearWeights(b.grid, p.x[i], &W.node[o], &W.weight[o], &W.gradient[o]));
      for (size_t e = o; e < o + W.count[i]; ++e) b.mass[W.node[e]] += p.mass[i] * W.weight[e];
    }
    b.dc.emplace_back(p.count(), 0.01);
  }
  // rf_elastic_plastic's odd particles plastic: eps_p = 0.02 and the start's deviator on the
  // surface along dev e of u (F_n = I, so R_n = I), as plasticTrial.
  ParticleSet& p = b.materials[0].particles;
  for (size_t i = 1; i < p.count(); i += 2) {
    Trial t;
    t.h = displacementGradient(b.weights[0], static_cast<long>(i), b.u);
    t.dc = b.dc[0][i];
    t.plasticStrain = 0.02;
    const Mat3 along = deviator(strainIncrement(c, t)).normalized();
    p.stress[i] = std::sqrt(2.0 / 3.0) * c.hardening.flowStress(t.plasticStrain) * along;
    p.modelArray<double>(0)[i] = t.plasticStrain;
  }
  return b;
}

std::vector<std::vector<Vec3>> along(const std::vector<Vec3>& u, double eps,
                                     const std::vector<Vec3>& du) {
  std::vector<Vec3> v(u.size());
  for (size_t k = 0; k < u.size(); ++k) v[k] = u[k] + eps * du[k];
  return {v};
}

double norm(const std::vector<Vec3>& v) {
  double s = 0;
  for (const Vec3& x : v) s += x.squaredNorm();
  return std::sqrt(s);
}

// r(u + eps du) = r(u) - eps K du + O(eps^2) when K is the stiffness -dr/du (r = f_ext - f_int):
// the remainder's ratio is 4 when eps halves. A tangent wrong by a share delta adds delta eps
// |K du|, and the ratio (4 a eps + 2 delta) / (a eps + delta) leaves [3.9, 4.1] once delta exceeds
// a eps / 20, a eps the remainder over eps |K du|: measured 3.5e-4 at eps = 0.1 falling to 7e-7 at
// 0.1 / 2^9, so a tangent wrong by more than about 4e-8 of itself fails (the difference's error is
// 2e-10 at most: test_tangent.cc). Measured ratios: 4.0000 at every halving. Round-off in r (1e-16
// of the internal forces) is below 1e-6 of the smallest remainder.
TEST(AlgorithmicTangent, ResidualTaylorRemainderIsSecondOrder) {
  SmallBody b = smallBody();
  const EquilibriumProblem problem = b.problem();
  ImplicitOptions options;
  options.dynamic = false;
  EquilibriumSolver solver;
  const EquilibriumSolver::Linearization at =
      solver.linearizeAt(Communicator::everyRank(), problem, kDt, options, {b.u}, {b.du});
  // No particle crosses the yield surface along the path (eps at most 0.1): a plastic one's trial
  // deviator moves by less than half its distance beyond the surface (2 G |dev e|), an elastic
  // one's stays below half the surface (the strain increment is about H to 1e-3 of itself).
  const RadialReturnCase c = linearHardening();
  const ParticleSet& p = b.materials[0].particles;
  for (size_t i = 0; i < p.count(); ++i) {
    const Mat3 H = displacementGradient(b.weights[0], static_cast<long>(i), b.u);
    const Mat3 dH = displacementGradient(b.weights[0], static_cast<long>(i), b.du);
    const double moved = 0.1 * deviator(symmetricPart(dH)).norm();
    if (i % 2 == 1)
      ASSERT_LT(moved, 0.5 * deviator(symmetricPart(H)).norm()) << "particle " << i;
    else
      ASSERT_LT(std::sqrt(1.5) * 2 * c.G * (deviator(symmetricPart(H)).norm() + moved),
                0.5 * c.flow.sigmaY)
          << "particle " << i;
  }
  const double slope = norm(at.jacobianTimesDirection[0]);
  ASSERT_GT(slope, 0);
  std::printf("%-10s %12s %12s %8s\n", "eps", "remainder", "/ eps|Kdu|", "ratio");
  double last = 0;
  for (int halvings = 0; halvings < 10; ++halvings) {
    const double eps = 0.1 * std::ldexp(1.0, -halvings);
    const EquilibriumSolver::Linearization moved = solver.linearizeAt(
        Communicator::everyRank(), problem, kDt, options, along(b.u, eps, b.du), {b.du});
    std::vector<Vec3> remainder(moved.residual[0].size());
    for (size_t k = 0; k < remainder.size(); ++k)
      remainder[k] =
          moved.residual[0][k] - at.residual[0][k] + eps * at.jacobianTimesDirection[0][k];
    const double size = norm(remainder);
    std::printf("%-10.3e %12.4e %12.4e %8.4f\n", eps, size, size / (eps * slope),
                last > 0 ? last / size : 0.0);
    if (last > 0) {
      EXPECT_GE(last / size, 3.9) << "eps " << eps;
      EXPECT_LE(last / size, 4.1) << "eps " << eps;
    }
    last = size;
  }
}

}  // namespace
}  // namespace anode
