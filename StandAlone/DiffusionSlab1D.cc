#include "StandAlone/DiffusionSlab1D.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "Core/Util/Errors.h"
#include "StandAlone/Simulation.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

std::string DiffusionSlabCase::variant() const {
  if (clampAfterStep) return dirichlet + "-clamp";
  return wideRange() ? dirichlet + "-wide" : dirichlet;
}

void setDiffusionSlabVariant(DiffusionSlabCase& c, const std::string& variant) {
  const std::vector<std::string> known = {"particle", "nodal", "particle-wide", "nodal-wide", "nodal-clamp"};
  if (std::find(known.begin(), known.end(), variant) == known.end())
    throw std::invalid_argument("diffusion slab: unknown variant \"" + variant +
                                "\"; accepted: particle, nodal, particle-wide, nodal-wide, nodal-clamp");
  c.dirichlet = variant.rfind("particle", 0) == 0 ? "particle" : "nodal";
  const bool wide = variant != "particle" && variant != "nodal";
  c.minConcentration = wide ? -1 : 0;
  c.maxConcentration = wide ? 2 : 1;
  c.clampAfterStep = variant == "nodal-clamp";
}

double diffusionSlabExact(double x, double t, double D, int terms) {
  double sum = 0;
  for (int n = 1; n <= terms; ++n)
    sum += std::exp(-D * kPi * kPi * n * n * t) * std::sin(n * kPi * x) / n;
  return (1 - x) - 2 / kPi * sum;
}

