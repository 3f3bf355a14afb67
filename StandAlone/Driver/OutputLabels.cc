#include "StandAlone/Driver/OutputLabels.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <stdexcept>
#include <type_traits>

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"

namespace anode {

namespace {

void putVec(const Vec3& v, double* out) {
  for (int d = 0; d < 3; ++d) out[d] = v[d];
}

// One particle array entry as real numbers (tensors row by row).
void put(double v, double* out) {
  out[0] = v;
}
void put(uint8_t v, double* out) {
  out[0] = v;
}
void put(int64_t v, double* out) {
  out[0] = static_cast<double>(v);
}
void put(const Vec3& v, double* out) {
  putVec(v, out);
}
void put(const Vec3i& v, double* out) {
  putVec(v.cast<double>(), out);
}
void put(const Mat3& m, double* out) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out[3 * r + c] = m(r, c);
}
// 0 for an array no label can save (its field's label is null).
template <class T>
constexpr int componentsOf() {
  if constexpr (std::is_same_v<T, Mat3>) return 9;
  if constexpr (std::is_same_v<T, Vec3> || std::is_same_v<T, Vec3i>) return 3;
  if constexpr (std::is_arithmetic_v<T>) return 1;
  return 0;
}

// Calls f(field) for every particle array any material may have: ParticleSet's one list, every
// constitutive model's state and the diffusion subcomponent's arrays.
template <class F>
void forEachParticleField(F&& f) {
  ParticleSet().forEachField([&f](const auto&, const auto& field) { f(field); });
  forEachModelStateField(f);
  DiffusionFields::forEach(f);
}

template <class T>
constexpr int componentsOf(const ParticleField<T>&) {
  return componentsOf<T>();
}

// The components of the particle array saved as `label`, 0 if none.
int fieldComponents(const std::string& label) {
  int components = 0;
  forEachParticleField([&](const auto& field) {
    if (field.label && label == field.label) components = componentsOf(field);
  });
  return components;
}

// Writes particle `indices` of the array saved as `label` to out, which holds zeros (left where
// the material does not have that array).
void copyField(const ParticleSet& p, const std::string& label, const std::vector<size_t>& indices,
               double* out) {
  p.forEachField([&](const auto& v, const auto& field) {
    if (!field.label || label != field.label || v.empty()) return;
    constexpr int n = componentsOf<typename std::decay_t<decltype(v)>::value_type>();
    if constexpr (n > 0)
      for (size_t k = 0; k < indices.size(); ++k) put(v[indices[k]], out + n * k);
  });
}

// Labels computed from the particle arrays (not stored): value of particle i of material m.
using DerivedGetter = std::function<void(const MPM&, size_t, size_t, double*)>;
struct DerivedLabel {
  int components;
  DerivedGetter get;
};

const std::map<std::string, DerivedLabel>& derivedLabels() {
  static const std::map<std::string, DerivedLabel> labels = {
      // Current physical particle domain F*size*diag(dx), computed only when written.
      {"p.scalefactor",
       {9,
        [](const MPM& mpm, size_t m, size_t i, double* o) {
          const ParticleSet& p = mpm.materials()[m].particles;
          put(Mat3(p.F[i] * p.size[i] * mpm.grid().dx.asDiagonal().toDenseMatrix()), o);
        }}},
      // No external mechanical loads exist in this code: the external force is zero.
      {"p.externalforce",
       {3, [](const MPM&, size_t, size_t, double* o) { o[0] = o[1] = o[2] = 0; }}},
      // Removed Uintah labels kept as aliases: the concentration and the scaled pressure that the
      // diffusivity uses (Eq. 23), and the von Mises equivalent stress.
      {"p.concentrationInterp",
       {1,
        [](const MPM& mpm, size_t m, size_t i, double* o) {
          const std::vector<double>* c = concentrationOf(mpm.materials()[m].particles);
          o[0] = c && !c->empty() ? (*c)[i] : 0.0;
        }}},
      {"p.pressure_t1",
       {1,
        [](const MPM& mpm, size_t m, size_t i, double* o) {
          const ReactiveFlow* diffusion = mpm.diffusion();
          o[0] = diffusion
                     ? diffusion->model(m).scaledPressure(mpm.materials()[m].particles.stress[i])
                     : 0.0;
        }}},
      {"p.equivalentStress_t1",
       {1,
        [](const MPM& mpm, size_t m, size_t i, double* o) {
          const Mat3& s = mpm.materials()[m].particles.stress[i];
          const Mat3 dev = s - s.trace() / 3.0 * Mat3::Identity();
          o[0] = std::sqrt(1.5) * dev.norm();
        }}},
  };
  return labels;
}

// The components of a particle label written as real numbers (0: none); the positions and IDs
// are written as points and integers.
int realComponents(const std::string& label) {
  if (label == "p.x" || label == "p.particleID") return 0;
  if (const int n = fieldComponents(label)) return n;
  const auto it = derivedLabels().find(label);
  return it == derivedLabels().end() ? 0 : it->second.components;
}

// The values of `label` (real components each) of the particles `indices` lists per material,
// in material order, as the array `name`.
NamedArray gatherLabel(const MPM& mpm, const std::string& name, const std::string& label,
                       int components, const std::vector<std::vector<size_t>>& indices) {
  size_t count = 0;
  for (const auto& i : indices) count += i.size();
  NamedArray a{name, components, std::vector<double>(count * components), {}};
  const bool stored = fieldComponents(label) > 0;
  size_t offset = 0;
  for (size_t m = 0; m < indices.size(); ++m) {
    const MPMMaterial& mat = mpm.materials()[m];
    double* out = a.real.data() + offset * components;  // a rank may hold none
    if (stored) {
      copyField(mat.particles, label, indices[m], out);
    } else {
      const DerivedLabel& d = derivedLabels().at(label);
      for (size_t k = 0; k < indices[m].size(); ++k)
        d.get(mpm, m, indices[m][k], out + components * k);
    }
    offset += indices[m].size();
  }
  return a;
}

const std::vector<std::string>& gridLabelNames() {
  static const std::vector<std::string> names = {"g.mass",
                                                 "g.velocity",
                                                 "g.velocity_star",
                                                 "g.acceleration",
                                                 "g.internalforce",
                                                 "g.concentration",
                                                 "g.concentrationRate",
                                                 "g.concentrationStar",
                                                 "g.concentrationnobc"};
  return names;
}

// Labels of the diffusion subcomponent, written only when it is on: its particle arrays (from
// the one list of them, with the error estimate of quasi-static steps with diffusion), the
// aliases computed from them and its grid fields.
bool isDiffusionLabel(const std::string& label) {
  bool diffusion = false;
  forEachParticleField([&](const auto& field) {
    if (field.label && label == field.label)
      diffusion = field.physics == Physics::Diffusion || field.physics == Physics::FluxBC ||
                  field.physics == Physics::CouplingHistory;
  });
  static const std::vector<std::string> others = {
      "p.externalscalarflux", "p.concentrationInterp", "p.pressure_t1",      "g.concentration",
      "g.concentrationRate",  "g.concentrationStar",   "g.concentrationnobc"};
  return diffusion || std::find(others.begin(), others.end(), label) != others.end();
}

// Labels Uintah saves that this code does not write: quantities it does not compute (the
// previous concentration, the particle flux vector, energies), computes with another meaning
// (g.externalscalarflux: here the flux source is handed to receivers, docs/diffusion.md step 5)
// or does not have (the hydrostatic stress of the Gauss solver).
const std::vector<std::string>& unsupportedLabels() {
  static const std::vector<std::string> names = {"p.concPrevious", "p.flux", "p.energy",
                                                 "g.externalscalarflux", "g.hydrostaticStressRD"};
  return names;
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

}  // namespace

LabelStatus classifyLabel(const std::string& label, bool diffusion) {
  if (!diffusion && isDiffusionLabel(label)) return LabelStatus::NeedsDiffusion;
  if (label == "p.externalscalarflux") return LabelStatus::Particle;
  if (label == "p.x" || label == "p.particleID" || realComponents(label) > 0)
    return LabelStatus::Particle;
  if (contains(gridLabelNames(), label)) return LabelStatus::Grid;
  if (contains(unsupportedLabels(), label)) return LabelStatus::Unsupported;
  return LabelStatus::Unknown;
}

bool isNodalConcentrationLabel(const std::string& label) {
  return label.rfind("g.concentration", 0) == 0;
}

ParticleData gatherParticles(const MPM& mpm, const std::vector<std::string>& labels) {
  ParticleData out;
  const size_t n = countParticles(mpm.materials());
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
  std::vector<std::vector<size_t>> all(mpm.materials().size());
  for (size_t m = 0; m < all.size(); ++m) {
    all[m].resize(mpm.materials()[m].particles.count());
    for (size_t i = 0; i < all[m].size(); ++i) all[m][i] = i;
  }
  for (const std::string& saved : labels) {
    // The label as saved in the input names the array; the old spelling reads the same field.
    const std::string label = saved == "p.externalscalarflux" ? "p.externalScalarFlux" : saved;
    const int components = realComponents(label);
    if (components > 0) out.arrays.push_back(gatherLabel(mpm, saved, label, components, all));
  }
  return out;
}

int particleLabelComponents(const std::string& label) {
  return realComponents(label);
}

ParticleData gatherParticlesWhere(
    const MPM& mpm, const std::vector<std::string>& labels,
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
    const int components = realComponents(label);
    if (components == 0) throw std::logic_error("no particle label " + label);
    out.arrays.push_back(gatherLabel(mpm, label, label, components, kept));
  }
  return out;
}

