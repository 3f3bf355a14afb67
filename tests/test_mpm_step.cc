// Pins the explicit step: rigid translation across cells gives no stress (all interpolators),
// momentum is conserved, single_velocity contact bonds materials, dt follows Eq. 43, only gravity
// acts on nodes below minimum_mass_for_acc, and the run stops after the first step at or past
// maxTime.
#include <gtest/gtest.h>

#include <cmath>

#include "StandAlone/Driver/Simulation.h"
#include "TestInputs.h"

namespace anode {
namespace {

using testing::BlockInput;

RunOptions quiet() {
  RunOptions o;
  o.progress = false;
  return o;
}

Vec3 totalMomentum(Simulation& sim) {
  Vec3 p = Vec3::Zero();
  for (const MPMMaterial& m : sim.mpm().materials())
    for (size_t i = 0; i < m.particles.count(); ++i)
      p += m.particles.mass[i] * m.particles.velocity[i];
  return p;
}

class RigidTranslation : public ::testing::TestWithParam<std::string> {};

TEST_P(RigidTranslation, CrossesCellsWithoutStress) {
  BlockInput in;
  in.interpolator = GetParam();
  in.velocity = "[30, 20, -10]";  // c = sqrt((K + 4G/3)/rho) ~ 41: dt ~ 5e-4 s at dx = 0.1
  in.boxMin = "[0.2, 0.3, 0.5]";
  in.boxMax = "[0.4, 0.5, 0.7]";
  in.maxSteps = 400;
  Simulation sim(in.text(), "translation.ups", quiet());
  const std::vector<Vec3> x0 = sim.mpm().materials()[0].particles.x;
  while (sim.step() < 40) sim.advance();
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  const Vec3 shift = Vec3(30, 20, -10) * sim.time();
  ASSERT_GT(shift.norm(), 0.15) << "the block must cross at least one cell";
  double maxStress = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    maxStress = std::max(maxStress, p.stress[i].norm());
    EXPECT_LT((p.x[i] - x0[i] - shift).norm(), 1e-12);
    EXPECT_LT((p.velocity[i] - Vec3(30, 20, -10)).norm(), 1e-10);
    EXPECT_LT((p.F[i] - Mat3::Identity()).norm(), 1e-12);
  }
  EXPECT_LT(maxStress, 1e-6);  // K = 1e6: relative 1e-12
}

INSTANTIATE_TEST_SUITE_P(Interpolators, RigidTranslation,
                         ::testing::Values("linear", "gimp", "cpdi"));

TEST(MPMStep, MomentumIsConservedForAFreeBodyWithCpdi) {
  // A spinning, expanding block with no boundary conditions: internal forces sum to zero.
  BlockInput in;
  in.interpolator = "cpdi";
  in.velocity = "[3, -2, 1]";
  in.maxSteps = 100;
  Simulation sim(in.text(), "momentum.ups", quiet());
  ParticleSet& p = sim.mpm().materials()[0].particles;
  const Vec3 c(0.5, 0.5, 0.5);
  for (size_t i = 0; i < p.count(); ++i)
    p.velocity[i] += Vec3(0, 0, 5).cross(p.x[i] - c) + 2.0 * (p.x[i] - c);
  const Vec3 before = totalMomentum(sim);
  double mass = 0;
  for (double m : p.mass) mass += m;
  for (int s = 0; s < 50; ++s) sim.advance();
  EXPECT_LT((totalMomentum(sim) - before).norm(), 1e-12 * mass * 10);
  double maxStress = 0;
  for (const Mat3& s : p.stress) maxStress = std::max(maxStress, s.norm());
  EXPECT_GT(maxStress, 1.0) << "the expanding block must be stressed";
}

TEST(MPMStep, FirstTimestepFollowsEquation43) {
  BlockInput in;
  in.velocity = "[5, 0, 0]";
  in.cells = "[10, 20, 40]";  // dx = 0.1, 0.05, 0.025
  Simulation sim(in.text(), "dt.ups", quiet());
  const double c = std::sqrt((in.bulk + 4 * in.shear / 3) / in.density);
  const double expected = in.multiplier * std::min({0.1 / (c + 5), 0.05 / c, 0.025 / c});
  EXPECT_NEAR(sim.dt(), expected, 1e-14 * expected);
}

TEST(MPMStep, StopsAfterTheFirstStepPastMaxTime) {
  BlockInput in;
  in.maxSteps = 0;
  in.maxTime = 0.01;
  in.saves = "";
  Simulation sim(in.text(), "maxtime.ups", quiet());
  const double dt = sim.dt();
  while (sim.time() < in.maxTime) sim.advance();
  EXPECT_EQ(sim.step(), static_cast<long>(std::ceil(in.maxTime / dt - 1e-9)));
}

TEST(MPMStep, BelowMinimumMassForAccOnlyGravityActs) {
  // Every node below the threshold: no force acts, but gravity does at every node (as in Uintah),
  // so each particle falls freely, v = g t.
  BlockInput in;
  in.mpmFlags = "<gravity>[0, 0, -10]</gravity><minimum_mass_for_acc>1e30</minimum_mass_for_acc>";
  in.velocity = "[0, 0, 0]";
  Simulation sim(in.text(), "light.ups", quiet());
  for (int s = 0; s < 5; ++s) sim.advance();
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  const double v = -10 * sim.time();
  for (size_t i = 0; i < p.count(); ++i) {
    EXPECT_NEAR(p.velocity[i].z(), v, 1e-12 * std::abs(v)) << i;
    EXPECT_NEAR(p.velocity[i].head<2>().norm(), 0.0, 1e-12 * std::abs(v)) << i;
  }
}

std::string secondBlock(const std::string& velocity) {
  return "<material name=\"second\"><density>1000</density><constitutive_model "
         "type=\"rf_elastic_plastic\">"
         "<bulk_modulus>1e6</bulk_modulus><shear_modulus>5e5</shear_modulus></constitutive_model>"
         "<geom_object><box><min>[0.5,0.25,0.25]</min><max>[0.75,0.75,0.75]</max></box>"
         "<res>[2,2,2]</res><velocity>" +
         velocity +
         "</velocity><temperature>298</temperature>"
         "</geom_object></material>";
}

TEST(Contact, SingleVelocityBondsTwoMaterials) {
  BlockInput in;
  in.boxMax = "[0.5, 0.75, 0.75]";
  in.velocity = "[0, 0, 4]";
  in.extraMaterials = secondBlock("[0, 0, 0]");
  in.contact = "<contact><type>single_velocity</type><materials>[0,1]</materials></contact>";
  Simulation sim(in.text(), "contact.ups", quiet());
  const Vec3 before = totalMomentum(sim);
  for (int s = 0; s < 20; ++s) sim.advance();
  EXPECT_LT((totalMomentum(sim) - before).norm(), 1e-10 * before.norm());
  // The bonded interface: shared nodes carry one velocity for both materials.
  const auto& g = sim.mpm().stepGrid().fields;
  int shared = 0;
  for (size_t n = 0; n < g[0].mass.size(); ++n)
    if (g[0].mass[n] > 0 && g[1].mass[n] > 0) {
      EXPECT_LT((g[0].velocityStar[n] - g[1].velocityStar[n]).norm(), 1e-12);
      ++shared;
    }
  EXPECT_GT(shared, 0);
  // The resting block was dragged along.
  double vz = 0;
  for (const Vec3& v : sim.mpm().materials()[1].particles.velocity) vz = std::max(vz, v.z());
  EXPECT_GT(vz, 0.1);
}

TEST(Contact, NullContactLeavesMaterialsIndependent) {
  BlockInput in;
  in.boxMax = "[0.5, 0.75, 0.75]";
  in.velocity = "[0, 0, 4]";
  in.extraMaterials = secondBlock("[0, 0, 0]");
  in.contact = "<contact><type>null</type></contact>";
  Simulation sim(in.text(), "null.ups", quiet());
  for (int s = 0; s < 20; ++s) sim.advance();
  for (const Vec3& v : sim.mpm().materials()[1].particles.velocity) EXPECT_EQ(v.norm(), 0.0);
}

TEST(BoundaryConditions, VelocityDirichletHoldsTheBaseAndSymmetryStopsNormalMotion) {
  // A block falling onto a fixed base (z-) between symmetric walls (x-, x+): the base layer of
  // nodes keeps zero velocity and no particle crosses the symmetric planes.
  BlockInput in;
  in.interpolator = "gimp";
  in.boxMin = "[0, 0.2, 0]";
  in.boxMax = "[1, 0.8, 0.5]";
  in.velocity = "[0, 0, -2]";
  in.faces =
      "<Face side=\"z-\"><BCType id=\"all\" label=\"Velocity\" "
      "var=\"Dirichlet\"><value>[0,0,0]</value></BCType></Face>"
      "<Face side=\"x-\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>"
      "<Face side=\"x+\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>";
  Simulation sim(in.text(), "bcs.ups", quiet());
  for (int s = 0; s < 30; ++s) sim.advance();
  const Grid& grid = sim.mpm().grid();
  const auto& g = sim.mpm().stepGrid().fields[0];
  for (int j = 0; j <= grid.cells.y(); ++j)
    for (int i = 0; i <= grid.cells.x(); ++i)
      EXPECT_EQ(g.velocityStar[grid.nodeIndex(i, j, 0)].norm(), 0.0);
  for (int k = 0; k <= grid.cells.z(); ++k)
    for (int j = 0; j <= grid.cells.y(); ++j) {
      EXPECT_EQ(g.velocityStar[grid.nodeIndex(0, j, k)].x(), 0.0);
      EXPECT_EQ(g.velocityStar[grid.nodeIndex(grid.cells.x(), j, k)].x(), 0.0);
    }
  double minStressZZ = 0;
  for (const Mat3& s : sim.mpm().materials()[0].particles.stress)
    minStressZZ = std::min(minStressZZ, s(2, 2));
  EXPECT_LT(minStressZZ, -1e3) << "the impact must compress the block";
}

}  // namespace
}  // namespace anode
