#include "StandAlone/FluxSlab.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "Components/MPM/Materials/Diffusion/ScalarFluxBC.h"
#include "StandAlone/Simulation.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string vec(double x, double y, double z) {
  return "[" + number(x) + "," + number(y) + "," + number(z) + "]";
}

std::string loadCurve(int id, const std::vector<std::pair<double, double>>& points) {
  std::string s = "        <load_curve>\n          <id>" + std::to_string(id) + "</id>\n";
  for (const auto& [t, J] : points)
    s += "          <time_point><time>" + number(t) + "</time><load>" + number(J) +
         "</load></time_point>\n";
  return s + "        </load_curve>\n";
}

double lithium(const ParticleSet& p) {
  double s = 0;
  for (size_t i = 0; i < p.count(); ++i) s += p.mass[i] * p.concentration[i];
  return s;
}

// Sets the OpenMP thread count for a scope (n = 0: unchanged).
class ThreadScope {
 public:
  explicit ThreadScope(int n) : saved_(omp_get_max_threads()), set_(n > 0) {
    if (set_) omp_set_num_threads(n);
  }
  ~ThreadScope() {
    if (set_) omp_set_num_threads(saved_);
  }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
  bool set_;
};

}  // namespace

double FluxSlabResult::balanceError() const {
  return std::abs(lithium - lithium0 - injected) / std::abs(injected);
}

double fluxSlabAnalytic(double x, double t, double J, double L, double D) {
  const double tau = D * t / (L * L);
  double sum = 0;
  for (int n = 1; n <= 100000; ++n) {
    const double decay = std::exp(-double(n) * n * kPi * kPi * tau);  // n * n overflows an int
    const double term = decay / (double(n) * n) * std::cos(n * kPi * x / L);
    sum += (n % 2 ? -term : term);
    // Remaining terms are below decay/n^2 each and fall faster than geometrically.
    if (decay < 1e-20 && n > 2) break;
  }
  return J * t / L + J * L / D * ((3 * x * x - L * L) / (6 * L * L) - 2 / (kPi * kPi) * sum);
}

std::string fluxSlabInput(const FluxSlabCase& c) {
  if (c.cells < 2) throw std::invalid_argument("flux slab: need at least 2 cells along x");
  if (c.thickness < 1) throw std::invalid_argument("flux slab: thickness must be >= 1 cell");
  if (c.interpolator != "linear" && c.interpolator != "gimp" && c.interpolator != "cpdi")
    throw std::invalid_argument("flux slab: interpolator must be linear, gimp or cpdi");
  const double L = c.length, h = L / c.cells, w = c.thickness * h;
  const std::string extra = c.interpolator == "linear" ? "[0,0,0]" : "[1,1,1]";
  std::vector<std::pair<double, double>> curve = c.loadCurve;
  if (curve.empty()) curve = {{0.0, c.flux}};
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"iso-8859-1\"?>\n";
  s += "<!-- Slab 0 <= x <= L with a constant lithium flux into its x+ face, insulated elsewhere\n"
       "     (Carslaw & Jaeger). Mechanics is inert: no swelling, no flow model, zero velocity. "
       "-->\n";
  s += "<Uintah_specification>\n";
  s += "  <Meta><title>Flux slab, " + c.interpolator + ", " + std::to_string(c.cells) +
       " cells</title></Meta>\n";
  s += "  <SimulationComponent type=\"mpm\"/>\n";
  s += "  <Time>\n";
  s += "    <initTime>0</initTime>\n";
  s += "    <maxTime>" + number(c.endTime()) + "</maxTime>\n";
  s += "    <delt_min>0</delt_min>\n";
  s += "    <delt_max>" + number(c.endTime()) + "</delt_max>\n";
  s += "    <timestep_multiplier>" + number(c.timestepMultiplier) + "</timestep_multiplier>\n";
  s += "    <end_at_max_time_exactly>true</end_at_max_time_exactly>\n";
  s += "  </Time>\n";
  s += "  <DataArchiver>\n";
  s += "    <filebase>flux_slab.uda</filebase>\n";
  s += "    <outputTimestepInterval>1000000</outputTimestepInterval>\n";
  s += "  </DataArchiver>\n";
  s += "  <MPM>\n";
  s += "    <time_integrator>explicit</time_integrator>\n";
  s += "    <interpolator>" + c.interpolator + "</interpolator>\n";
  s += "    <do_scalar_diffusion>true</do_scalar_diffusion>\n";
  s += "    <use_load_curves>true</use_load_curves>\n";
  s += "  </MPM>\n";
  s += "  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>\n";
  s += "  <MaterialProperties>\n";
  s += "    <MPM>\n";
  s += "      <material name=\"slab\">\n";
  s += "        <density>" + number(c.density) + "</density>\n";
  s += "        <constitutive_model type=\"rf_elastic_plastic\">\n";
  s += "          <bulk_modulus>" + number(c.bulkModulus) + "</bulk_modulus>\n";
  s += "          <shear_modulus>" + number(c.shearModulus) + "</shear_modulus>\n";
  s += "          <volume_expansion_coeff>0</volume_expansion_coeff>\n";
  s += "          <equation_of_state type=\"default_hypo\"/>\n";
  s += "        </constitutive_model>\n";
  s += "        <diffusion_model type=\"jg\">\n";
  s += "          <diffusivity>" + number(c.diffusivity) + "</diffusivity>\n";
  s += "          <max_concentration>1.0</max_concentration>\n";
  s += "        </diffusion_model>\n";
  s += "        <geom_object>\n";
  s += "          <box label=\"slab\"><min>[0,0,0]</min><max>" + vec(L, w, w) + "</max></box>\n";
  s += "          <res>[2,1,1]</res>\n";
  s += "          <velocity>[0,0,0]</velocity>\n";
  s += "          <temperature>298</temperature>\n";
  s += "          <concentration>0</concentration>\n";
  s += "        </geom_object>\n";
  s += "      </material>\n";
  s += "      <contact><type>null</type></contact>\n";
  s += "    </MPM>\n";
  s += "  </MaterialProperties>\n";
  s += "  <PhysicalBC>\n";
  s += "    <MPM>\n";
  s += "      <scalar_flux>\n";
  s += "        <geom_object><box label=\"x+ face\"><min>" + vec(L, 0, 0) + "</min><max>" +
       vec(L, w, w) + "</max></box></geom_object>\n";
  s += loadCurve(1, curve);
  s += "      </scalar_flux>\n";
  if (c.fluxAtZero != 0) {
    s += "      <scalar_flux>\n";
    s += "        <geom_object><box label=\"x- face\"><min>[0,0,0]</min><max>" + vec(0, w, w) +
         "</max></box></geom_object>\n";
    s += loadCurve(2, {{0.0, c.fluxAtZero}});
    s += "      </scalar_flux>\n";
  }
  s += "    </MPM>\n";
  s += "  </PhysicalBC>\n";
  s += "  <Grid>\n";
  s += "    <BoundaryConditions>\n";
  for (const char* side : {"x-", "x+", "y-", "y+", "z-", "z+"})
    s += std::string("      <Face side=\"") + side +
         "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>\n";
  s += "    </BoundaryConditions>\n";
  s += "    <Level>\n";
  s += "      <Box label=\"1\">\n";
  s += "        <lower>[0,0,0]</lower>\n";
  s += "        <upper>" + vec(L, w, w) + "</upper>\n";
  s += "        <resolution>[" + std::to_string(c.cells) + "," + std::to_string(c.thickness) + "," +
       std::to_string(c.thickness) + "]</resolution>\n";
  s += "        <extraCells>" + extra + "</extraCells>\n";
  s += "        <patches>[1,1,1]</patches>\n";
  s += "      </Box>\n";
  s += "    </Level>\n";
  s += "  </Grid>\n";
  s += "</Uintah_specification>\n";
  return s;
}