GridData gatherGrid(const MPM& mpm, const std::vector<std::string>& labels) {
  const Grid& g = mpm.grid();
  GridData out;
  // The whole grid's first node is the origin; a rank's window starts further in.
  const Vec3 origin = g.nodePosition(-g.extra.x(), -g.extra.y(), -g.extra.z());
  for (int d = 0; d < 3; ++d) {
    out.origin[d] = origin[d];
    out.spacing[d] = g.dx[d];
    out.dims[d] = g.nodes()[d];
    out.first[d] = g.trimLower[d];
  }
  const size_t nodes = g.numNodes();
  const size_t nm = mpm.stepGrid().fields.size();
  for (const std::string& label : labels)
    for (size_t m = 0; m < nm; ++m) {
      const GridFields& f = mpm.stepGrid().fields[m];
      const std::string name = nm > 1 ? label + "_m" + std::to_string(m) : label;
      if (isNodalConcentrationLabel(label)) {
        const ConcentrationGridFields& c = (*mpm.stepGrid().concentration)[m];
        const std::vector<double>& v = label == "g.concentration"       ? c.concentration
                                       : label == "g.concentrationRate" ? c.concentrationRate
                                       : label == "g.concentrationStar" ? c.concentrationStar
                                                                        : c.concentrationNoBC;
        out.arrays.push_back({name, 1, v, {}});
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
