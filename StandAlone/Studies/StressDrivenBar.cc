#include "StandAlone/Studies/StressDrivenBar.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

double StressDrivenBarCase::stressPotential(double X) const {
  const double nu = (3 * bulkModulus - 2 * shearModulus) / (2 * (3 * bulkModulus + shearModulus));
  const double sxx = -density * gravity * (length - X);
  const double J = 1 + sxx / (bulkModulus + 4 * shearModulus / 3);
  return stressCoupling / cmaxRT * J * sxx * (1 + nu) / (3 * (1 - nu));
}

namespace {
double logistic(double u) {
  return 1 / (1 + std::exp(-u));
}
}  // namespace

StressDrivenBarEquilibrium::StressDrivenBarEquilibrium(const StressDrivenBarCase& c) : case_(c) {
  // ln A by bisection: the mean of c(X) over the bar (uniform mass per length) is c0.
  const int n = 20000;
  const auto mean = [&](double logA) {
    double sum = 0;
    for (int i = 0; i < n; ++i) sum += logistic(logA + c.stressPotential((i + 0.5) * c.length / n));
    return sum / n;
  };
  double lo = -50, hi = 50;
  for (int k = 0; k < 200; ++k) {
    logA_ = 0.5 * (lo + hi);
    (mean(logA_) < c.initialConcentration ? lo : hi) = logA_;
  }
}

double StressDrivenBarEquilibrium::concentration(double X) const {
  return logistic(logA_ + case_.stressPotential(X));
}

StressDrivenBarReference::StressDrivenBarReference(const StressDrivenBarCase& c, int cells)
    : h_(c.length / cells), c_(static_cast<size_t>(cells), c.initialConcentration) {
  std::vector<double> phi(c_.size()), flux(c_.size() + 1, 0.0);
  for (size_t i = 0; i < c_.size(); ++i) phi[i] = c.stressPotential((i + 0.5) * h_);
  const double limit = 0.4 * h_ * h_ / (2 * c.diffusivity);
  const long steps = static_cast<long>(std::ceil(c.endTime / limit));
  const double dt = c.endTime / static_cast<double>(steps);
  for (long s = 0; s < steps; ++s) {
    // The flux through each inner face (none through the ends), then each cell's change.
    for (size_t i = 1; i < c_.size(); ++i) {
      const double face = 0.5 * (c_[i - 1] + c_[i]);
      flux[i] =
          -c.diffusivity / h_ * ((c_[i] - c_[i - 1]) - face * (1 - face) * (phi[i] - phi[i - 1]));
    }
    for (size_t i = 0; i < c_.size(); ++i) c_[i] -= dt / h_ * (flux[i + 1] - flux[i]);
  }
}

double StressDrivenBarReference::concentration(double X) const {
  const double u = std::clamp(X / h_ - 0.5, 0.0, static_cast<double>(c_.size() - 1));
  const size_t i = std::min(static_cast<size_t>(u), c_.size() - 2);
  const double w = u - static_cast<double>(i);
  return (1 - w) * c_[i] + w * c_[i + 1];
}

std::string stressDrivenBarInput(const StressDrivenBarCase& c) {
  if (c.cells < 2) throw std::invalid_argument("stress-driven bar: need at least 2 cells");
  requireInterpolator("stress-driven bar", c.interpolator);
  const double h = c.length / c.cells;
  std::string material;
  material += "      <material name=\"bar\">\n";
  material += "        <density>" + upsNumber(c.density) + "</density>\n";
  material += upsElasticModel(c.bulkModulus, c.shearModulus, true);
  material += "        <diffusion_model type=\"chemical_potential\">\n";
  material += "          <diffusivity>" + upsNumber(c.diffusivity) + "</diffusivity>\n";
  material += "          <max_concentration>1</max_concentration>\n";
  material += "          <cmax_RT>" + upsNumber(c.cmaxRT) + "</cmax_RT>\n";
  material += "          <stress_coupling>" + upsNumber(c.stressCoupling) + "</stress_coupling>\n";
  material += "        </diffusion_model>\n";
  material += "        <geom_object>\n";
  material += "          <box label=\"bar\"><min>[0,0,0]</min><max>" + upsVector(c.length, h, h) +
              "</max></box>\n";
  material += "          <res>[2,1,1]</res>\n";
  material += "          <velocity>[0,0,0]</velocity>\n";
  material +=
      "          <concentration>" + upsNumber(c.initialConcentration) + "</concentration>\n";
  material += "        </geom_object>\n";
  material += "      </material>\n";

  std::string faces;
  for (const char* side : {"x-", "y-", "y+", "z-", "z+"}) faces += upsSymmetricFace(side);
  std::string s;
  s += upsOpening(
      "A bar standing under gravity, held laterally, its lithium redistributed by the\n"
      "     stress's part of the chemical potential (quasi-static steps, no swelling).",
      "Stress-driven bar, " + c.interpolator + ", " + std::to_string(c.cells) + " cells", "mpm");
  s += upsTimeAndArchiver(c.endTime, c.maxDt, 0.4, "stress_driven_bar.uda", c.firstDt);
  s += upsMPM(c.interpolator,
              "    <dynamic>false</dynamic>\n    <do_scalar_diffusion>true</do_scalar_diffusion>\n",
              "implicit");
  s += upsMaterialProperties(material, "", upsVector(-c.gravity, 0, 0));
  s += upsGrid(faces, c.length + 4 * h, h, c.cells + 4, 1, "[1,1,1]");
  s += "</Uintah_specification>\n";
  return s;
}

StressDrivenBarResult runStressDrivenBar(const StressDrivenBarCase& c, bool equilibrium) {
  const ThreadScope threads(c.threads);
  VerificationRun run(
      "stress-driven bar", stressDrivenBarInput(c),
      "stress_driven_bar_" + c.interpolator + "_" + std::to_string(c.cells) + ".ups");
  Simulation& sim = run.simulation();
  ParticleSet& p = run.particles();
  const std::vector<Vec3> X = p.x;
  while (run.beforeEndTime()) sim.advance();

  std::vector<double> exact(X.size());
  if (equilibrium) {
    const StressDrivenBarEquilibrium solution(c);
    for (size_t i = 0; i < X.size(); ++i) exact[i] = solution.concentration(X[i].x());
  } else {
    const StressDrivenBarReference solution(c);
    for (size_t i = 0; i < X.size(); ++i) exact[i] = solution.concentration(X[i].x());
  }
  StressDrivenBarResult r;
  r.interpolator = c.interpolator;
  r.cells = c.cells;
  r.h = c.length / c.cells;
  r.particles = p.count();
  const std::vector<double>& concentration = ConstDiffusionParticles(p).concentration;
  const auto [lo, hi] = std::minmax_element(concentration.begin(), concentration.end());
  r.concentrationRange = *hi - *lo;
  for (size_t i = 0; i < p.count(); ++i) {
    const double e = std::abs(concentration[i] - exact[i]);
    r.largestError = std::max(r.largestError, e);
    r.meanError += e / static_cast<double>(p.count());
  }
  r.newtonIterations = sim.implicitStep().newtonCounts().iterations;
  r.steps = sim.step();
  r.finalTime = sim.time();
  r.wallSeconds = run.wallSeconds();
  return r;
}

}  // namespace anode
