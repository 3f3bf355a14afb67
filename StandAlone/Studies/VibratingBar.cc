#include "StandAlone/Studies/VibratingBar.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

double kineticEnergy(const ParticleSet& p) {
  double e = 0;
  for (size_t i = 0; i < p.count(); ++i) e += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
  return e;
}

// V (p^2/(2K) + s:s/(4G)) per particle, p = tr(sigma)/3, s the deviator.
double strainEnergy(const ParticleSet& p, double K, double G) {
  double e = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    const double mean = p.stress[i].trace() / 3.0;
    const Mat3 s = p.stress[i] - mean * Mat3::Identity();
    e += p.volume[i] * (mean * mean / (2 * K) + s.squaredNorm() / (4 * G));
  }
  return e;
}

double centreOfMassVelocity(const ParticleSet& p) {
  double m = 0, mv = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    m += p.mass[i];
    mv += p.mass[i] * p.velocity[i].x();
  }
  return mv / m;
}

}  // namespace

double VibratingBarCase::waveSpeed() const {
  return std::sqrt((bulkModulus + 4.0 * shearModulus / 3.0) / density);
}
double VibratingBarCase::omega() const {
  return kPi / (2 * length) * waveSpeed();
}
double VibratingBarCase::period() const {
  return 2 * kPi / omega();
}

std::string vibratingBarInput(const VibratingBarCase& c) {
  if (c.cells < 2)
    throw std::invalid_argument("vibrating bar: need at least 2 cells along the bar");
  requireInterpolator("vibrating bar", c.interpolator);
  const double h = c.length / c.cells;
  // The free end sits inside the grid, which reaches ~1.25 L (at least two cells beyond L).
  const int gridCells = c.cells + std::max(2, (c.cells + 3) / 4);
  const std::string extra = c.interpolator == "linear" ? "[0,0,0]" : "[1,1,1]";
  std::string material;
  material += "      <material name=\"bar\">\n";
  material += "        <density>" + upsNumber(c.density) + "</density>\n";
  material += "        <thermal_conductivity>0</thermal_conductivity>\n";
  material += "        <specific_heat>1</specific_heat>\n";
  material += upsElasticModel(c.bulkModulus, c.shearModulus, false);
  material += upsParticleBox("bar", c.length, h, 294, false);
  material += "      </material>\n";
  std::string faces;
  faces += "      <Face side=\"x-\">\n";
  faces +=
      "        <BCType id=\"all\" label=\"Velocity\" "
      "var=\"Dirichlet\"><value>[0,0,0]</value></BCType>\n";
  faces += "      </Face>\n";
  for (const char* side : {"y-", "y+", "z-", "z+"}) faces += upsSymmetricFace(side);

  const bool implicit = c.implicitStepsPerPeriod > 0;
  std::string s;
  s += upsOpening(
      "Axial vibrating bar: fixed at x = 0, free at x = L, uniaxial strain (one cell\n"
      "     thick, Symmetric y and z faces). The caller sets the initial velocity.",
      "Axial vibrating bar, " + c.interpolator + ", " + std::to_string(c.cells) + " cells",
      implicit ? "impm" : "mpm");
  if (implicit) {
    // Newmark's steps of T / n (Newton's few iterations would double dt each step otherwise);
    // the displacement increments are ~1e-5 m, so Newton's criteria are set below ImpMPM's
    // absolute floors (docs/quasi-static.md) and it stops on the relative ratios.
    s += upsTimeAndArchiver(c.periods * c.period(), c.period() / c.implicitStepsPerPeriod, 1,
                            "vibrating_bar.uda");
    s += upsMPM(c.interpolator,
                "    <dynamic>true</dynamic>\n"
                "    <convergence_criteria_disp>1e-16</convergence_criteria_disp>\n"
                "    <convergence_criteria_energy>1e-16</convergence_criteria_energy>\n",
                "implicit");
  } else {
    s += upsTimeAndArchiver(c.periods * c.period(), 1, c.timestepMultiplier, "vibrating_bar.uda");
    s += upsMPM(c.interpolator, "");
  }
  s += upsMaterialProperties(material, "");
  s += upsGrid(faces, gridCells * h, h, gridCells, 1, extra);
  s += "</Uintah_specification>\n";
  return s;
}

