#include "StandAlone/Studies/FluxSlab.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Components/MPM/ReactiveFlow/FluxRestriction.h"
#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

namespace {

constexpr double kPi = 3.14159265358979323846;

std::string loadCurve(int id, const std::vector<std::pair<double, double>>& points) {
  std::string s = "        <load_curve>\n          <id>" + std::to_string(id) + "</id>\n";
  for (const auto& [t, J] : points)
    s += "          <time_point><time>" + upsNumber(t) + "</time><load>" + upsNumber(J) +
         "</load></time_point>\n";
  return s + "        </load_curve>\n";
}

double lithium(const ParticleSet& p) {
  double s = 0;
  const ConstDiffusionParticles d(p);
  for (size_t i = 0; i < p.count(); ++i) s += p.mass[i] * d.concentration[i];
  return s;
}

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

double robinSlabAnalytic(double x, double t, double cs, double k, double L, double D) {
  const double biot = k * L / D, fourier = D * t / (L * L);
  double sum = 0;
  for (int n = 0; n < 100000; ++n) {
    // The root of z sin z - Bi cos z in [n pi, n pi + pi/2], where it changes sign.
    double lo = n * kPi, hi = n * kPi + 0.5 * kPi;
    const double atLo = lo * std::sin(lo) - biot * std::cos(lo);
    for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      const double f = mid * std::sin(mid) - biot * std::cos(mid);
      ((f < 0) == (atLo < 0) ? lo : hi) = mid;
    }
    const double z = 0.5 * (lo + hi);
    const double decay = std::exp(-z * z * fourier);
    sum += 4 * std::sin(z) / (2 * z + std::sin(2 * z)) * decay * std::cos(z * x / L);
    if (decay < 1e-20 && n > 2) break;
  }
  return cs * (1 - sum);
}

std::string fluxSlabInput(const FluxSlabCase& c) {
  if (c.cells < 2) throw std::invalid_argument("flux slab: need at least 2 cells along x");
  if (c.thickness < 1) throw std::invalid_argument("flux slab: thickness must be >= 1 cell");
  requireInterpolator("flux slab", c.interpolator);
  const double L = c.length, h = L / c.cells, w = c.thickness * h;
  const std::string extra = c.interpolator == "linear" ? "[0,0,0]" : "[1,1,1]";
  std::vector<std::pair<double, double>> curve = c.loadCurve;
  if (curve.empty()) curve = {{0.0, c.surfaceRate > 0 ? c.heldConcentration : c.flux}};
  std::string material;
  material += "      <material name=\"slab\">\n";
  material += "        <density>" + upsNumber(c.density) + "</density>\n";
  material += upsElasticModel(c.bulkModulus, c.shearModulus, true);
  material += "        <diffusion_model type=\"jg\">\n";
  material += "          <diffusivity>" + upsNumber(c.diffusivity) + "</diffusivity>\n";
  material += "          <max_concentration>1.0</max_concentration>\n";
  material += "        </diffusion_model>\n";
  material += upsParticleBox("slab", L, w, 298, true);
  material += "      </material>\n";
  std::string faces;
  for (const char* side : {"x-", "x+", "y-", "y+", "z-", "z+"}) faces += upsSymmetricFace(side);

  std::string s;
  s += upsOpening(
      "Slab 0 <= x <= L with a constant lithium flux into its x+ face, insulated elsewhere\n"
      "     (Carslaw & Jaeger). Mechanics is inert: no swelling, no flow model, zero velocity.",
      "Flux slab, " + c.interpolator + ", " + std::to_string(c.cells) + " cells", "mpm");
  s += upsTimeAndArchiver(c.endTime(), c.endTime(), c.timestepMultiplier, "flux_slab.uda");
  s += upsMPM(c.interpolator,
              "    <do_scalar_diffusion>true</do_scalar_diffusion>\n"
              "    <use_load_curves>true</use_load_curves>\n");
  s += upsMaterialProperties(material, "");
  s += "  <PhysicalBC>\n";
  s += "    <MPM>\n";
  s += "      <scalar_flux>\n";
  if (c.surfaceRate > 0)
    s += "        <mode>potentiostatic</mode><surface_rate>" + upsNumber(c.surfaceRate) +
         "</surface_rate>\n";
  s += "        <geom_object><box label=\"x+ face\"><min>" + upsVector(L, 0, 0) + "</min><max>" +
       upsVector(L, w, w) + "</max></box></geom_object>\n";
  s += loadCurve(1, curve);
  s += "      </scalar_flux>\n";
  if (c.fluxAtZero != 0) {
    s += "      <scalar_flux>\n";
    s += "        <geom_object><box label=\"x- face\"><min>[0,0,0]</min><max>" +
         upsVector(0, w, w) + "</max></box></geom_object>\n";
    s += loadCurve(2, {{0.0, c.fluxAtZero}});
    s += "      </scalar_flux>\n";
  }
  s += "    </MPM>\n";
  s += "  </PhysicalBC>\n";
  s += upsGrid(faces, L, w, c.cells, c.thickness, extra);
  s += "</Uintah_specification>\n";
  return s;
}

