#include "StandAlone/OutputLabels.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>

namespace anode {

namespace {

using ParticleGetter = std::function<void(const MPMMaterial&, const Grid&, size_t, double*)>;
struct ParticleLabel {
  int components;
  ParticleGetter get;
};

void putVec(const Vec3& v, double* out) {
  for (int d = 0; d < 3; ++d) out[d] = v[d];
}

void putMat(const Mat3& m, double* out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[3 * r + c] = m(r, c);
}

const std::map<std::string, ParticleLabel>& particleLabels() {
  static const std::map<std::string, ParticleLabel> labels = {
      {"p.mass", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) { o[0] = m.particles.mass[i]; }}},
      {"p.volume", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) { o[0] = m.particles.volume[i]; }}},
      {"p.velocity", {3, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putVec(m.particles.velocity[i], o); }}},
      {"p.displacement", {3, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putVec(m.particles.displacement[i], o); }}},
      {"p.stress", {9, [](const MPMMaterial& m, const Grid&, size_t i, double* o) { putMat(m.particles.stress[i], o); }}},
      {"p.deformationMeasure", {9, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putMat(m.particles.F[i], o); }}},
      // Current physical particle domain F*size*diag(dx), computed only when written.
      {"p.scalefactor", {9, [](const MPMMaterial& m, const Grid& g, size_t i, double* o) {
         putMat(m.particles.F[i] * m.particles.size[i] * g.dx.asDiagonal().toDenseMatrix(), o); }}},
      {"p.size", {9, [](const MPMMaterial& m, const Grid&, size_t i, double* o) { putMat(m.particles.size[i], o); }}},
      // No external mechanical loads exist in this code: the external force is zero.
      {"p.externalforce", {3, [](const MPMMaterial&, const Grid&, size_t, double* o) { o[0] = o[1] = o[2] = 0; }}},
      {"p.plasticStrain", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.plasticStrain.empty() ? 0.0 : m.particles.plasticStrain[i]; }}},
      {"p.plasticStrainRate", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.plasticStrainRate.empty() ? 0.0 : m.particles.plasticStrainRate[i]; }}},
      {"p.concentration", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.concentration.empty() ? 0.0 : m.particles.concentration[i]; }}},
      {"p.diffusivity", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.diffusivity.empty() ? 0.0 : m.particles.diffusivity[i]; }}},
      {"p.concentrationGradient", {3, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putVec(m.particles.concentrationGradient.empty() ? Vec3(Vec3::Zero()) : m.particles.concentrationGradient[i], o); }}},
      // Flux BCs: the dc/dt they apply, the load curves of each particle (0: none) and the face
      // area of each of those curves.
      {"p.externalScalarFlux", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.externalScalarFlux.empty() ? 0.0 : m.particles.externalScalarFlux[i]; }}},
      {"p.loadCurveID", {3, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putVec(m.particles.loadCurveID.empty() ? Vec3(Vec3::Zero()) : Vec3(m.particles.loadCurveID[i].cast<double>()), o); }}},
      {"p.area", {3, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         putVec(m.particles.area.empty() ? Vec3(Vec3::Zero()) : m.particles.area[i], o); }}},
      // 1 for particles made by splitting (or split themselves), 0 otherwise.
      {"p.refinedMPM", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.refined.empty() ? 0.0 : m.particles.refined[i]; }}},
      // Removed Uintah labels kept as aliases: the concentration and the scaled pressure that the
      // diffusivity uses (Eq. 23), and the von Mises equivalent stress.
      {"p.concentrationInterp", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.particles.concentration.empty() ? 0.0 : m.particles.concentration[i]; }}},
      {"p.pressure_t1", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         o[0] = m.diffusion ? m.diffusion->scaledPressure(m.particles.stress[i]) : 0.0; }}},
      {"p.equivalentStress_t1", {1, [](const MPMMaterial& m, const Grid&, size_t i, double* o) {
         const Mat3& s = m.particles.stress[i];
         const Mat3 dev = s - s.trace() / 3.0 * Mat3::Identity();
         o[0] = std::sqrt(1.5) * dev.norm(); }}},
  };
  return labels;
}

const std::vector<std::string>& gridLabelNames() {
  static const std::vector<std::string> names = {"g.mass", "g.velocity", "g.velocity_star", "g.acceleration",
                                                 "g.internalforce", "g.concentration", "g.concentrationRate"};
  return names;
}

// Labels of the diffusion subcomponent: written only when it is on.
const std::vector<std::string>& diffusionLabels() {
  static const std::vector<std::string> names = {
      "p.concentration", "p.diffusivity", "p.concentrationGradient", "p.externalScalarFlux",
      "p.externalscalarflux", "p.loadCurveID", "p.area", "p.concentrationInterp", "p.pressure_t1",
      "g.concentration", "g.concentrationRate"};
  return names;
}

