#include "Components/MPM/MPM.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "Components/MPM/GridBoundaryConditions.h"
#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"
#include "Components/MPM/ParticleSplitting.h"
#include "Components/MPM/ProblemSize.h"
#include "Core/Util/Errors.h"

namespace anode {

namespace {

void readOtherPhysicalBCs(const PSNode& root) {
  const PSNode physical = root.child("PhysicalBC");
  if (!physical) return;
  const PSNode mpm = physical.child("MPM");
  if (!mpm) return;
  for (const PSNode& bc : mpm.children()) {
    if (bc.name() == "scalar_flux") continue;
    if (bc.name() == "pressure" || bc.name() == "force" || bc.name() == "heat_flux" ||
        bc.name() == "arches_heat_flux")
      bc.unsupported("<" + bc.name() + "> boundary condition");
    else
      bc.fail("unknown physical boundary condition <" + bc.name() + ">");
    bc.markSubtreeUsed();
  }
}

}  // namespace

void MPM::problemSetup(const PSNode& root, double initTime, double maxTime) {
  flags_ = MPMFlags::fromInput(root);
  const PSNode gridNode = root.requireChild("Grid");
  grid_ = Grid::fromInput(gridNode);
  if (flags_.interpolator != InterpolatorKind::Linear && (grid_.extra.array() < 1).any())
    gridNode.requireChild("Level")
        .requireChild("Box")
        .fail("interpolator \"" + interpolatorName(flags_.interpolator) +
              "\" reaches beyond the cell: it needs <extraCells>[1,1,1]");

  const PSNode matProps = root.requireChild("MaterialProperties");
  const PSNode mpmMats = matProps.requireChild("MPM");
  GeometryPieceFactory pieces;
  int64_t nextId = 0;
  const auto materialNodes = mpmMats.children("material");
  if (materialNodes.empty()) mpmMats.fail("<MaterialProperties><MPM> needs at least one <material>");
  for (const PSNode& m : materialNodes)
    materials_.push_back(MPMMaterial::fromInput(m, grid_, flags_, maxTime, pieces, nextId));
  nextParticleId_ = nextId;
  if (flags_.refineMaterial >= static_cast<int>(materials_.size()))
    root.requireChild("AMR").fail("the stretchRatio names material " + std::to_string(flags_.refineMaterial) +
                                  ", but there are " + std::to_string(materials_.size()));
  for (size_t m = 0; m < materials_.size(); ++m)
    if (flags_.refineParticles && (flags_.refineMaterial < 0 || flags_.refineMaterial == static_cast<int>(m)))
      materials_[m].particles.refined.assign(materials_[m].particles.count(), 0);
  contact_ = Contact::fromInput(mpmMats, static_cast<int>(materials_.size()));
  if (const PSNode iface = mpmMats.child("diffusion_interface")) {
    const std::string type = iface.get<std::string>("type", "null");
    if (type == "common") {
      if (!flags_.doScalarDiffusion) iface.fail("diffusion_interface \"common\" needs <do_scalar_diffusion>true");
      commonDiffusionInterface_ = materials_.size() > 1;
    } else if (type != "null") {
      iface.requireChild("type").fail("diffusion_interface type \"" + type + "\" is not supported; accepted: null, common");
    }
    iface.acceptInert("materials");
  }
  faceBCs_ = readFaceBCs(gridNode, static_cast<int>(materials_.size()), flags_.doScalarDiffusion);
  for (size_t m = 0; m < materials_.size(); ++m) {
    std::array<bool, 6> mirror{};
    for (const FaceBC& b : faceBCs_)
      if (b.kind == FaceBC::Kind::Symmetric && b.appliesTo(static_cast<int>(m)))
        mirror[2 * b.axis + b.side] = true;
    materials_[m].checkPiecesInsideGrid(grid_, mirror);
  }
  if (const PSNode physical = root.child("PhysicalBC")) {
    fluxBCs_ = ScalarFluxBC::fromInput(physical);
    if (!fluxBCs_.empty() && !flags_.doScalarDiffusion)
      physical.fail("<scalar_flux> needs <MPM><do_scalar_diffusion>true");
    if (flags_.autoCycle && fluxBCs_.empty())
    root.requireChild("MPM").requireChild("do_auto_cycle_bc").fail("<do_auto_cycle_bc>true needs <scalar_flux> boundary conditions");
  if (!fluxBCs_.empty() && !flags_.useLoadCurves)
      physical.fail("<scalar_flux> needs <MPM><use_load_curves>true (without it Uintah applies no flux)");
  }
  readOtherPhysicalBCs(root);

  checkProblemSize(gridNode, grid_, flags_, materials_.size(), numParticles(), omp_get_max_threads());
  const int nodes = grid_.numNodes();
  fields_.resize(materials_.size());
  for (auto& f : fields_) {
    f.resize(nodes);
    if (flags_.doScalarDiffusion) f.resizeDiffusion(nodes);
  }
  weights_.resize(materials_.size());
  capacity_.resize(materials_.size());
  threadScatter_.resize(omp_get_max_threads() > 1 ? omp_get_max_threads() : 0);
  for (auto& t : threadScatter_) {
    t.mass.resize(nodes);
    t.velocity.resize(nodes);
    t.internalForce.resize(nodes);
    if (flags_.doScalarDiffusion) t.resizeDiffusionScatter(nodes);
  }
  if (flags_.doScalarDiffusion) {
    findDirichletNodes();
    const std::vector<size_t> flagged = assignFluxBCs();
    bool anyFlux = false;
    for (size_t m = 0; m < materials_.size(); ++m)
      if (!materials_[m].particles.externalScalarFlux.empty()) {
        fields_[m].resizeFlux(nodes);
        anyFlux = true;
      }
    if (anyFlux)
      for (auto& t : threadScatter_) t.resizeFluxScatter(nodes);
    for (size_t b = 0; b < flagged.size(); ++b)
      if (flagged[b] == 0)
        root.child("PhysicalBC").child("MPM").children("scalar_flux")[b].requireChild("geom_object")
            .fail("this <scalar_flux> flags no particle: its geometry selects no surface particle of a "
                  "material that diffuses (selection rules in docs/diffusion.md), so its flux would "
                  "go nowhere");
    computeDiffusivity(initTime);
    applyExternalScalarFlux(initTime);
  }
}

std::vector<size_t> MPM::assignFluxBCs() {
  // Surface particles get, per BC that flags them, the area of the face that BC names
  // (UINTAH_UPS.md §3.1; unlike Uintah, not the area left by the last BC tested).
  std::vector<size_t> flagged(fluxBCs_.size(), 0);
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    ParticleSet& p = mat.particles;
    if (fluxBCs_.empty() || !mat.diffusion->diffuses()) {
      mat.surface = {};
      continue;  // a material without diffusivity gets no lithium
    }
    p.externalScalarFlux.assign(p.count(), 0.0);
    p.loadCurveID.assign(p.count(), Vec3i::Zero());
    p.area.assign(p.count(), Vec3::Zero());
    for (size_t i = 0; i < p.count(); ++i) {
      if (!mat.surface.onSurface[i]) continue;
      int slot = 0;
      for (size_t b = 0; b < fluxBCs_.size(); ++b) {
        const double a = fluxBCs_[b].flaggedArea(p.x[i], mat.surface.spacing[i], mat.surface.faceArea[i]);
        if (a <= 0) continue;
        ++flagged[b];
        if (slot == 3) continue;  // a particle holds at most 3 load curves
        p.loadCurveID[i][slot] = static_cast<int>(b) + 1;
        p.area[i][slot] = a;
        ++slot;
      }
    }
    mat.surface = {};
  }
  return flagged;
}

