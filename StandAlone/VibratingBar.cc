#include "StandAlone/VibratingBar.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "StandAlone/Simulation.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

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
  if (c.interpolator != "linear" && c.interpolator != "gimp" && c.interpolator != "cpdi")
    throw std::invalid_argument("vibrating bar: interpolator must be linear, gimp or cpdi");
  const double h = c.length / c.cells;
  // The free end sits inside the grid, which reaches ~1.25 L (at least two cells beyond L).
  const int gridCells = c.cells + std::max(2, (c.cells + 3) / 4);
  const std::string extra = c.interpolator == "linear" ? "[0,0,0]" : "[1,1,1]";
  const std::string hs = number(h);
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"iso-8859-1\"?>\n";
  s += "<!-- Axial vibrating bar: fixed at x = 0, free at x = L, uniaxial strain (one cell\n"
       "     thick, Symmetric y and z faces). The caller sets the initial velocity. -->\n";
  s += "<Uintah_specification>\n";
  s += "  <Meta><title>Axial vibrating bar, " + c.interpolator + ", " + std::to_string(c.cells) +
       " cells</title></Meta>\n";
  s += "  <SimulationComponent type=\"mpm\"/>\n";
  s += "  <Time>\n";
  s += "    <initTime>0</initTime>\n";
  s += "    <maxTime>" + number(c.periods * c.period()) + "</maxTime>\n";
  s += "    <delt_min>0</delt_min>\n";
  s += "    <delt_max>1</delt_max>\n";
  s += "    <timestep_multiplier>" + number(c.timestepMultiplier) + "</timestep_multiplier>\n";
  s += "    <end_at_max_time_exactly>true</end_at_max_time_exactly>\n";
  s += "  </Time>\n";
  s += "  <DataArchiver>\n";
  s += "    <filebase>vibrating_bar.uda</filebase>\n";
  s += "    <outputTimestepInterval>1000000</outputTimestepInterval>\n";
  s += "  </DataArchiver>\n";
  s += "  <MPM>\n";
  s += "    <time_integrator>explicit</time_integrator>\n";
  s += "    <interpolator>" + c.interpolator + "</interpolator>\n";
  s += "  </MPM>\n";
  s += "  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>\n";
  s += "  <MaterialProperties>\n";
  s += "    <MPM>\n";
  s += "      <material name=\"bar\">\n";
  s += "        <density>" + number(c.density) + "</density>\n";
  s += "        <thermal_conductivity>0</thermal_conductivity>\n";
  s += "        <specific_heat>1</specific_heat>\n";
  s += "        <constitutive_model type=\"rf_elastic_plastic\">\n";
  s += "          <bulk_modulus>" + number(c.bulkModulus) + "</bulk_modulus>\n";
  s += "          <shear_modulus>" + number(c.shearModulus) + "</shear_modulus>\n";
  s += "          <equation_of_state type=\"default_hypo\"/>\n";
  s += "        </constitutive_model>\n";
  s += "        <geom_object>\n";
  s += "          <box label=\"bar\"><min>[0,0,0]</min><max>[" + number(c.length) + "," + hs + "," +
       hs + "]</max></box>\n";
  s += "          <res>[2,1,1]</res>\n";
  s += "          <velocity>[0,0,0]</velocity>\n";
  s += "          <temperature>294</temperature>\n";
  s += "        </geom_object>\n";
  s += "      </material>\n";
  s += "      <contact><type>null</type></contact>\n";
  s += "    </MPM>\n";
  s += "  </MaterialProperties>\n";
  s += "  <Grid>\n";
  s += "    <BoundaryConditions>\n";
  s += "      <Face side=\"x-\">\n";
  s += "        <BCType id=\"all\" label=\"Velocity\" "
       "var=\"Dirichlet\"><value>[0,0,0]</value></BCType>\n";
  s += "      </Face>\n";
  for (const char* side : {"y-", "y+", "z-", "z+"})
    s += std::string("      <Face side=\"") + side +
         "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>\n";
  s += "    </BoundaryConditions>\n";
  s += "    <Level>\n";
  s += "      <Box label=\"1\">\n";
  s += "        <lower>[0,0,0]</lower>\n";
  s += "        <upper>[" + number(gridCells * h) + "," + hs + "," + hs + "]</upper>\n";
  s += "        <resolution>[" + std::to_string(gridCells) + ",1,1]</resolution>\n";
  s += "        <extraCells>" + extra + "</extraCells>\n";
  s += "        <patches>[1,1,1]</patches>\n";
  s += "      </Box>\n";
  s += "    </Level>\n";
  s += "  </Grid>\n";
  s += "</Uintah_specification>\n";
  return s;
}

VibratingBarResult runVibratingBar(const VibratingBarCase& c) {
  const auto start = std::chrono::steady_clock::now();
  RunOptions options;
  options.progress = false;
  const std::string name =
      "vibrating_bar_" + c.interpolator + "_" + std::to_string(c.cells) + ".ups";
  Simulation sim(vibratingBarInput(c), name, options);
  if (sim.mpm().materials().size() != 1)
    throw std::logic_error("vibrating bar: expected one material");
  ParticleSet& p = sim.mpm().materials()[0].particles;
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

  const double endTime = sim.timeControl().maxTime;
  // end_at_max_time_exactly makes the last step land on endTime (up to rounding).
  while (sim.time() < endTime * (1 - 1e-12)) {
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
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<int> vibratingBarStudyCells() {
  return {8, 16, 32, 64, 128, 256, 512};
}
std::vector<int> vibratingBarQuickCells() {
  return {8, 16, 32};
}

}  // namespace anode