std::string diffusionSlabInput(const DiffusionSlabCase& c) {
  if (c.cells < 2) throw std::invalid_argument("diffusion slab: need at least 2 cells");
  if (c.interpolator != "linear" && c.interpolator != "gimp" && c.interpolator != "cpdi")
    throw std::invalid_argument("diffusion slab: interpolator must be linear, gimp or cpdi");
  if (c.dirichlet != "particle" && c.dirichlet != "nodal")
    throw std::invalid_argument("diffusion slab: dirichlet must be particle or nodal");
  const std::string hs = number(c.h());
  std::string s;
  s += "<?xml version=\"1.0\" encoding=\"iso-8859-1\"?>\n";
  s += "<!-- 1-D diffusion (paper section 2.2): c(x,0) = 0, c(0,t) = 1, c(1,t) = 0, D = " +
       number(c.diffusivity) +
       ".\n     Mechanics is inert: no swelling, zero stress, wave speed 0.07 so the mechanical dt\n"
       "     (14 h) is far above the diffusion dt (h^2/(2D)). -->\n";
  s += "<Uintah_specification>\n";
  s += "  <Meta><title>1-D diffusion slab, " + c.interpolator + ", " + std::to_string(c.cells) +
       " cells, " + c.dirichlet + " Dirichlet</title></Meta>\n";
  s += "  <SimulationComponent type=\"amrmpm\"/>\n";
  s += "  <AMR><useLockStep>true</useLockStep></AMR>\n";
  s += "  <Time>\n";
  s += "    <initTime>0</initTime>\n";
  s += "    <maxTime>" + number(c.endTime) + "</maxTime>\n";
  s += "    <delt_min>0</delt_min>\n";
  s += "    <delt_max>1</delt_max>\n";
  s += "    <timestep_multiplier>" + number(c.timestepMultiplier) + "</timestep_multiplier>\n";
  s += "    <end_at_max_time_exactly>true</end_at_max_time_exactly>\n";
  s += "  </Time>\n";
  s += "  <DataArchiver>\n";
  s += "    <filebase>diffusion_1d.uda</filebase>\n";
  s += "    <outputTimestepInterval>100000000</outputTimestepInterval>\n";
  s += "  </DataArchiver>\n";
  s += "  <MPM>\n";
  s += "    <time_integrator>explicit</time_integrator>\n";
  s += "    <interpolator>" + c.interpolator + "</interpolator>\n";
  s += "    <do_scalar_diffusion>true</do_scalar_diffusion>\n";
  s += "    <concentration_dirichlet>" + c.dirichlet + "</concentration_dirichlet>\n";
  s += "  </MPM>\n";
  s += "  <PhysicalConstants><gravity>[0,0,0]</gravity></PhysicalConstants>\n";
  s += "  <MaterialProperties>\n";
  s += "    <MPM>\n";
  s += "      <material name=\"slab\">\n";
  s += "        <density>2.33e9</density>\n";
  s += "        <thermal_conductivity>0</thermal_conductivity>\n";
  s += "        <specific_heat>5</specific_heat>\n";
  s += "        <constitutive_model type=\"rf_elastic_plastic\">\n";
  s += "          <bulk_modulus>6.5e6</bulk_modulus>\n";
  s += "          <shear_modulus>3.9e6</shear_modulus>\n";
  s += "          <volume_expansion_coeff>0</volume_expansion_coeff>\n";
  s += "          <equation_of_state type=\"default_hypo\"/>\n";
  s += "        </constitutive_model>\n";
  s += "        <diffusion_model type=\"jg\">\n";
  s += "          <diffusivity>" + number(c.diffusivity) + "</diffusivity>\n";
  s += "          <min_concentration>" + number(c.minConcentration) + "</min_concentration>\n";
  s += "          <max_concentration>" + number(c.maxConcentration) + "</max_concentration>\n";
  s += "        </diffusion_model>\n";
  s += "        <geom_object>\n";
  s += "          <box label=\"slab\"><min>[0,0,0]</min><max>[1," + hs + "," + hs + "]</max></box>\n";
  s += "          <res>[2,1,1]</res>\n";
  s += "          <velocity>[0,0,0]</velocity>\n";
  s += "          <temperature>298</temperature>\n";
  s += "          <concentration>0</concentration>\n";
  s += "        </geom_object>\n";
  s += "      </material>\n";
  s += "      <contact><type>null</type></contact>\n";
  s += "      <diffusion_interface><type>null</type></diffusion_interface>\n";
  s += "    </MPM>\n";
  s += "  </MaterialProperties>\n";
  s += "  <Grid>\n";
  s += "    <BoundaryConditions>\n";
  s += "      <Face side=\"x-\">\n";
  s += "        <BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/>\n";
  s += "        <BCType id=\"all\" label=\"SD-Type\" var=\"Dirichlet\"><value>1</value></BCType>\n";
  s += "      </Face>\n";
  s += "      <Face side=\"x+\">\n";
  s += "        <BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/>\n";
  s += "        <BCType id=\"all\" label=\"SD-Type\" var=\"Dirichlet\"><value>0</value></BCType>\n";
  s += "      </Face>\n";
  for (const char* side : {"y-", "y+", "z-", "z+"})
    s += std::string("      <Face side=\"") + side +
         "\"><BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/></Face>\n";
  s += "    </BoundaryConditions>\n";
  s += "    <Level>\n";
  s += "      <Box label=\"1\">\n";
  s += "        <lower>[0,0,0]</lower>\n";
  s += "        <upper>[1," + hs + "," + hs + "]</upper>\n";
  s += "        <resolution>[" + std::to_string(c.cells) + ",1,1]</resolution>\n";
  s += "        <extraCells>[1,1,1]</extraCells>\n";
  s += "        <patches>[1,1,1]</patches>\n";
  s += "      </Box>\n";
  s += "    </Level>\n";
  s += "  </Grid>\n";
  s += "</Uintah_specification>\n";
  return s;
}