void MPM::splitParticles() {
  // The weights of the next step are laid out for the new particle count.
  for (MPMMaterial& mat : materials_)
    if (!mat.particles.refined.empty())
      splitStretchedParticles(mat.particles, grid_, flags_.stretchRatio, fluxBCs_, nextParticleId_);
}

size_t MPM::numParticles() const {
  size_t n = 0;
  for (const auto& m : materials_) n += m.particles.count();
  return n;
}

void MPM::timeAdvance(double t, double dt) {
  static const char* names[] = {"computeInterpolationWeights", "interpolateParticlesToGrid",
                                "exchangeMomentum+integrateGrid", "interpolateToParticles+computeStress",
                                "splitParticles", "diffusivity+externalScalarFlux"};
  int k[6];
  for (int i = 0; i < 6; ++i) k[i] = timers_.task(names[i]);
  { ScopedTimer s(timers_, k[0]); computeInterpolationWeights(); }        // 1
  { ScopedTimer s(timers_, k[1]); interpolateParticlesToGrid(); }         // 3, 5 (Eqs. 4, 5, 7, 18)
  {
    ScopedTimer s(timers_, k[2]);
    exchangeMomentumInterpolated();                                        // 4
    integrateGridMomentum(dt);                                             // 6
    if (flags_.doScalarDiffusion) integrateConcentration(dt);
    setGridBoundaryConditions(dt);
  }
  { ScopedTimer s(timers_, k[3]); interpolateToParticlesAndUpdate(dt); }  // 7 (Eq. 8), 8 (Eqs. 25-39)
  if (flags_.refineParticles) {
    ScopedTimer s(timers_, k[4]);
    splitParticles();
  }
  if (flags_.doScalarDiffusion) {
    ScopedTimer s(timers_, k[5]);
    checkConcentrationRange(t + dt);
    if (flags_.autoCycle) updateAutoCycle();
    computeDiffusivity(t + dt);     // D of the next step from this step's c and stress (Eq. 23)
    applyExternalScalarFlux(t + dt);  // flux rate of the next step (Eqs. 16-17)
  }
}

