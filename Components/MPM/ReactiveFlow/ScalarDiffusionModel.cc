#include "Components/MPM/ReactiveFlow/ScalarDiffusionModel.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "Components/MPM/ReactiveFlow/ChemicalPotential.h"

namespace anode {

double nonLinear1Diffusivity(double D0, double alpha, double beta, double c,
                             double scaledPressure) {
  return D0 * std::exp(alpha * c - beta * scaledPressure);
}

double cubicDiffusivity(double D0, double Dmax, double c) {
  const double u = 1 - c;
  return D0 * u * u * u + Dmax * c * c * c;
}

namespace {

double maxOf(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, x);
  return m;
}

// p.diffusivity[i] = diffusivityOf(i, c_i / cmax) for every particle; returns the largest.
template <class F>
double setDiffusivity(ParticleSet& p, double cmax, F&& diffusivityOf) {
  const DiffusionParticles d(p);
  const long n = static_cast<long>(p.count());
  double dmax = 0;
#pragma omp parallel for schedule(static) reduction(max : dmax)
  for (long i = 0; i < n; ++i) {
    d.diffusivity[i] = diffusivityOf(i, d.concentration[i] / cmax);
    dmax = std::max(dmax, d.diffusivity[i]);
  }
  return dmax;
}

// jg: constant D (Fick).
class ConstantDiffusivity : public ScalarDiffusionModel {
 public:
  double computeDiffusivity(ParticleSet& p, double) override {
    const DiffusionParticles d(p);
    std::fill(d.diffusivity.begin(), d.diffusivity.end(), D0);
    return D0;
  }
};

// constant_rate: no flux; every node's concentration changes at the same rate.
class ConstantRate : public ScalarDiffusionModel {
 public:
  double rate = 0;
  double computeDiffusivity(ParticleSet& p, double) override {
    const DiffusionParticles d(p);
    std::fill(d.diffusivity.begin(), d.diffusivity.end(), 0.0);
    return 0.0;
  }
  double constantRate() const override { return rate; }
  bool diffuses() const override { return false; }
};

// The optional <diff_curve> of non_linear1: intervals in which D is computed ("in",
// "transition") or frozen at each particle's previous value ("out", delithiation, paper §4.7).
struct DiffusivityCurve {
  std::vector<double> times;
  std::vector<bool> frozen;
  size_t interval = 0;

  // Advances at most one interval per call, as Uintah does; true if D is frozen at time t.
  bool frozenAt(double t) {
    if (interval + 1 < times.size() - 1 && t > times[interval + 1]) ++interval;
    return frozen[interval];
  }
};

// non_linear1: paper Eq. 23, optionally pressure dependent.
class NonLinear1 : public ScalarDiffusionModel {
 public:
  double alpha = 0, beta = 0, pFloor = 0, pMax = 0, pScale = 1;
  bool usePressure = false;
  std::unique_ptr<DiffusivityCurve> curve;

  double scaledPressure(const Mat3& stress) const override {
    return usePressure ? std::clamp(-pScale * stress.trace() / 3.0, pFloor, pMax)
                       : 0.0;  // compression positive
  }

  double computeDiffusivity(ParticleSet& p, double t) override {
    const DiffusionParticles d(p);
    // Frozen: each particle keeps its diffusivity (D0 from the start, as in Uintah).
    if (curve && curve->frozenAt(t)) return maxOf(d.diffusivity);
    return setDiffusivity(p, maxConcentration, [&](long i, double c) {
      return nonLinear1Diffusivity(D0, alpha, beta, c, scaledPressure(p.stress[i]));
    });
  }