VibratingBarResult runVibratingBar(const VibratingBarCase& c) {
  VerificationRun run("vibrating bar", vibratingBarInput(c),
                      "vibrating_bar_" + c.interpolator + "_" + std::to_string(c.cells) + ".ups");
  Simulation& sim = run.simulation();
  ParticleSet& p = run.particles();
  const double K = c.bulkModulus, G = c.shearModulus;

  const double L = c.length, v0 = c.amplitudeRatio * c.waveSpeed(), w = c.omega();
  const double k = kPi / (2 * L);
  for (size_t i = 0; i < p.count(); ++i) p.velocity[i] = Vec3(v0 * std::sin(k * p.x[i].x()), 0, 0);

  VibratingBarResult r;
  r.interpolator = c.interpolator;
  r.cells = c.cells;
  r.particles = p.count();
  const double vcmAmplitude = 2 * v0 / kPi;
  auto vcmError = [&](double t) {
    return std::abs(centreOfMassVelocity(p) - vcmAmplitude * std::cos(w * t)) / vcmAmplitude;
  };
  r.centreOfMassError = r.centreOfMassErrorStaggered = vcmError(0);
  const double E0 = kineticEnergy(p) + strainEnergy(p, K, G);
  std::vector<Vec3> previousVelocity;
  double previousStrainEnergy = strainEnergy(p, K, G), leapfrogE0 = 0;

  while (run.beforeEndTime()) {
    const double dt = sim.dt();
    previousVelocity = p.velocity;
    sim.advance();
    const double t = sim.time();
    r.centreOfMassError = std::max(r.centreOfMassError, vcmError(t));
    r.centreOfMassErrorStaggered = std::max(r.centreOfMassErrorStaggered, vcmError(t - dt / 2));
    const double se = strainEnergy(p, K, G);
    r.energyDrift = std::max(r.energyDrift, std::abs(kineticEnergy(p) + se - E0) / E0);
    double crossKinetic = 0;
    for (size_t i = 0; i < p.count(); ++i) {
      crossKinetic += 0.5 * p.mass[i] * previousVelocity[i].dot(p.velocity[i]);
      r.transverseVelocity = std::max({r.transverseVelocity, std::abs(p.velocity[i].y()) / v0,
                                       std::abs(p.velocity[i].z()) / v0});
    }
    const double leapfrogE = crossKinetic + previousStrainEnergy;
    if (sim.step() == 1) leapfrogE0 = leapfrogE;
    r.leapfrogEnergyDrift =
        std::max(r.leapfrogEnergyDrift, std::abs(leapfrogE - leapfrogE0) / leapfrogE0);
    previousStrainEnergy = se;
  }

  double err2 = 0, ref2 = 0;
  const double t = sim.time();
  for (size_t i = 0; i < p.count(); ++i) {
    const double X = p.x[i].x() - p.displacement[i].x();
    const double shape = v0 * std::sin(k * X);
    err2 += p.mass[i] * (p.velocity[i] - Vec3(shape * std::cos(w * t), 0, 0)).squaredNorm();
    ref2 += p.mass[i] * shape * shape;
  }
  r.velocityL2Error = std::sqrt(err2 / ref2);
  r.steps = sim.step();
  r.finalTime = t;
  r.wallSeconds = run.wallSeconds();
  return r;
}

std::vector<int> vibratingBarStudyCells() {
  return {8, 16, 32, 64, 128, 256, 512};
}
std::vector<int> vibratingBarQuickCells() {
  return {8, 16, 32};
}

}  // namespace anode