void MPM::computeInterpolationWeights() {
  previous_ = active_;
  long lowest = grid_.numNodes(), highest = -1;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    InterpolationWeights& W = weights_[m];
    const long n = static_cast<long>(p.count());
    std::vector<uint8_t>& capacity = capacity_[m];
    capacity.resize(n);
    if (flags_.interpolator == InterpolatorKind::CPDI) {
#pragma omp parallel for schedule(static)
      for (long i = 0; i < n; ++i) capacity[i] = static_cast<uint8_t>(cpdiCapacity(grid_, p.x[i], p.size[i], p.F[i]));
    } else {
      std::fill(capacity.begin(), capacity.end(), static_cast<uint8_t>(maxNodesPerParticle(flags_.interpolator)));
    }
    W.layOut(capacity);
    long firstOutside = n;
#pragma omp parallel for schedule(static) reduction(min : firstOutside, lowest) reduction(max : highest)
    for (long i = 0; i < n; ++i) {
      const size_t b = W.offset[i];
      int count = 0;
      switch (flags_.interpolator) {
        case InterpolatorKind::Linear:
          count = linearWeights(grid_, p.x[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
        case InterpolatorKind::GIMP:
          count = gimpWeights(grid_, p.x[i], p.size[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
        case InterpolatorKind::CPDI:
          count = cpdiWeights(grid_, p.x[i], p.size[i], p.F[i], &W.node[b], &W.weight[b], &W.gradient[b]);
          break;
      }
      if (count < 0) firstOutside = std::min(firstOutside, i);
      W.count[i] = static_cast<uint8_t>(std::max(count, 0));
      for (int e = 0; e < count; ++e) {
        lowest = std::min<long>(lowest, W.node[b + e]);
        highest = std::max<long>(highest, W.node[b + e]);
      }
    }
    if (firstOutside < n)
      throw SimulationError(describeParticle(materials_[m], m, firstOutside) +
                            " has left the grid (its interpolation support reaches beyond the last node)");
  }
  active_ = highest < 0 ? NodeRange{0, 0} : NodeRange{lowest, highest + 1};
}

void MPM::applyExternalScalarFlux(double t) {
  // Eqs. 16-17: rate_p = R(c_p) sum_k J_k(t) A_k / V_p, the restriction applied once.
  maxFluxRateCoefficient_ = 0;
  if (fluxBCs_.empty()) return;
  std::vector<double> J(fluxBCs_.size());
  for (size_t b = 0; b < fluxBCs_.size(); ++b) J[b] = fluxSign_ * fluxBCs_[b].load.at(t);
  for (MPMMaterial& mat : materials_) {
    ParticleSet& p = mat.particles;
    if (p.loadCurveID.empty()) continue;
    const double cmax = mat.diffusion->maxConcentration;
    const long n = static_cast<long>(p.count());
    double kmax = 0;
#pragma omp parallel for schedule(static) reduction(max : kmax)
    for (long i = 0; i < n; ++i) {
      double rate = 0, k = 0;
      for (int s = 0; s < 3 && p.loadCurveID[i][s] > 0; ++s) {
        rate += J[p.loadCurveID[i][s] - 1] * p.area[i][s];
        k += std::abs(J[p.loadCurveID[i][s] - 1]) * p.area[i][s];
      }
      // Eq. 17 restricts inflow as c -> 1; outflow is restricted the same way as c -> 0.
      const double c = p.concentration[i] / cmax;
      p.externalScalarFlux[i] = rate / p.volume[i] * fluxRestriction(c, rate >= 0) * cmax;
      kmax = std::max(kmax, k / p.volume[i]);
    }
    maxFluxRateCoefficient_ = std::max(maxFluxRateCoefficient_, kmax);
  }
}

namespace {

// Nodal accumulators one scatter writes into (the grid's own, or a thread's private copy).
struct ScatterTarget {
  double* mass;
  Vec3* momentum;
  Vec3* force;
  double* massConcentration;  // sum m c S (Eq. 5 numerator)
  double* diffusionRate;      // -sum m (grad S . D grad c) (Eq. 7 numerator)
  double* fluxSource;         // sum m rate S (Eq. 18 numerator)
  double* receiverWeightIn;   // sum m S R(c)
  double* receiverWeightOut;  // sum m S R(1 - c)

  static ScatterTarget of(GridFields& g) {
    const bool d = !g.concentration.empty(), f = !g.receiverWeightIn.empty();
    return {g.mass.data(), g.velocity.data(), g.internalForce.data(),
            d ? g.concentration.data() : nullptr, d ? g.diffusionRate.data() : nullptr,
            d ? g.externalScalarFlux.data() : nullptr, f ? g.receiverWeightIn.data() : nullptr,
            f ? g.receiverWeightOut.data() : nullptr};
  }
};

// The nodes a flux source reaches (those of the particles with a nonzero flux rate: bit 1 an
// inflow, bit 2 an outflow), and the material's max_concentration for the restriction of the
// particles that receive it there.
struct SourceNodes {
  const unsigned char* reached;
  double cmax;
};

// Marks, on nodes [begin, end), the nodes the flux sources of this step reach.
void markSourceNodes(const ParticleSet& p, const InterpolationWeights& W, std::vector<unsigned char>& reached,
                     long begin, long end) {
  std::fill(reached.begin() + begin, reached.begin() + end, 0);
  unsigned char* mark = reached.data();
  const long n = static_cast<long>(p.count());
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    const double rate = p.externalScalarFlux[i];
    if (rate == 0) continue;
    const unsigned char bit = rate > 0 ? 1 : 2;
    for (int e = 0; e < W.count[i]; ++e) {
      unsigned char& node = mark[W.node[W.offset[i] + e]];
      unsigned char seen;
#pragma omp atomic read
      seen = node;
      if (!(seen & bit)) {
#pragma omp atomic update
        node |= bit;
      }
    }
  }
}

// P2G of particles [begin, end): mass, momentum, internal force (f = -sum V sigma grad S) and,
// with diffusion, concentration, flux divergence (q_p = D_p grad c_p of the previous step) and
// the flux source with, on the nodes a source reaches, the weights of the particles that can
// receive it.
template <bool Diffusion, bool Flux>
void scatterToGrid(const ParticleSet& p, const InterpolationWeights& W, long begin, long end,
                   const SourceNodes& sources, const ScatterTarget& g) {
  for (long i = begin; i < end; ++i) {
    const double mp = p.mass[i];
    const Vec3 mv = mp * p.velocity[i];
    const Mat3 Vsigma = p.volume[i] * p.stress[i];
    const size_t b = W.offset[i];
    double mc = 0, mrate = 0, mIn = 0, mOut = 0;
    Vec3 mq = Vec3::Zero();
    if constexpr (Diffusion) {
      mc = mp * p.concentration[i];
      mq = mp * p.diffusivity[i] * p.concentrationGradient[i];
      if constexpr (Flux) {
        mrate = mp * p.externalScalarFlux[i];
        // A particle's weights matter only on the nodes a source reaches (elsewhere G = 0).
        unsigned char reached = 0;
        for (int e = 0; e < W.count[i]; ++e) reached |= sources.reached[W.node[b + e]];
        const double c = p.concentration[i] / sources.cmax;
        if (reached & 1) mIn = mp * fluxRestriction(c, true);
        if (reached & 2) mOut = mp * fluxRestriction(c, false);
      }
    }
    for (int e = 0; e < W.count[i]; ++e) {
      const int n = W.node[b + e];
      const double w = W.weight[b + e];
      const Vec3& grad = W.gradient[b + e];
      g.mass[n] += mp * w;
      g.momentum[n] += mv * w;
      g.force[n] -= Vsigma * grad;
      if constexpr (Diffusion) {
        g.massConcentration[n] += mc * w;
        g.diffusionRate[n] -= grad.dot(mq);
        if constexpr (Flux) {
          g.fluxSource[n] += mrate * w;
          g.receiverWeightIn[n] += mIn * w;
          g.receiverWeightOut[n] += mOut * w;
        }
      }
    }
  }
}

void scatter(bool diffusion, bool flux, const ParticleSet& p, const InterpolationWeights& W, long begin,
             long end, const SourceNodes& sources, const ScatterTarget& g) {
  if (!diffusion)
    scatterToGrid<false, false>(p, W, begin, end, sources, g);
  else if (!flux)
    scatterToGrid<true, false>(p, W, begin, end, sources, g);
  else
    scatterToGrid<true, true>(p, W, begin, end, sources, g);
}

template <class T>
void zero(std::vector<T>& v, long begin, long end, const T& value) {
  if (!v.empty()) std::fill(v.begin() + begin, v.begin() + end, value);
}

// Zeroes the fields a scatter accumulates into, on nodes [begin, end).
void clearScatterFields(GridFields& g, long begin, long end) {
  zero(g.mass, begin, end, 0.0);
  zero(g.velocity, begin, end, Vec3(Vec3::Zero()));
  zero(g.internalForce, begin, end, Vec3(Vec3::Zero()));
  zero(g.concentration, begin, end, 0.0);
  zero(g.diffusionRate, begin, end, 0.0);
  zero(g.externalScalarFlux, begin, end, 0.0);
  zero(g.receiverWeightIn, begin, end, 0.0);
  zero(g.receiverWeightOut, begin, end, 0.0);
}

// Zeroes every field on nodes [begin, end).
void clearAllFields(GridFields& g, long begin, long end) {
  clearScatterFields(g, begin, end);
  zero(g.velocityStar, begin, end, Vec3(Vec3::Zero()));
  zero(g.acceleration, begin, end, Vec3(Vec3::Zero()));
  zero(g.concentrationNoBC, begin, end, 0.0);
  zero(g.concentrationStar, begin, end, 0.0);
  zero(g.concentrationRate, begin, end, 0.0);
}

}  // namespace

void MPM::interpolateParticlesToGrid() {
  const long begin = active_.begin, end = active_.end;
  const bool diffusion = flags_.doScalarDiffusion;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    GridFields& g = fields_[m];
    const long n = static_cast<long>(p.count());
    const bool flux = !p.externalScalarFlux.empty();
    clearAllFields(g, std::min(begin, previous_.begin), std::max(end, previous_.end));
    SourceNodes sources{nullptr, 1.0};
    if (diffusion && flux) {
      markSourceNodes(p, weights_[m], g.sourceReached, std::min(begin, previous_.begin),
                      std::max(end, previous_.end));
      sources = {g.sourceReached.data(), materials_[m].diffusion->maxConcentration};
    }
    if (threadScatter_.empty()) {
      scatter(diffusion, flux, p, weights_[m], 0, n, sources, ScatterTarget::of(g));
    } else {
      // Each thread scatters a contiguous block of particles into its own buffer; the buffers are
      // summed in thread order, so results do not depend on scheduling.
      const int threads = static_cast<int>(threadScatter_.size());
#pragma omp parallel num_threads(threads)
      {
        const int t = omp_get_thread_num();
        GridFields& s = threadScatter_[t];
        clearScatterFields(s, begin, end);
        scatter(diffusion, flux, p, weights_[m], n * t / threads, n * (t + 1) / threads, sources,
                ScatterTarget::of(s));
#pragma omp barrier
#pragma omp for schedule(static)
        for (long k = begin; k < end; ++k)
          for (int u = 0; u < threads; ++u) {
            const GridFields& b = threadScatter_[u];
            g.mass[k] += b.mass[k];
            g.velocity[k] += b.velocity[k];
            g.internalForce[k] += b.internalForce[k];
            if (diffusion) {
              g.concentration[k] += b.concentration[k];
              g.diffusionRate[k] += b.diffusionRate[k];
              g.externalScalarFlux[k] += b.externalScalarFlux[k];
            }
            if (flux) {
              g.receiverWeightIn[k] += b.receiverWeightIn[k];
              g.receiverWeightOut[k] += b.receiverWeightOut[k];
            }
          }
      }
    }
#pragma omp parallel for schedule(static)
    for (long k = begin; k < end; ++k) {
      const bool massive = g.mass[k] > 0;
      g.velocity[k] = massive ? Vec3(g.velocity[k] / g.mass[k]) : Vec3::Zero();
      if (diffusion) g.concentration[k] = massive ? g.concentration[k] / g.mass[k] : 0.0;  // Eq. 5
    }
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.velocity);
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.internalForce);
    if (diffusion) {
      std::copy(g.concentration.begin() + begin, g.concentration.begin() + end, g.concentrationNoBC.begin() + begin);
      applyConcentrationBCs(grid_, faceBCs_, static_cast<int>(m), g.concentration);
    }
  }
  if (commonDiffusionInterface_) {
    // diffusion_interface common: one mass-weighted concentration for all materials at a node.
#pragma omp parallel for schedule(static)
    for (long k = begin; k < end; ++k) {
      double mass = 0, mc = 0;
      for (const GridFields& g : fields_) {
        mass += g.mass[k];
        mc += g.mass[k] * g.concentration[k];
      }
      if (mass > 0)
        for (GridFields& g : fields_) g.concentration[k] = mc / mass;
    }
  }
}