FluxSlabResult runFluxSlab(const FluxSlabCase& c) {
  const auto start = std::chrono::steady_clock::now();
  const ThreadScope threads(c.threads);
  RunOptions options;
  options.progress = false;
  const std::string name = "flux_slab_" + c.interpolator + "_" + std::to_string(c.cells) + ".ups";
  Simulation sim(fluxSlabInput(c), name, options);
  if (sim.mpm().materials().size() != 1) throw std::logic_error("flux slab: expected one material");
  const ParticleSet& p = sim.mpm().materials()[0].particles;
  if (p.externalScalarFlux.size() != p.count())
    throw std::logic_error("flux slab: the flux BC was not assigned");

  FluxSlabResult r;
  r.interpolator = c.interpolator;
  r.cells = c.cells;
  r.particles = p.count();
  for (size_t i = 0; i < p.count(); ++i) r.fluxParticles += p.loadCurveID[i][0] > 0;
  r.lithium0 = lithium(p);
  r.minConcentration = 0;
  double maxFlagged = 0;

  const double endTime = sim.timeControl().maxTime;
  while (sim.time() < endTime * (1 - 1e-12)) {
    const double dt = sim.dt();
    if (sim.step() == 0) r.dt = dt;
    double rate = 0;  // sum_p m_p rate_p of this step's start
    for (size_t i = 0; i < p.count(); ++i) rate += p.mass[i] * p.externalScalarFlux[i];
    r.injected += dt * rate;
    sim.advance();
    for (size_t i = 0; i < p.count(); ++i) {
      r.minConcentration = std::min(r.minConcentration, p.concentration[i]);
      if (p.loadCurveID[i][0] > 0) maxFlagged = std::max(maxFlagged, p.concentration[i]);
    }
  }
  r.lithium = lithium(p);
  r.maxRestrictionDeviation = 1 - fluxRestriction(maxFlagged);

  const double t = sim.time();
  double err2 = 0, ref2 = 0, maxErr = 0, maxRef = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    const double exact = fluxSlabAnalytic(p.x[i].x(), t, c.flux, c.length, c.diffusivity);
    const double e = p.concentration[i] - exact;
    err2 += e * e;
    ref2 += exact * exact;
    if (p.x[i].x() <= 0.5 * c.length)
      r.interiorMaxError = std::max(r.interiorMaxError, std::abs(e));
    if (std::abs(e) > maxErr) {
      maxErr = std::abs(e);
      r.maxErrorAt = p.x[i].x();
    }
    r.x.push_back(p.x[i].x());
    r.c.push_back(p.concentration[i]);
    r.exact.push_back(exact);
    maxRef = std::max(maxRef, std::abs(exact));
    r.maxConcentration = std::max(r.maxConcentration, p.concentration[i]);
  }
  r.l2Error = std::sqrt(err2 / ref2);
  r.maxError = maxErr / maxRef;
  r.interiorMaxError /= maxRef;
  if (c.loadCurve.empty() && c.fluxAtZero == 0) {
    const double w = c.thickness * c.length / c.cells;
    const double exactInjected = c.density * c.flux * t * w * w;
    r.injectedVsExact = r.injected / exactInjected - 1;
  }
  r.steps = sim.step();
  r.finalTime = t;
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<int> fluxSlabStudyCells() {
  return {8, 16, 32, 64, 128, 256};
}
std::vector<int> fluxSlabQuickCells() {
  return {8, 16, 32};
}

}  // namespace anode