  // The diff_curve's current interval: it advances at most once per step, so neither a restart
  // nor a retaken step can recompute it from the time.
  std::vector<uint64_t> stepState() const override {
    return curve ? std::vector<uint64_t>{curve->interval} : std::vector<uint64_t>{};
  }
  void restoreStepState(const std::vector<uint64_t>& state) override {
    if (!curve) return;
    if (state.at(0) >= curve->times.size())
      throw std::runtime_error("the checkpoint's <diff_curve> interval is beyond the curve");
    curve->interval = state[0];
  }
};

// cubic: paper Eq. 24 (Berla et al.), for comparison with Eq. 23.
class Cubic : public ScalarDiffusionModel {
 public:
  double Dmax = 0;
  double computeDiffusivity(ParticleSet& p, double) override {
    return setDiffusivity(p, maxConcentration,
                          [&](long, double c) { return cubicDiffusivity(D0, Dmax, c); });
  }
  bool diffuses() const override { return D0 > 0 || Dmax > 0; }
};

// chemical_potential (ours; DESIGN.md §9, ChemicalPotential.h): J = -(D c (1 - c) / RT) grad mu,
// mu = RT ln(c / (1 - c)) - Omega tau_h, with a constant D. p.diffusivity holds the pass's
// diffusivity of grad c, D (1 + s J c (1 - c)) (effectiveDiffusivity).
class ChemicalPotentialDiffusion : public ScalarDiffusionModel {
 public:
  double perStress = 0;      // k = (Omega c_max) / (c_max R T)
  double stabilization = 0;  // s
  double computeDiffusivity(ParticleSet& p, double) override {
    return setDiffusivity(p, maxConcentration, [&](long i, double c) {
      return effectiveDiffusivity(D0, stabilization, p.F[i].determinant(), c);
    });
  }
  double stressPotentialPerStress() const override { return perStress; }
  double stressPotentialStabilization() const override { return stabilization; }
};

// <cmax_RT> and <stress_coupling> of chemical_potential: Omega c_max is 3 eta unless given (the
// swelling's own partial molar volume; another value is warned of).
std::unique_ptr<ScalarDiffusionModel> readChemicalPotential(const PSNode& node,
                                                            const DiffusionModelContext& context) {
  if (!context.implicit)
    node.unsupported(
        "diffusion_model type=\"chemical_potential\" on the explicit path (it needs "
        "<time_integrator>implicit)");
  auto m = std::make_unique<ChemicalPotentialDiffusion>();
  const double cmaxRT = node.require<double>("cmax_RT");
  if (!(cmaxRT > 0)) node.requireChild("cmax_RT").fail("<cmax_RT> must be positive");
  const double swelling = 3 * context.swellingCoefficient;
  double coupling = swelling;
  if (const PSNode given = node.child("stress_coupling")) {
    coupling = given.value<double>();
    if (!(coupling >= 0)) given.fail("<stress_coupling> must be >= 0");
    if (std::abs(coupling - swelling) > 1e-9 * std::max(coupling, swelling))
      given.warn("<stress_coupling> differs from 3 x <volume_expansion_coeff> = " +
                 std::to_string(swelling) +
                 ": the chemical potential's stress term and the swelling are not one free energy");
  }
  m->perStress = coupling / cmaxRT;
  m->stabilization =
      m->perStress *
      localSwellingPressure(context.swellingCoefficient, context.bulkModulus, context.shearModulus);
  return m;
}

std::unique_ptr<DiffusivityCurve> readCurve(const PSNode& node, double maxTime) {
  auto curve = std::make_unique<DiffusivityCurve>();
  for (const PSNode& point : node.children("time_point")) {
    const double t = point.require<double>("time");
    if (!curve->times.empty() && !(t > curve->times.back()))
      point.requireChild("time").fail("<diff_curve> times must be strictly increasing");
    const std::string dir = point.require<std::string>("flux_direction");
    if (dir != "in" && dir != "out" && dir != "transition")
      point.requireChild("flux_direction")
          .fail("<flux_direction> must be in, out or transition, found \"" + dir + "\"");
    curve->times.push_back(t);
    curve->frozen.push_back(dir == "out");
  }
  if (curve->times.size() < 2) node.fail("<diff_curve> needs at least two <time_point>");
  if (!(curve->times.back() > maxTime))
    node.fail(
        "the last <diff_curve> time must lie beyond <maxTime> (Uintah reads past the list "
        "otherwise)");
  return curve;
}

double positiveOrZero(const PSNode& node, const char* tag) {
  const double v = node.require<double>(tag);
  if (v < 0) node.requireChild(tag).fail("<" + std::string(tag) + "> must be >= 0");
  return v;
}

}  // namespace