// Labels of Uintah features this code does not have yet (diffusion, splitting, ...).
const std::vector<std::string>& unsupportedLabels() {
  static const std::vector<std::string> names = {
      "p.concPrevious", "p.flux", "p.energy", "g.concentrationStar", "g.externalscalarflux", "g.concentrationnobc",
      "g.hydrostaticStressRD"};
  return names;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

LabelStatus classifyLabel(const std::string& label, bool diffusion) {
  if (!diffusion && contains(diffusionLabels(), label)) return LabelStatus::NeedsDiffusion;
  if (label == "p.externalscalarflux") return LabelStatus::Particle;
  if (label == "p.x" || label == "p.particleID" || particleLabels().count(label)) return LabelStatus::Particle;
  if (contains(gridLabelNames(), label)) return LabelStatus::Grid;
  if (contains(unsupportedLabels(), label)) return LabelStatus::Unsupported;
  return LabelStatus::Unknown;
}

ParticleData gatherParticles(const MPM& mpm, const std::vector<std::string>& labels) {
  ParticleData out;
  const size_t n = mpm.numParticles();
  out.points.reserve(3 * n);
  NamedArray material{"material", 1, {}, {}};
  NamedArray ids{"p.particleID", 1, {}, {}};
  const bool wantIds = contains(labels, "p.particleID");
  for (size_t m = 0; m < mpm.materials().size(); ++m) {
    const ParticleSet& p = mpm.materials()[m].particles;
    for (size_t i = 0; i < p.count(); ++i) {
      out.points.insert(out.points.end(), p.x[i].data(), p.x[i].data() + 3);
      material.integer.push_back(static_cast<int64_t>(m));
      if (wantIds) ids.integer.push_back(p.id[i]);
    }
  }
  out.arrays.push_back(std::move(material));
  if (wantIds) out.arrays.push_back(std::move(ids));
  for (const std::string& saved : labels) {
    // The label as saved in the input names the array; the old spelling reads the same field.
    const std::string label = saved == "p.externalscalarflux" ? "p.externalScalarFlux" : saved;
    auto it = particleLabels().find(label);
    if (it == particleLabels().end()) continue;
    NamedArray a{saved, it->second.components, std::vector<double>(n * it->second.components), {}};
    size_t offset = 0;
    for (const MPMMaterial& mat : mpm.materials()) {
      for (size_t i = 0; i < mat.particles.count(); ++i)
        it->second.get(mat, mpm.grid(), i, &a.real[(offset + i) * a.components]);
      offset += mat.particles.count();
    }
    out.arrays.push_back(std::move(a));
  }
  return out;
}

int particleLabelComponents(const std::string& label) {
  const auto it = particleLabels().find(label);
  return it == particleLabels().end() ? 0 : it->second.components;
}

ParticleData gatherParticlesWhere(const MPM& mpm, const std::vector<std::string>& labels,
                                  const std::function<bool(size_t material, const double* x)>& keep) {
  ParticleData out;
  std::vector<std::vector<size_t>> kept(mpm.materials().size());
  for (size_t m = 0; m < kept.size(); ++m) {
    const ParticleSet& p = mpm.materials()[m].particles;
    for (size_t i = 0; i < p.count(); ++i)
      if (keep(m, p.x[i].data())) {
        kept[m].push_back(i);
        out.points.insert(out.points.end(), p.x[i].data(), p.x[i].data() + 3);
      }
  }
  for (const std::string& label : labels) {
    const auto it = particleLabels().find(label);
    if (it == particleLabels().end()) throw std::logic_error("no particle label " + label);
    NamedArray a{label, it->second.components, std::vector<double>(out.count() * it->second.components), {}};
    size_t k = 0;
    for (size_t m = 0; m < kept.size(); ++m)
      for (size_t i : kept[m]) it->second.get(mpm.materials()[m], mpm.grid(), i, &a.real[a.components * k++]);
    out.arrays.push_back(std::move(a));
  }
  return out;
}

GridData gatherGrid(const MPM& mpm, const std::vector<std::string>& labels) {
  const Grid& g = mpm.grid();
  GridData out;
  const Vec3 origin = g.nodePosition(-g.extra.x(), -g.extra.y(), -g.extra.z());
  for (int d = 0; d < 3; ++d) {
    out.origin[d] = origin[d];
    out.spacing[d] = g.dx[d];
    out.dims[d] = g.nodes()[d];
  }
  const size_t nodes = g.numNodes();
  const size_t nm = mpm.gridFields().size();
  for (const std::string& label : labels)
    for (size_t m = 0; m < nm; ++m) {
      const GridFields& f = mpm.gridFields()[m];
      const std::string name = nm > 1 ? label + "_m" + std::to_string(m) : label;
      if (label == "g.concentration" || label == "g.concentrationRate") {
        const ConcentrationGridFields& c = mpm.diffusion()->gridFields()[m];
        out.arrays.push_back({name, 1, label == "g.concentration" ? c.concentration : c.concentrationRate, {}});
        continue;
      }
      if (label == "g.mass") {
        out.arrays.push_back({name, 1, f.mass, {}});
        continue;
      }
      const std::vector<Vec3>& v = label == "g.velocity"        ? f.velocity
                                   : label == "g.velocity_star" ? f.velocityStar
                                   : label == "g.acceleration"  ? f.acceleration
                                                                : f.internalForce;
      NamedArray a{name, 3, std::vector<double>(3 * nodes), {}};
      for (size_t k = 0; k < nodes; ++k) putVec(v[k], &a.real[3 * k]);
      out.arrays.push_back(std::move(a));
    }
  return out;
}

}  // namespace anode