void MPM::exchangeMomentumInterpolated() {
  if (contact_.exchangeInterpolated)
    contact_.exchange(fields_, &GridFields::velocity, active_.begin, active_.end);
}

void MPM::integrateGridMomentum(double dt) {
  for (GridFields& g : fields_) {
#pragma omp parallel for schedule(static)
    for (long k = active_.begin; k < active_.end; ++k) {
      Vec3 a = Vec3::Zero();
      if (g.mass[k] > flags_.minimumMassForAcc && g.mass[k] > 0)
        a = g.internalForce[k] / g.mass[k] + flags_.gravity - flags_.artificialDampingCoeff * g.velocity[k];
      g.velocityStar[k] = g.velocity[k] + a * dt;
    }
  }
}

void MPM::integrateConcentration(double dt) {
  // Eq. 18: c* = c + (R/m + G/m) dt, then the SD-Type BCs on c*. Unlike Uintah (UINTAH_UPS.md
  // §6 step 7) the flux source is part of c*, so the next step's gradient sees the lithium that
  // entered. The nodal rate that drives the particles, (c° - c_noBC)/dt with c° = c + (R/m) dt
  // under the same BCs, leaves the source out: each node hands its G to the particles it reaches
  // in proportion to m S R, R the restriction of Eq. 17 at each particle's own c (R(1 - c) for
  // an outflow), so a full (or emptied) particle receives nothing from its neighbours' sources
  // and the node delivers all of G. externalScalarFlux becomes G / sum m S R.
  const long begin = active_.begin, end = active_.end;
  for (size_t m = 0; m < materials_.size(); ++m) {
    GridFields& g = fields_[m];
    const double constantRate = materials_[m].diffusion->constantRate();
    const bool source = !materials_[m].particles.externalScalarFlux.empty();
    std::vector<double>& withoutSource = source ? g.concentrationRate : g.concentrationStar;
#pragma omp parallel for schedule(static)
    for (long k = begin; k < end; ++k) {
      const double invMass = g.mass[k] > 0 ? 1.0 / g.mass[k] : 0.0;
      const double rate = invMass > 0 ? g.diffusionRate[k] * invMass + constantRate : 0.0;
      withoutSource[k] = g.concentration[k] + rate * dt;
      if (!source) continue;
      const double G = g.externalScalarFlux[k];
      g.concentrationStar[k] = withoutSource[k] + G * invMass * dt;
      const double receivers = G >= 0 ? g.receiverWeightIn[k] : g.receiverWeightOut[k];
      g.externalScalarFlux[k] = receivers > 0 ? G / receivers : 0.0;
    }
    applyConcentrationBCs(grid_, faceBCs_, static_cast<int>(m), g.concentrationStar);
    if (source) applyConcentrationBCs(grid_, faceBCs_, static_cast<int>(m), g.concentrationRate);
#pragma omp parallel for schedule(static)
    for (long k = begin; k < end; ++k)
      g.concentrationRate[k] = g.mass[k] > 0 ? (withoutSource[k] - g.concentrationNoBC[k]) / dt : 0.0;
  }
}