DiffusionSlabResult runDiffusionSlab(const DiffusionSlabCase& c) {
  const auto start = std::chrono::steady_clock::now();
  RunOptions options;
  options.progress = false;
  const std::string name = "diffusion_1d_" + c.interpolator + "_" + std::to_string(c.cells) + "_" +
                           c.variant() + ".ups";
  Simulation sim(diffusionSlabInput(c), name, options);
  if (sim.mpm().materials().size() != 1) throw std::logic_error("diffusion slab: expected one material");
  ParticleSet& p = sim.mpm().materials()[0].particles;

  DiffusionSlabResult r;
  r.interpolator = c.interpolator;
  r.variant = c.variant();
  r.cells = c.cells;
  r.h = c.h();
  r.particles = p.count();
  r.firstDt = sim.dt();
  r.minConcentration = std::numeric_limits<double>::infinity();
  r.maxConcentration = -std::numeric_limits<double>::infinity();
  auto track = [&](double t) {
    const auto [lo, hi] = std::minmax_element(p.concentration.begin(), p.concentration.end());
    if (*lo < r.minConcentration) {
      r.minConcentration = *lo;
      r.minConcentrationTime = t;
    }
    if (*hi > r.maxConcentration) {
      r.maxConcentration = *hi;
      r.maxConcentrationTime = t;
    }
  };
  track(sim.time());

  const double endTime = sim.timeControl().maxTime;
  try {
    // end_at_max_time_exactly makes the last step land on endTime (up to rounding).
    while (sim.time() < endTime * (1 - 1e-12)) {
      sim.advance();
      if (c.clampAfterStep)
        for (double& x : p.concentration) x = std::clamp(x, 0.0, 1.0);
      track(sim.time());
    }
    r.completed = true;
  } catch (const SimulationError& e) {
    // The range check throws after the G2P update: the particles hold the offending state.
    track(sim.time() + sim.dt());
    const double above = r.maxConcentration - c.maxConcentration;
    const double below = c.minConcentration - r.minConcentration;
    if (above > 0 || below > 0) {
      char buf[160];
      std::snprintf(buf, sizeof buf, "stopped: c = %.7g at step %ld (t = %.4g)",
                    above > below ? r.maxConcentration : r.minConcentration, sim.step() + 1,
                    sim.time() + sim.dt());
      r.stopMessage = buf;
    } else {
      r.stopMessage = std::string("stopped: ") + e.what();  // not the range check
    }
    r.steps = sim.step() + 1;
    r.finalTime = sim.time() + sim.dt();
    r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }

  r.steps = sim.step();
  r.finalTime = sim.time();
  const size_t n = p.count();
  double sumRel2 = 0, sumAbs2 = 0, interiorAbs2 = 0, interiorRel2 = 0;
  size_t interior = 0;
  r.finalMinConcentration = std::numeric_limits<double>::infinity();
  r.finalMaxConcentration = -std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    const double x = p.x[i].x();
    const double exact = diffusionSlabExact(x, r.finalTime, c.diffusivity, c.fourierTerms);
    const double computed = p.concentration[i];
    const double err = computed - exact;
    const double rel = exact != 0 ? (exact - computed) / exact : 0.0;  // Eq. 14
    sumRel2 += rel * rel;
    sumAbs2 += err * err;
    if (std::abs(err) > r.maxAbsolute) {
      r.maxAbsolute = std::abs(err);
      r.maxAbsoluteAt = x;
    }
    if (x >= 0.1 && x <= 0.9) {
      interiorAbs2 += err * err;
      interiorRel2 += rel * rel;
      ++interior;
    }
    r.finalMinConcentration = std::min(r.finalMinConcentration, computed);
    r.finalMaxConcentration = std::max(r.finalMaxConcentration, computed);
    r.maxDisplacement = std::max(r.maxDisplacement, p.displacement[i].norm());
  }
  r.paperNorm = std::sqrt(sumRel2) / n;  // Eq. 15
  r.rmsRelative = std::sqrt(sumRel2 / n);
  r.rmsAbsolute = std::sqrt(sumAbs2 / n);
  r.interiorRmsAbsolute = interior ? std::sqrt(interiorAbs2 / interior) : 0.0;
  r.interiorRmsRelative = interior ? std::sqrt(interiorRel2 / interior) : 0.0;
  r.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::vector<int> diffusionSlabStudyCells() {
  return {10, 20, 50, 100, 200, 500, 1000};
}
std::vector<int> diffusionSlabQuickCells() {
  return {20, 40, 80};
}

}  // namespace anode