FluxSlabResult runFluxSlab(const FluxSlabCase& c) {
  const ThreadScope threads(c.threads);
  VerificationRun run("flux slab", fluxSlabInput(c),
                      "flux_slab_" + c.interpolator + "_" + std::to_string(c.cells) + ".ups");
  Simulation& sim = run.simulation();
  const ParticleSet& p = run.particles();
  const ConstDiffusionParticles d(p);
  if (d.externalScalarFlux.size() != p.count())
    throw std::logic_error("flux slab: the flux BC was not assigned");

  FluxSlabResult r;
  r.interpolator = c.interpolator;
  r.cells = c.cells;
  r.particles = p.count();
  for (size_t i = 0; i < p.count(); ++i) r.fluxParticles += d.loadCurveID[i][0] > 0;
  r.lithium0 = lithium(p);
  r.minConcentration = 0;
  double maxFlagged = 0;

  while (run.beforeEndTime()) {
    const double dt = sim.dt();
    if (sim.step() == 0) r.dt = dt;
    double rate = 0;  // sum_p m_p rate_p of this step's start
    for (size_t i = 0; i < p.count(); ++i) rate += p.mass[i] * d.externalScalarFlux[i];
    r.injected += dt * rate;
    sim.advance();
    for (size_t i = 0; i < p.count(); ++i) {
      r.minConcentration = std::min(r.minConcentration, d.concentration[i]);
      if (d.loadCurveID[i][0] > 0) maxFlagged = std::max(maxFlagged, d.concentration[i]);
    }
  }
  r.lithium = lithium(p);
  r.maxRestrictionDeviation = 1 - fluxRestriction(maxFlagged);

  const double t = sim.time();
  double err2 = 0, ref2 = 0, maxErr = 0, maxRef = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    const double exact = c.surfaceRate > 0
                             ? robinSlabAnalytic(p.x[i].x(), t, c.heldConcentration, c.surfaceRate,
                                                 c.length, c.diffusivity)
                             : fluxSlabAnalytic(p.x[i].x(), t, c.flux, c.length, c.diffusivity);
    const double e = d.concentration[i] - exact;
    err2 += e * e;
    ref2 += exact * exact;
    if (p.x[i].x() <= 0.5 * c.length)
      r.interiorMaxError = std::max(r.interiorMaxError, std::abs(e));
    if (std::abs(e) > maxErr) {
      maxErr = std::abs(e);
      r.maxErrorAt = p.x[i].x();
    }
    r.x.push_back(p.x[i].x());
    r.c.push_back(d.concentration[i]);
    r.exact.push_back(exact);
    maxRef = std::max(maxRef, std::abs(exact));
    r.maxConcentration = std::max(r.maxConcentration, d.concentration[i]);
  }
  r.l2Error = std::sqrt(err2 / ref2);
  r.maxError = maxErr / maxRef;
  r.interiorMaxError /= maxRef;
  if (c.loadCurve.empty() && c.fluxAtZero == 0 && c.surfaceRate == 0) {
    const double w = c.thickness * c.length / c.cells;
    const double exactInjected = c.density * c.flux * t * w * w;
    r.injectedVsExact = r.injected / exactInjected - 1;
  }
  r.steps = sim.step();
  r.finalTime = t;
  r.wallSeconds = run.wallSeconds();
  return r;
}

std::vector<int> fluxSlabStudyCells() {
  return {8, 16, 32, 64, 128, 256};
}
std::vector<int> fluxSlabQuickCells() {
  return {8, 16, 32};
}

}  // namespace anode