void MPM::setGridBoundaryConditions(double dt) {
  contact_.exchange(fields_, &GridFields::velocityStar, active_.begin, active_.end);
  for (size_t m = 0; m < fields_.size(); ++m) {
    GridFields& g = fields_[m];
    applyVelocityDirichlet(grid_, faceBCs_, static_cast<int>(m), g.velocityStar);
    applySymmetry(grid_, faceBCs_, static_cast<int>(m), g.velocityStar);
#pragma omp parallel for schedule(static)
    for (long k = active_.begin; k < active_.end; ++k) g.acceleration[k] = (g.velocityStar[k] - g.velocity[k]) / dt;
  }
}

void MPM::findDirichletNodes() {
  // 1 on the nodes an SD-Type Dirichlet condition sets (per material).
  std::vector<FaceBC> dirichlet;
  for (FaceBC b : faceBCs_)
    if (b.kind == FaceBC::Kind::ConcentrationDirichlet) {
      b.value = 1.0;
      dirichlet.push_back(b);
    }
  if (dirichlet.empty()) return;
  dirichletMask_.assign(materials_.size(), std::vector<double>(grid_.numNodes(), 0.0));
  for (size_t m = 0; m < materials_.size(); ++m)
    applyConcentrationBCs(grid_, dirichlet, static_cast<int>(m), dirichletMask_[m]);
}