std::unique_ptr<ScalarDiffusionModel> createDiffusionModel(const PSNode& node,
                                                           const DiffusionModelContext& context) {
  const std::string type = node.requireAttribute("type");
  std::unique_ptr<ScalarDiffusionModel> model;
  if (type == "jg") {
    model = std::make_unique<ConstantDiffusivity>();
  } else if (type == "constant_rate") {
    auto m = std::make_unique<ConstantRate>();
    m->rate = node.require<double>("constant_rate");
    model = std::move(m);
  } else if (type == "non_linear1") {
    auto m = std::make_unique<NonLinear1>();
    m->usePressure = node.require<bool>("use_pressure");
    m->alpha = node.require<double>("tuning1");
    m->beta = node.require<double>("tuning2");
    if (m->usePressure) {
      m->pFloor = node.require<double>("tuning3");
      m->pMax = node.require<double>("tuning4");
      m->pScale = node.require<double>("tuning5");
      if (m->pMax < m->pFloor)
        node.requireChild("tuning4").fail("<tuning4> (p_max) must be >= <tuning3>");
    } else {
      for (const char* inert : {"tuning3", "tuning4", "tuning5"}) node.acceptInert(inert);
    }
    if (const PSNode curve = node.child("diff_curve")) m->curve = readCurve(curve, context.maxTime);
    model = std::move(m);
  } else if (type == "cubic") {
    auto m = std::make_unique<Cubic>();
    m->Dmax = positiveOrZero(node, "max_diffusivity");
    model = std::move(m);
  } else if (type == "chemical_potential") {
    model = readChemicalPotential(node, context);
  } else if (type == "rf1" || type == "non_linear2") {
    node.fail("diffusion_model type=\"" + type +
              "\" is not supported; accepted: jg, constant_rate, non_linear1, cubic, "
              "chemical_potential");
  } else {
    node.fail("unknown diffusion_model type=\"" + type +
              "\"; accepted: jg, constant_rate, non_linear1, cubic, "
              "chemical_potential");
  }
  model->type = type;
  model->D0 = positiveOrZero(node, "diffusivity");
  model->maxConcentration = node.require<double>("max_concentration");
  if (!(model->maxConcentration > 0))
    node.requireChild("max_concentration").fail("<max_concentration> must be positive");
  model->minConcentration = node.get<double>("min_concentration", 0.0);
  if (model->minConcentration >= model->maxConcentration)
    node.requireChild("min_concentration")
        .fail("<min_concentration> must be below <max_concentration>");
  // Uintah clamps c to [min + conc_tolerance, max - conc_tolerance] after every step; this code
  // never clamps (docs/differences-from-uintah.md), which only a margin within the range
  // diagnostic's tolerance leaves unchanged.
  if (const PSNode tol = node.child("conc_tolerance"))
    if (tol.value<double>() >
        kConcentrationTolerance * (model->maxConcentration - model->minConcentration)) {
      std::ostringstream limit;
      limit << kConcentrationTolerance;
      tol.unsupported("<conc_tolerance> above " + limit.str() +
                      " of the concentration range (Uintah clamps c that far inside it)");
    }
  // The initial concentration comes from <geom_object><concentration>; Uintah never applies
  // this one.
  node.acceptInert("initial_concentration");
  if (const PSNode cond = node.child("conductivity_equation"))
    cond.unsupported("<conductivity_equation> (Gauss solver)");
  return model;
}

}  // namespace anode
