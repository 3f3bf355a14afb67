#include "StandAlone/Studies/DiffusionSlab1D.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Core/Util/Errors.h"
#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

std::string DiffusionSlabCase::variant() const {
  if (clampAfterStep) return dirichlet + "-clamp";
  return wideRange() ? dirichlet + "-wide" : dirichlet;
}

void setDiffusionSlabVariant(DiffusionSlabCase& c, const std::string& variant) {
  const std::vector<std::string> known = {"particle", "nodal", "particle-wide", "nodal-wide",
                                          "nodal-clamp"};
  if (std::find(known.begin(), known.end(), variant) == known.end())
    throw std::invalid_argument(
        "diffusion slab: unknown variant \"" + variant +
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
  requireInterpolator("diffusion slab", c.interpolator);
  if (c.dirichlet != "particle" && c.dirichlet != "nodal")
    throw std::invalid_argument("diffusion slab: dirichlet must be particle or nodal");
  std::string material;
  material += "      <material name=\"slab\">\n";
  material += "        <density>2.33e9</density>\n";
  material += "        <thermal_conductivity>0</thermal_conductivity>\n";
  material += "        <specific_heat>5</specific_heat>\n";
  material += upsElasticModel(6.5e6, 3.9e6, true);
  material += "        <diffusion_model type=\"jg\">\n";
  material += "          <diffusivity>" + upsNumber(c.diffusivity) + "</diffusivity>\n";
  material +=
      "          <min_concentration>" + upsNumber(c.minConcentration) + "</min_concentration>\n";
  material +=
      "          <max_concentration>" + upsNumber(c.maxConcentration) + "</max_concentration>\n";
  material += "        </diffusion_model>\n";
  material += upsParticleBox("slab", 1, c.h(), 298, true);
  material += "      </material>\n";
  std::string faces;
  faces += "      <Face side=\"x-\">\n";
  faces += "        <BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/>\n";
  faces +=
      "        <BCType id=\"all\" label=\"SD-Type\" var=\"Dirichlet\"><value>1</value></BCType>\n";
  faces += "      </Face>\n";
  faces += "      <Face side=\"x+\">\n";
  faces += "        <BCType id=\"all\" label=\"Symmetric\" var=\"symmetry\"/>\n";
  faces +=
      "        <BCType id=\"all\" label=\"SD-Type\" var=\"Dirichlet\"><value>0</value></BCType>\n";
  faces += "      </Face>\n";
  for (const char* side : {"y-", "y+", "z-", "z+"}) faces += upsSymmetricFace(side);

  const std::string comment =
      "1-D diffusion (paper section 2.2): c(x,0) = 0, c(0,t) = 1, c(1,t) = 0, D = " +
      upsNumber(c.diffusivity) +
      ".\n"
      "     Mechanics is inert: no swelling, zero stress, wave speed 0.07 so the mechanical dt\n"
      "     (14 h) is far above the diffusion dt (h^2/(2D)).";
  const std::string title = "1-D diffusion slab, " + c.interpolator + ", " +
                            std::to_string(c.cells) + " cells, " + c.dirichlet + " Dirichlet";

  std::string s;
  s += upsOpening(comment, title, "amrmpm");
  s += "  <AMR><useLockStep>true</useLockStep></AMR>\n";
  s += upsTimeAndArchiver(c.endTime, 1, c.timestepMultiplier, "diffusion_1d.uda");
  s += upsMPM(c.interpolator,
              "    <do_scalar_diffusion>true</do_scalar_diffusion>\n"
              "    <concentration_dirichlet>" +
                  c.dirichlet + "</concentration_dirichlet>\n");
  s += upsMaterialProperties(
      material, "      <diffusion_interface><type>null</type></diffusion_interface>\n");
  s += upsGrid(faces, 1, c.h(), c.cells, 1, "[1,1,1]");
  s += "</Uintah_specification>\n";
  return s;
}

DiffusionSlabResult runDiffusionSlab(const DiffusionSlabCase& c) {
  VerificationRun run("diffusion slab", diffusionSlabInput(c),
                      "diffusion_1d_" + c.interpolator + "_" + std::to_string(c.cells) + "_" +
                          c.variant() + ".ups");
  Simulation& sim = run.simulation();
  ParticleSet& p = run.particles();
  const DiffusionParticles d(p);

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
    const auto [lo, hi] = std::minmax_element(d.concentration.begin(), d.concentration.end());
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

  try {
    while (run.beforeEndTime()) {
      sim.advance();
      if (c.clampAfterStep)
        for (double& x : d.concentration) x = std::clamp(x, 0.0, 1.0);
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
    r.wallSeconds = run.wallSeconds();
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
    const double computed = d.concentration[i];
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
  r.wallSeconds = run.wallSeconds();
  return r;
}

std::vector<int> diffusionSlabStudyCells() {
  return {10, 20, 50, 100, 200, 500, 1000};
}
std::vector<int> diffusionSlabQuickCells() {
  return {20, 40, 80};
}

}  // namespace anode