void MPM::interpolateToParticlesAndUpdate(double dt) {
  const bool diffusion = flags_.doScalarDiffusion;
  // Particle treatment of SD-Type Dirichlet (docs/diffusion.md): a particle touching a boundary
  // node takes the grid solution c = sum S c* instead of Uintah's nodal rate.
  const bool particleDirichlet = flags_.particleDirichlet && !dirichletMask_.empty();
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    ParticleSet& p = mat.particles;
    const InterpolationWeights& W = weights_[m];
    const GridFields& g = fields_[m];
    const long n = static_cast<long>(p.count());
    const double rho0 = mat.density;
    // The stress update (Eqs. 25-39) runs in the same particle loop, dispatched once per material.
    const auto* model = dynamic_cast<const RFElasticPlastic*>(mat.model.get());
    if (!model) throw std::logic_error("interpolateToParticlesAndUpdate: unknown constitutive model");
    const bool yields = model->canYield(), swells = diffusion && model->swells();
    const double* wallMask = particleDirichlet ? dirichletMask_[m].data() : nullptr;
    const bool flux = diffusion && !p.externalScalarFlux.empty();
    const double cmax = diffusion ? mat.diffusion->maxConcentration : 1.0;
    long firstInverted = n;
#pragma omp parallel for schedule(static) reduction(min : firstInverted)
    for (long i = 0; i < n; ++i) {
      Mat3 gradV = Mat3::Zero();
      Vec3 acc = Vec3::Zero(), vel = Vec3::Zero(), gradC = Vec3::Zero();
      double cRate = 0, cGrid = 0, inflow = 0, outflow = 0;
      bool touchesWall = false;
      const size_t b = W.offset[i];
      for (int e = 0; e < W.count[i]; ++e) {
        const int k = W.node[b + e];
        const double w = W.weight[b + e];
        gradV += g.velocityStar[k] * W.gradient[b + e].transpose();
        acc += g.acceleration[k] * w;
        vel += g.velocityStar[k] * w;
        if (diffusion) {
          gradC += g.concentrationStar[k] * W.gradient[b + e];  // grad c for the next step's flux
          cRate += g.concentrationRate[k] * w;
          if (flux) {
            const double source = g.externalScalarFlux[k] * w;
            (source >= 0 ? inflow : outflow) += source;
          }
          if (wallMask) {
            cGrid += g.concentrationStar[k] * w;
            touchesWall |= wallMask[k] > 0;
          }
        }
      }
      // F^{n+1} = (I + L dt/N)^N F^n, subcycled when L dt is large (Uintah's rule).
      const int cycles = std::min(std::max(flags_.minimumSubcyclesForF,
                                           2 * static_cast<int>(gradV.norm() * dt)), 10000);
      const Mat3 increment = Mat3::Identity() + gradV * (dt / cycles);
      Mat3 F = p.F[i];
      for (int c = 0; c < cycles; ++c) F = increment * F;
      const double J = F.determinant();
      p.velocity[i] += acc * dt;
      p.x[i] += vel * dt;
      p.displacement[i] += vel * dt;
      p.volume[i] = p.mass[i] / rho0 * J;
      double dc = 0;
      if (diffusion) {
        p.concentrationGradient[i] = gradC;
        // Eq. 8 plus the flux source this particle receives (integrateConcentration); next to a
        // Dirichlet wall, a convex combination of nodal values instead.
        const double c0 = p.concentration[i];
        double received = 0;
        if (inflow != 0) received += inflow * fluxRestriction(c0 / cmax, true);
        if (outflow != 0) received += outflow * fluxRestriction(c0 / cmax, false);
        const double c = touchesWall ? cGrid : c0 + dt * (cRate + received);
        dc = c - p.concentration[i];
        p.concentration[i] = c;
      }
      if (!(J > 0)) {  // no stress update for an inverted particle: the run stops below
        firstInverted = std::min(firstInverted, i);
        p.F[i] = F;
        continue;
      }
      double ep = 0, epdot = 0;
      if (yields) {
        ep = p.plasticStrain[i];
        epdot = p.plasticStrainRate[i];
      }
      p.stress[i] = model->updateStress(p.stress[i], p.rotation[i], F, gradV, swells ? dc : 0.0, dt, ep, epdot);
      if (yields) {
        p.plasticStrain[i] = ep;
        p.plasticStrainRate[i] = epdot;
      }
      p.F[i] = F;
    }
    if (firstInverted < n) {
      std::ostringstream s;
      s << describeParticle(mat, m, firstInverted) << " has det F = " << p.F[firstInverted].determinant()
        << " (inverted or degenerate deformation)";
      throw SimulationError(s.str());
    }
  }
}

