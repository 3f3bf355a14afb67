#include "StandAlone/Studies/LithiatedSphere.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

namespace {

constexpr int kSeriesTerms = 200;  // a_200 ~ 630: exp(-a^2 D t / b^2) is nothing at t = 0.01
constexpr int kIntegralPoints = 20000;
constexpr int kShells = 400;  // of the stress-driven sphere's finite volumes

// The root of a cos a - sin a (a cot a = 1) in ((k + 1/2) pi, (k + 3/2) pi), by bisection.
double rootOfFluxSeries(int k) {
  double lo = (k + 0.5) * M_PI + 1e-12, hi = (k + 1.5) * M_PI - 1e-12;
  const auto f = [](double a) { return a * std::cos(a) - std::sin(a); };
  const bool rising = f(lo) < 0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0) == rising ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

double LithiatedSphereCase::youngsModulus() const {
  return 9 * bulkModulus * shearModulus / (3 * bulkModulus + shearModulus);
}

double LithiatedSphereCase::poissonsRatio() const {
  return (3 * bulkModulus - 2 * shearModulus) / (2 * (3 * bulkModulus + shearModulus));
}

double LithiatedSphereCase::stabilization() const {
  return 3 * expansion / cmaxRT * 2 * expansion * youngsModulus() / (3 * (1 - poissonsRatio()));
}

namespace {

// c of kShells shells of [0, b] at the end time: dc/dt = (1 / r^2) d/dr (r^2 D_eff(c) dc/dr),
// D_eff = D (1 + s c (1 - c)) at each face's mean c, the flux J in through r = b; explicit steps
// at 0.4 of the limit of the largest D_eff of the step's start.
std::vector<double> stressDrivenSphereShells(const LithiatedSphereCase& c) {
  const double b = c.radius, h = b / kShells, s = c.stabilization();
  std::vector<double> shell(kShells, 0.0), flux(kShells + 1, 0.0), volume(kShells);
  for (int i = 0; i < kShells; ++i)
    volume[i] = (std::pow(i + 1, 3) - std::pow(i, 3)) * h * h * h / 3;
  flux[kShells] = -c.flux * b * b;  // outward r^2 flux through the surface
  for (double t = 0; t < c.endTime;) {
    double largest = 0;
    for (int i = 1; i < kShells; ++i) {
      const double face = 0.5 * (shell[i - 1] + shell[i]), r = i * h;
      const double diffusivity = c.diffusivity * (1 + s * face * (1 - face));
      largest = std::max(largest, diffusivity);
      flux[i] = -diffusivity * (shell[i] - shell[i - 1]) / h * r * r;
    }
    const double dt = std::min(0.4 * h * h / (2 * largest), c.endTime - t);
    for (int i = 0; i < kShells; ++i) shell[i] -= dt * (flux[i + 1] - flux[i]) / volume[i];
    t += dt;
  }
  return shell;
}

}  // namespace

LithiatedSphereSolution::LithiatedSphereSolution(const LithiatedSphereCase& c) : case_(c) {
  if (c.cmaxRT > 0)
    shells_ = stressDrivenSphereShells(c);
  else
    for (int k = 0; k < kSeriesTerms; ++k) roots_.push_back(rootOfFluxSeries(k));
  // I(r) = int_0^r c s^2 ds by the trapezoidal rule.
  const double b = c.radius;
  radius_.push_back(0);
  integral_.push_back(0);
  double last = 0;
  for (int i = 1; i <= kIntegralPoints; ++i) {
    const double r = b * i / kIntegralPoints, value = concentration(r) * r * r;
    integral_.push_back(integral_.back() + 0.5 * (last + value) * (r - radius_.back()));
    radius_.push_back(r);
    last = value;
  }
}

double LithiatedSphereSolution::concentration(double r) const {
  const LithiatedSphereCase& c = case_;
  if (!shells_.empty()) {  // linear between the shells' mid-radii
    const double u = std::clamp(r / c.radius * kShells - 0.5, 0.0, kShells - 1.0);
    const int i = std::min(static_cast<int>(u), kShells - 2);
    const double w = u - i;
    return (1 - w) * shells_[i] + w * shells_[i + 1];
  }
  const double b = c.radius, tau = c.diffusivity * c.endTime / (b * b), x = r / b;
  double series = 0;
  for (double a : roots_) {
    // (2 b / r) sin(a r / b), which is 2 a at the centre
    const double shape = x > 1e-9 ? 2 * std::sin(a * x) / x : 2 * a;
    series += std::exp(-a * a * tau) * shape / (a * a * std::sin(a));
  }
  return c.flux * b / c.diffusivity * (3 * tau + 0.5 * x * x - 0.3 - series);
}

LithiatedSphereExact LithiatedSphereSolution::at(double r) const {
  const LithiatedSphereCase& c = case_;
  const double b = c.radius;
  r = std::clamp(r, 0.0, b);
  const double k = c.expansion * c.youngsModulus() / (1 - c.poissonsRatio());
  const double whole = integral_.back() / (b * b * b), cr = concentration(r);
  // I(r) / r^3, interpolated on the fine grid; c(0) / 3 at the centre.
  double inner = cr / 3;
  if (r > b / kIntegralPoints) {
    const size_t i =
        std::min<size_t>(static_cast<size_t>(r / b * kIntegralPoints), kIntegralPoints - 1);
    const double w = (r - radius_[i]) / (radius_[i + 1] - radius_[i]);
    inner = ((1 - w) * integral_[i] + w * integral_[i + 1]) / (r * r * r);
  }
  return {cr, 2 * k * (whole - inner), k * (2 * whole + inner - cr)};
}

std::string lithiatedSphereInput(const LithiatedSphereCase& c) {
  if (c.cells < 2)
    throw std::invalid_argument("lithiated sphere: need at least 2 cells per radius");
  requireInterpolator("lithiated sphere", c.interpolator);
  const std::string res = std::to_string(c.particlesPerCell);
  const std::string sphere = "<sphere label=\"sphere\"><origin>[0,0,0]</origin><radius>" +
                             upsNumber(c.radius) + "</radius></sphere>";

  std::string material;
  material += "      <material name=\"sphere\">\n";
  material += "        <density>1</density>\n";
  material += "        <constitutive_model type=\"rf_elastic_plastic\">\n";
  material += "          <bulk_modulus>" + upsNumber(c.bulkModulus) + "</bulk_modulus>\n";
  material += "          <shear_modulus>" + upsNumber(c.shearModulus) + "</shear_modulus>\n";
  material +=
      "          <volume_expansion_coeff>" + upsNumber(c.expansion) + "</volume_expansion_coeff>\n";
  material += "          <equation_of_state type=\"default_hypo\"/>\n";
  material += "        </constitutive_model>\n";
  material += std::string("        <diffusion_model type=\"") +
              (c.cmaxRT > 0 ? "chemical_potential" : "jg") + "\">\n";
  material += "          <diffusivity>" + upsNumber(c.diffusivity) + "</diffusivity>\n";
  material += "          <max_concentration>1</max_concentration>\n";
  if (c.cmaxRT > 0) material += "          <cmax_RT>" + upsNumber(c.cmaxRT) + "</cmax_RT>\n";
  material += "        </diffusion_model>\n";
  material += "        <geom_object>\n";
  material += "          " + sphere + "\n";
  material += "          <res>[" + res + "," + res + "," + res + "]</res>\n";
  material += "          <velocity>[0,0,0]</velocity>\n";
  material += "          <concentration>0</concentration>\n";
  material += "        </geom_object>\n";
  material += "      </material>\n";
  const std::string load = "<load_curve><id>1</id><time_point><time>0</time><load>" +
                           upsNumber(c.flux) + "</load></time_point><time_point><time>" +
                           upsNumber(10 * c.endTime) + "</time><load>" + upsNumber(c.flux) +
                           "</load></time_point></load_curve>";
  std::string flux;
  flux += "  <PhysicalBC>\n    <MPM>\n      <scalar_flux>\n";
  flux += "        <geom_object>" + sphere + "</geom_object>\n";
  flux += "        " + load + "\n";
  flux += "      </scalar_flux>\n    </MPM>\n  </PhysicalBC>\n";

  std::string s;
  s += upsOpening(
      "An octant of a free elastic sphere taking up lithium at a constant flux through its\n"
      "     surface, in quasi-static steps (Crank's sphere, Timoshenko & Goodier's stresses).",
      "Lithiated sphere, " + c.interpolator + ", " + std::to_string(c.cells) +
          " cells per radius, swelling_strain " + c.swellingStrain,
      "mpm");
  s += upsTimeAndArchiver(c.endTime, c.endTime, 0.25, "lithiated_sphere.uda");
  s += "  <MPM>\n";
  s += "    <time_integrator>implicit</time_integrator>\n";
  s += "    <dynamic>false</dynamic>\n";
  s += "    <error_tolerance>" + upsNumber(c.errorTolerance) + "</error_tolerance>\n";
  s += "    <swelling_strain>" + c.swellingStrain + "</swelling_strain>\n";
  s += "    <interpolator>" + c.interpolator + "</interpolator>\n";
  s += "    <do_scalar_diffusion>true</do_scalar_diffusion>\n";
  s += "    <use_load_curves>true</use_load_curves>\n";
  s += "  </MPM>\n";
  s += upsMaterialProperties(material, "");
  s += flux;
  s += upsSphereOctantGrid(c.radius, c.cells, c.interpolator);
  s += "</Uintah_specification>\n";
  return s;
}

LithiatedSphereResult runLithiatedSphere(const LithiatedSphereCase& c) {
  const ThreadScope threads(c.threads);
  VerificationRun run("lithiated sphere", lithiatedSphereInput(c),
                      "lithiated_sphere_" + c.interpolator + "_" + std::to_string(c.cells) + "_" +
                          c.swellingStrain + (c.cmaxRT > 0 ? "_chemical_potential" : "") + ".ups");
  Simulation& sim = run.simulation();
  ParticleSet& p = run.particles();
  const std::vector<Vec3> X = p.x;
  while (run.beforeEndTime()) sim.advance();

  const LithiatedSphereSolution solution(c);
  std::vector<LithiatedSphereExact> exact;
  double largestHoop = 0;
  for (const Vec3& x : X) {
    exact.push_back(solution.at(x.norm()));
    largestHoop = std::max(largestHoop, std::abs(exact.back().hoopStress));
  }
  LithiatedSphereResult r;
  r.interpolator = c.interpolator;
  r.swellingStrain = c.swellingStrain;
  r.cmaxRT = c.cmaxRT;
  r.cells = c.cells;
  r.h = c.radius / c.cells;
  r.particles = p.count();
  const ConstDiffusionParticles d(p);
  const std::vector<double>& concentration = d.concentration;
  double e[3] = {0, 0, 0}, ref[3] = {0, 0, 0};
  for (size_t i = 0; i < p.count(); ++i) {
    const double radius = X[i].norm();
    const Vec3 n = X[i] / radius;
    const double srr = n.dot(p.stress[i] * n), stt = 0.5 * (p.stress[i].trace() - srr);
    const LithiatedSphereExact& x = exact[i];
    const double q[3] = {concentration[i], srr, stt};
    const double qExact[3] = {x.concentration, x.radialStress, x.hoopStress};
    for (int k = 0; k < 3; ++k) {
      e[k] += p.volume[i] * (q[k] - qExact[k]) * (q[k] - qExact[k]);
      ref[k] += p.volume[i] * qExact[k] * qExact[k];
    }
    r.largestStressError = std::max(
        {r.largestStressError, std::abs(srr - x.radialStress), std::abs(stt - x.hoopStress)});
  }
  r.concentrationError = std::sqrt(e[0] / ref[0]);
  r.radialStressError = std::sqrt(e[1] / ref[1]);
  r.hoopStressError = std::sqrt(e[2] / ref[2]);
  r.largestStressError /= largestHoop;
  r.newtonIterations = sim.implicitStep().newtonCounts().iterations;
  r.steps = sim.step();
  r.finalTime = sim.time();
  r.wallSeconds = run.wallSeconds();
  return r;
}

}  // namespace anode
