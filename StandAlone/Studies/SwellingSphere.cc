#include "StandAlone/Studies/SwellingSphere.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "Components/MPM/Implicit/ImplicitStep.h"
#include "StandAlone/Studies/StudyInput.h"
#include "StandAlone/Studies/StudyTools.h"
#include "StandAlone/Studies/VerificationRun.h"

namespace anode {

double SwellingSphereCase::youngsModulus() const {
  return 9 * bulkModulus * shearModulus / (3 * bulkModulus + shearModulus);
}

double SwellingSphereCase::poissonsRatio() const {
  return (3 * bulkModulus - 2 * shearModulus) / (2 * (3 * bulkModulus + shearModulus));
}

double SwellingSphereCase::waveSpeed() const {
  return std::sqrt((bulkModulus + 4 * shearModulus / 3) / density);
}

SwellingSphereExact swellingSphereExact(const SwellingSphereCase& c, double r) {
  const double nu = c.poissonsRatio(), b = c.radius, s = r * r / (b * b);
  const double a = c.surfaceStrain / (5 * (1 - nu)), E = c.youngsModulus();
  return {a * ((1 + nu) * r * s + 2 * (1 - 2 * nu) * r), 2 * a * E * (1 - s),
          2 * a * E * (1 - 2 * s)};
}

std::string swellingSphereInput(const SwellingSphereCase& c) {
  if (c.cells < 2) throw std::invalid_argument("swelling sphere: need at least 2 cells per radius");
  requireInterpolator("swelling sphere", c.interpolator);
  const bool implicit = c.integrator == "implicit";
  if (!implicit && c.integrator != "explicit")
    throw std::invalid_argument("swelling sphere: integrator must be implicit or explicit");
  if (!implicit && !(c.endTime > 0))
    throw std::invalid_argument("swelling sphere: an explicit run needs an end time");
  const std::string res = std::to_string(c.particlesPerCell);

  std::string material;
  material += "      <material name=\"sphere\">\n";
  material += "        <density>" + upsNumber(c.density) + "</density>\n";
  material += upsElasticModel(c.bulkModulus, c.shearModulus, false);
  material += "        <geom_object>\n";
  material += "          <sphere label=\"sphere\"><origin>[0,0,0]</origin><radius>" +
              upsNumber(c.radius) + "</radius></sphere>\n";
  material += "          <res>[" + res + "," + res + "," + res + "]</res>\n";
  material += "          <velocity>[0,0,0]</velocity>\n";
  material += "          <temperature>0</temperature>\n";
  material += "        </geom_object>\n";
  material += "      </material>\n";

  std::string s;
  s += upsOpening(
      "An octant of a free elastic sphere relaxing the stress -3 K beta (r/b)^2 I of a\n"
      "     concentration c_s (r/b)^2 swollen with F held at I (Timoshenko & Goodier's\n"
      "     thermoelastic sphere); the stress is set on the particles by the run.",
      "Swelling sphere, " + c.integrator + ", " + c.interpolator + ", " + std::to_string(c.cells) +
          " cells per radius",
      "mpm");
  // Implicit: one quasi-static step of dt = 1 (the answer does not depend on dt).
  s += implicit
           ? upsTimeAndArchiver(1, 1, 1, "swelling_sphere.uda")
           : upsTimeAndArchiver(c.endTime, c.endTime, c.timestepMultiplier, "swelling_sphere.uda");
  s += "  <MPM>\n";
  s += "    <time_integrator>" + c.integrator + "</time_integrator>\n";
  if (implicit) s += "    <dynamic>false</dynamic>\n";
  if (implicit && c.hourglassStabilization >= 0)
    s += "    <hourglass_stabilization>" + upsNumber(c.hourglassStabilization) +
         "</hourglass_stabilization>\n";
  s += "    <interpolator>" + c.interpolator + "</interpolator>\n";
  if (c.damping > 0)
    s += "    <artificial_damping_coeff>" + upsNumber(c.damping) + "</artificial_damping_coeff>\n";
  s += "  </MPM>\n";
  s += upsMaterialProperties(material, "");
  s += upsSphereOctantGrid(c.radius, c.cells, c.interpolator);
  s += "</Uintah_specification>\n";
  return s;
}

SwellingSphereResult runSwellingSphere(const SwellingSphereCase& c) {
  const ThreadScope threads(c.threads);
  VerificationRun run("swelling sphere", swellingSphereInput(c),
                      "swelling_sphere_" + c.integrator + "_" + c.interpolator + "_" +
                          std::to_string(c.cells) + ".ups");
  Simulation& sim = run.simulation();
  ParticleSet& p = run.particles();
  const std::vector<Vec3> X = p.x;
  const double b = c.radius;
  for (size_t i = 0; i < p.count(); ++i) {
    const double s = X[i].squaredNorm() / (b * b);
    p.stress[i] = -3 * c.bulkModulus * c.surfaceStrain * s * Mat3::Identity();
  }
  while (run.beforeEndTime()) sim.advance();

  SwellingSphereResult r;
  r.interpolator = c.interpolator;
  r.integrator = c.integrator;
  r.cells = c.cells;
  r.h = b / c.cells;
  r.particles = p.count();
  double e[3] = {0, 0, 0}, ref[3] = {0, 0, 0}, maxU = 0;
  for (size_t i = 0; i < p.count(); ++i) {
    const double radius = X[i].norm();
    const Vec3 n = X[i] / radius, u = p.x[i] - X[i];
    const double ur = n.dot(u), srr = n.dot(p.stress[i] * n);
    const double stt = 0.5 * (p.stress[i].trace() - srr);
    const SwellingSphereExact exact = swellingSphereExact(c, radius);
    const double V = p.volume[i];
    const double q[3] = {ur, srr, stt};
    const double qExact[3] = {exact.radialDisplacement, exact.radialStress, exact.hoopStress};
    for (int k = 0; k < 3; ++k) {
      e[k] += V * (q[k] - qExact[k]) * (q[k] - qExact[k]);
      ref[k] += V * qExact[k] * qExact[k];
    }
    r.tangentialDisplacement = std::max(r.tangentialDisplacement, (u - ur * n).norm());
    maxU = std::max(maxU, std::abs(exact.radialDisplacement));
    r.r.push_back(radius);
    r.ur.push_back(ur);
    r.srr.push_back(srr);
    r.stt.push_back(stt);
  }
  r.radialDisplacementError = std::sqrt(e[0] / ref[0]);
  r.radialStressError = std::sqrt(e[1] / ref[1]);
  r.hoopStressError = std::sqrt(e[2] / ref[2]);
  r.tangentialDisplacement /= maxU;
  if (sim.mpm().problem().flags.implicit) {
    r.newtonIterations = sim.implicitStep().newtonCounts().iterations;
    r.krylovIterations = sim.implicitStep().newtonCounts().krylov;
  }
  r.steps = sim.step();
  r.finalTime = sim.time();
  r.wallSeconds = run.wallSeconds();
  return r;
}

double relativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("relativeDifference: sizes differ");
  double d = 0, n = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    d += (a[i] - b[i]) * (a[i] - b[i]);
    n += b[i] * b[i];
  }
  return std::sqrt(d / n);
}

std::vector<int> swellingSphereStudyCells() {
  return {4, 8, 12, 16, 24, 32};
}
std::vector<int> swellingSphereQuickCells() {
  return {4, 8, 16};
}

}  // namespace anode