void MPM::updateAutoCycle() {
  // Mean (or min and max) normalised concentration of the particles that receive flux.
  double sum = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  size_t n = 0;
  for (const MPMMaterial& mat : materials_) {
    if (mat.particles.loadCurveID.empty()) continue;
    const double cmax = mat.diffusion->maxConcentration;
    for (double c : mat.particles.concentration) {
      sum += c / cmax;
      lo = std::min(lo, c / cmax);
      hi = std::max(hi, c / cmax);
    }
    n += mat.particles.count();
  }
  if (n == 0) return;
  const double mean = sum / n;
  if (fluxSign_ > 0 && (flags_.autoCycleUseMinMax ? lo : mean) > flags_.autoCycleMax) fluxSign_ = -1;
  if (fluxSign_ < 0 && (flags_.autoCycleUseMinMax ? hi : mean) < flags_.autoCycleMin) fluxSign_ = 1;
}

void MPM::computeDiffusivity(double t) {
  maxDiffusivity_ = 0;
  for (MPMMaterial& mat : materials_)
    maxDiffusivity_ = std::max(maxDiffusivity_, mat.diffusion->computeDiffusivity(mat.particles, t));
}

void MPM::checkConcentrationRange(double t) const {
  for (size_t m = 0; m < materials_.size(); ++m) {
    const ParticleSet& p = materials_[m].particles;
    const ScalarDiffusionModel& d = *materials_[m].diffusion;
    const double tol = kConcentrationTolerance * (d.maxConcentration - d.minConcentration);
    for (size_t i = 0; i < p.count(); ++i) {
      const double c = p.concentration[i];
      if (c >= d.minConcentration - tol && c <= d.maxConcentration + tol) continue;
      std::ostringstream s;
      s << describeParticle(materials_[m], m, i) << " has concentration " << c << " at t = " << t
        << ", outside [" << d.minConcentration << ", " << d.maxConcentration << "] by more than "
        << tol << " (no clamp is applied)";
      throw SimulationError(s.str());
    }
  }
}

