// Pins chemo-mechanical swelling (paper Eqs. 25, 32-33, 36; issue 4): a free body reaches
// J = exp(3 eta dc) stress-free; a fully confined body has mean stress -3 K eta dc; a body
// constrained along one axis has sigma = -E eta dc until yield, then the perfectly plastic or
// linear-hardening value; the swelling update is objective under rigid rotation. comp_neo_hook
// (hyperelastic) against its finite-strain closed forms: free swelling stress-free, confined
// pressure -K sinh(3 eta dc), and one axis held.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <iostream>

#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"
#include "StandAlone/Driver/Simulation.h"

namespace anode {
namespace {

const double K = 6e5, G = 3e5, eta = 0.56;
const double E = 9 * K * G / (3 * K + G);

struct SwellingCase {
  std::string model = "rf_elastic_plastic";
  std::string flowModel;  // empty: elastic
  std::string faces;      // <Face> elements
  std::string gridUpper = "[2, 2, 2]", cells = "[8, 8, 8]";
  std::string boxMin = "[0.75, 0.75, 0.75]", boxMax = "[1.25, 1.25, 1.25]";
  double rate = 1.0, endTime = 0.5;  // dc/dt and duration: dc = rate * endTime
  double damping = 0;

  std::string text() const {
    std::ostringstream s;
    s << "<Uintah_specification><SimulationComponent type=\"mpm\"/>"
      << "<Time><maxTime>" << endTime << "</maxTime><initTime>0</initTime><delt_min>0</delt_min>"
      << "<delt_max>1</delt_max><timestep_multiplier>0.3</timestep_multiplier>"
      << "<end_at_max_time_exactly>true</end_at_max_time_exactly></Time>"
      << "<DataArchiver><filebase>swell.uda</filebase><outputTimestepInterval>1000000</"
         "outputTimestepInterval></DataArchiver>"
      << "<MPM><interpolator>cpdi</interpolator><do_scalar_diffusion>true</do_scalar_diffusion>"
      << "<artificial_damping_coeff>" << damping << "</artificial_damping_coeff></MPM>"
      << "<MaterialProperties><MPM><material><density>1000</density>"
      << "<constitutive_model type=\"" << model << "\"><bulk_modulus>" << K << "</bulk_modulus>"
      << "<shear_modulus>" << G << "</shear_modulus><volume_expansion_coeff>" << eta
      << "</volume_expansion_coeff>" << flowModel << "</constitutive_model>"
      << "<diffusion_model "
         "type=\"constant_rate\"><diffusivity>0</diffusivity><max_concentration>1</"
         "max_concentration>"
      << "<constant_rate>" << rate << "</constant_rate></diffusion_model>"
      << "<geom_object><box><min>" << boxMin << "</min><max>" << boxMax
      << "</max></box><res>[2,2,2]</res>"
      << "<velocity>[0,0,0]</velocity><concentration>0</concentration></geom_object></material></"
         "MPM></MaterialProperties>"
      << "<Grid><Level><Box><lower>[0,0,0]</lower><upper>" << gridUpper << "</upper><resolution>"
      << cells << "</resolution><extraCells>[1,1,1]</extraCells></Box></Level><BoundaryConditions>"
      << faces << "</BoundaryConditions></Grid></Uintah_specification>";
    return s.str();
  }
};

std::unique_ptr<Simulation> run(const SwellingCase& c) {
  omp_set_num_threads(1);  // a few dozen particles over 10^4 steps: threads would only wait
  RunOptions o;
  o.progress = false;
  auto sim = std::make_unique<Simulation>(c.text(), "swelling.ups", o);
  while (sim->time() < c.endTime * (1 - 1e-12)) sim->advance();
  return sim;
}

std::string symmetric(const char* side) {
  return std::string("<Face side=\"") + side +
         "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>";
}

TEST(Swelling, FreeBodyReachesExpOf3EtaDcWithoutStress) {
  SwellingCase c;
  c.rate = 0.02;   // slow against the wave transit time (quasi-static)
  c.endTime = 25;  // dc = 0.5
  const auto sim = run(c);
  const MPMMaterial& m = sim->mpm().materials()[0];
  const double expected = std::exp(3 * eta * 0.5);
  double maxStress = 0;
  for (size_t i = 0; i < m.particles.count(); ++i) {
    EXPECT_NEAR(diffusionParticles(m.particles).concentration[i], 0.5, 1e-12);
    EXPECT_NEAR(m.particles.F[i].determinant(), expected,
                1e-4 * expected);  // measured 9e-6; the issue asks 0.5%
    maxStress = std::max(maxStress, m.particles.stress[i].norm());
  }
  EXPECT_LT(maxStress, 1e-3 * 3 * K * eta * 0.5) << "free swelling is (nearly) stress-free";
}

TEST(Swelling, ConfinedBoxHasMeanStressMinus3KEtaDc) {
  // The body fills the grid; Symmetric faces on all six sides hold every normal velocity.
  SwellingCase c;
  c.gridUpper = "[1, 1, 1]";
  c.cells = "[4, 4, 4]";
  c.boxMin = "[0, 0, 0]";
  c.boxMax = "[1, 1, 1]";
  c.rate = 0.1;
  c.endTime = 0.2;  // dc = 0.02
  for (const char* s : {"x-", "x+", "y-", "y+", "z-", "z+"}) c.faces += symmetric(s);
  const auto sim = run(c);
  const ParticleSet& p = sim->mpm().materials()[0].particles;
  for (size_t i = 0; i < p.count(); ++i) {
    EXPECT_NEAR(p.stress[i].trace() / 3, -3 * K * eta * 0.02, 1e-9 * 3 * K * eta * 0.02);
    EXPECT_NEAR(p.F[i].determinant(), 1.0, 1e-12);
  }
}

// One axis (z) held by Symmetric faces at both ends of the body; x and y free.
SwellingCase constrainedInZ(const std::string& flow, double dc) {
  SwellingCase c;
  c.gridUpper = "[2, 2, 0.5]";
  c.cells = "[8, 8, 2]";
  c.boxMin = "[0.75, 0.75, 0]";
  c.boxMax = "[1.25, 1.25, 0.5]";
  c.flowModel = flow;
  c.rate = 2e-4;  // quasi-static
  c.endTime = dc / c.rate;
  c.faces = symmetric("z-") + symmetric("z+");
  return c;
}

double meanStressZZ(const Simulation& sim) {
  const ParticleSet& p = const_cast<Simulation&>(sim).mpm().materials()[0].particles;
  double s = 0;
  for (const Mat3& m : p.stress) s += m(2, 2);
  return s / p.count();
}

const double sigmaY = 1e3;  // yield at eta dc = sigmaY / E ~ 1.3e-3

TEST(Swelling, ConstrainedAxisIsElasticUntilYield) {
  const double dc = 1e-3;  // eta dc E = 0.75 sigmaY: elastic
  const auto sim = run(constrainedInZ("", dc));
  EXPECT_NEAR(meanStressZZ(*sim), -E * eta * dc, 1e-4 * E * eta * dc);
}

TEST(Swelling, ConstrainedAxisHoldsTheYieldStressWithPerfectPlasticity) {
  const double dc = 5e-3;
  const auto sim = run(
      constrainedInZ("<flow_model type=\"johnson_cook\"><A>1e3</A><B>0</B><C>0</C><n>0</n><m>1</m>"
                     "</flow_model><yield_condition type=\"vonMises\"/>",
                     dc));
  EXPECT_NEAR(meanStressZZ(*sim), -sigmaY, 1e-4 * sigmaY);
}

TEST(Swelling, ConstrainedAxisFollowsLinearHardening) {
  const double dc = 5e-3, H = 2e5;
  const auto sim =
      run(constrainedInZ("<flow_model type=\"isotropic_hardening\"><sigma_Y>1e3</sigma_Y><K>2e5</K>"
                         "</flow_model><yield_condition type=\"vonMises\"/>",
                         dc));
  const double expected = sigmaY + E * H / (E + H) * (eta * dc - sigmaY / E);
  EXPECT_NEAR(meanStressZZ(*sim), -expected, 1e-4 * expected);
}

TEST(Swelling, RigidRotationKeepsTheStressInvariants) {
  // The same stretch and concentration history with and without a superposed rotation Q(t):
  // the stresses must differ by Q only.
  FlowModel flow;
  flow.type = FlowModel::Type::IsotropicHardening;
  flow.sigmaY = 5e3;
  flow.K = 1e4;
  const RFElasticPlastic model(K, G, flow, eta);
  const double dt = 1e-3, dc = 2e-4;
  Mat3 sA = Mat3::Zero(), sB = Mat3::Zero(), FA = Mat3::Identity(), FB = Mat3::Identity();
  RFElasticPlastic::State<double> A{Mat3::Identity(), 0, 0, 0}, B{Mat3::Identity(), 0, 0, 0};
  const Vec3 axis = Vec3(0.3, -1, 0.5).normalized();
  for (int n = 1; n <= 400; ++n) {
    const Mat3 U = Vec3(std::exp(0.05 * n * dt), std::exp(-0.02 * n * dt), 1.0).asDiagonal();
    const Mat3 Q = Eigen::AngleAxisd(3.0 * n * dt, axis).toRotationMatrix();
    const Mat3 FAn = U, FBn = Q * U;
    const Mat3 LA = (FAn - FA) / dt * (0.5 * (FAn + FA)).inverse();
    const Mat3 LB = (FBn - FB) / dt * (0.5 * (FBn + FB)).inverse();
    sA = model.updateStress(sA, FAn, LA, dc, dt, A);
    sB = model.updateStress(sB, FBn, LB, dc, dt, B);
    FA = FAn;
    FB = FBn;
  }
  const Mat3 R = Eigen::AngleAxisd(3.0 * 400 * dt, axis).toRotationMatrix();
  EXPECT_GT(A.ep, 0.0) << "the history must reach plasticity";
  EXPECT_NEAR(B.ep, A.ep, 1e-3 * A.ep);
  EXPECT_NEAR(sB.trace(), sA.trace(), 1e-3 * sA.norm());
  EXPECT_LT((sB - R * sA * R.transpose()).norm(), 1e-3 * sA.norm());
  auto vonMises = [](const Mat3& s) {
    return std::sqrt(1.5) * (s - s.trace() / 3 * Mat3::Identity()).norm();
  };
  EXPECT_NEAR(vonMises(sB), vonMises(sA), 1e-3 * vonMises(sA));
}

// comp_neo_hook: Fe = F exp(-eta dc), sigma = K/2 (Je - 1/Je) I + G Je^(-5/3) dev(Fe Fe^T).

TEST(Swelling, NeoHookeanFreeBodyIsStressFreeAtFiniteStretch) {
  SwellingCase c;
  c.model = "comp_neo_hook";
  c.rate = 0.02;
  c.endTime = 25;  // dc = 0.5: each axis stretched by exp(0.28)
  const auto sim = run(c);
  const ParticleSet& p = sim->mpm().materials()[0].particles;
  const double expected = std::exp(3 * eta * 0.5);
  double maxStress = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    EXPECT_NEAR(p.F[i].determinant(), expected, 1e-4 * expected);
    maxStress = std::max(maxStress, p.stress[i].norm());
  }
  EXPECT_LT(maxStress, 1e-3 * 3 * K * eta * 0.5) << "free swelling is (nearly) stress-free";
  std::cout << "comp_neo_hook free swelling: largest |stress| / (3 K eta dc) = "
            << maxStress / (3 * K * eta * 0.5) << "\n";
}

TEST(Swelling, NeoHookeanConfinedBoxHasPressureKSinh3EtaDc) {
  SwellingCase c;
  c.model = "comp_neo_hook";
  c.gridUpper = "[1, 1, 1]";
  c.cells = "[4, 4, 4]";
  c.boxMin = "[0, 0, 0]";
  c.boxMax = "[1, 1, 1]";
  c.rate = 2.5;
  c.endTime = 0.2;  // dc = 0.5, where the linear -3 K eta dc is 12% off
  for (const char* s : {"x-", "x+", "y-", "y+", "z-", "z+"}) c.faces += symmetric(s);
  const auto sim = run(c);
  const ParticleSet& p = sim->mpm().materials()[0].particles;
  const double expected = -K * std::sinh(3 * eta * 0.5);
  for (size_t i = 0; i < p.count(); ++i) {
    EXPECT_NEAR(p.stress[i].trace() / 3, expected, 1e-9 * std::abs(expected));
    EXPECT_NEAR(p.stress[i](0, 0), p.stress[i](2, 2), 1e-9 * std::abs(expected));
  }
}

TEST(Swelling, NeoHookeanConstrainedAxisByClosedForm) {
  // z held, x and y free: F = diag(l, l, 1). With a = l exp(-theta), b = exp(-theta),
  // Je = a^2 b, sigma_xx = K/2 (Je - 1/Je) + G Je^(-5/3) (a^2 - b^2)/3 = 0 fixes a (bisection);
  // then sigma_zz = K/2 (Je - 1/Je) - 2/3 G Je^(-5/3) (a^2 - b^2).
  const double dc = 0.5, theta = eta * dc, b = std::exp(-theta);
  auto parts = [&](double a) {
    const double Je = a * a * b;
    return std::pair{0.5 * K * (Je - 1 / Je), G * std::pow(Je, -5.0 / 3.0) * (a * a - b * b)};
  };
  double lo = 0.5, hi = 3;
  for (int k = 0; k < 200; ++k) {
    const double a = 0.5 * (lo + hi);
    const auto [pressure, shear] = parts(a);
    (pressure + shear / 3 > 0 ? hi : lo) = a;
  }
  const auto [pressure, shear] = parts(lo);
  const double szz = pressure - 2.0 / 3.0 * shear, stretch = lo / b;
  SwellingCase c = constrainedInZ("", dc);
  c.model = "comp_neo_hook";
  c.rate = 0.02;
  c.endTime = dc / c.rate;
  const auto sim = run(c);
  const ParticleSet& p = sim->mpm().materials()[0].particles;
  double Fxx = 0;
  for (const Mat3& F : p.F) Fxx += F(0, 0) / p.count();
  EXPECT_NEAR(Fxx, stretch, 1e-6 * stretch);                   // measured 7e-9
  EXPECT_NEAR(meanStressZZ(*sim), szz, 1e-6 * std::abs(szz));  // measured 3.5e-8
  std::cout << "comp_neo_hook, z held: lateral stretch " << Fxx << ", relative error "
            << Fxx / stretch - 1 << "; sigma_zz " << meanStressZZ(*sim) << ", relative error "
            << meanStressZZ(*sim) / szz - 1 << " (the linear value " << -E * theta << " is "
            << -E * theta / szz - 1 << " off)\n";
  EXPECT_GT(std::abs(szz + E * theta), 0.01 * E * theta) << "finite strain: not the linear value";
}

}  // namespace
}  // namespace anode