double MPM::computeStableTimestep() const {
  double dt = std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const double modulus = mat.model->dilatationalModulus();
    const long n = static_cast<long>(p.count());
    double wx = 0, wy = 0, wz = 0;
#pragma omp parallel for schedule(static) reduction(max : wx, wy, wz)
    for (long i = 0; i < n; ++i) {
      const double c = std::sqrt(modulus * p.volume[i] / p.mass[i]);  // Eq. 41 with rho = m/V
      wx = std::max(wx, c + std::abs(p.velocity[i].x()));
      wy = std::max(wy, c + std::abs(p.velocity[i].y()));
      wz = std::max(wz, c + std::abs(p.velocity[i].z()));
    }
    dt = std::min({dt, grid_.dx.x() / wx, grid_.dx.y() / wy, grid_.dx.z() / wz});  // Eq. 43
  }
  if (maxDiffusivity_ > 0) dt = std::min(dt, grid_.dx.minCoeff() * grid_.dx.minCoeff() / (2 * maxDiffusivity_));  // Eq. 44
  if (maxFluxRateCoefficient_ > 0) dt = std::min(dt, 1.0 / (kRestrictionSlope * maxFluxRateCoefficient_));
  return dt;
}

void MPM::interpolateToGridForOutput() {
  computeInterpolationWeights();
  interpolateParticlesToGrid();
}

void MPM::releaseInterpolationWeights() {
  for (InterpolationWeights& w : weights_) w = InterpolationWeights();
}

StepSummary MPM::summarize() const {
  StepSummary s;
  s.minJ = std::numeric_limits<double>::infinity();
  s.maxJ = -std::numeric_limits<double>::infinity();
  s.diffusion = flags_.doScalarDiffusion;
  s.minConcentration = std::numeric_limits<double>::infinity();
  s.maxConcentration = -std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    for (size_t i = 0; i < p.count(); ++i) {
      s.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
      const double J = p.volume[i] * mat.density / p.mass[i];
      s.minJ = std::min(s.minJ, J);
      s.maxJ = std::max(s.maxJ, J);
      if (s.diffusion) {
        s.totalLithium += p.mass[i] * p.concentration[i];
        s.minConcentration = std::min(s.minConcentration, p.concentration[i]);
        s.maxConcentration = std::max(s.maxConcentration, p.concentration[i]);
      }
    }
    s.particles += p.count();
  }
  return s;
}

}  // namespace anode
