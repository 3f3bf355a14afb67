#include "Components/MPM/MPM.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include "Components/MPM/Materials/ConstitutiveModels/ConcreteModels.h"
#include "Components/MPM/Materials/MaterialOverlap.h"
#include "Components/MPM/ParticleLoops.h"
#include "Components/MPM/ParticleSplitting.h"
#include "Components/MPM/PhysicalBCs.h"
#include "Components/MPM/ProblemSize.h"
#include "Components/MPM/ReactiveFlow/ConcentrationSubstep.h"
#include "Components/MPM/SwellingRoom.h"
#include "Core/Parallel/StopTogether.h"
#include "Core/Util/Errors.h"

namespace anode {

void MPM::problemSetup(const PSNode& root, double initTime, double maxTime, bool withParticles,
                       const std::function<void()>& problemRead) {
  flags_ = MPMFlags::fromInput(root);
  distributed_ = Communicator::size() > 1;
  initTime_ = initTime;
  const PSNode gridNode = root.requireChild("Grid");
  grid_ = Grid::fromInput(gridNode);
  if (flags_.interpolator != InterpolatorKind::Linear && (grid_.extra.array() < 1).any())
    gridNode.requireChild("Level").requireChild("Box").fail(
        "interpolator \"" + interpolatorName(flags_.interpolator) +
        "\" reaches beyond the cell: it needs <extraCells>[1,1,1]");

  const PSNode matProps = root.requireChild("MaterialProperties");
  const PSNode mpmMats = matProps.requireChild("MPM");
  GeometryPieceFactory pieces;
  const auto materialNodes = mpmMats.children("material");
  if (materialNodes.empty())
    mpmMats.fail("<MaterialProperties><MPM> needs at least one <material>");
  seeds_.assign(materialNodes.size(), {});
  for (size_t m = 0; m < materialNodes.size(); ++m)
    materials_.push_back(
        MPMMaterial::fromInput(materialNodes[m], grid_, flags_, pieces, seeds_[m]));
  // Each geom_object's particles are numbered on from the objects' before it, in input order.
  for (MaterialSeeds& s : seeds_)
    for (MaterialSeeds::Object& object : s.objects) {
      object.firstId = nextParticleId_;
      nextParticleId_ += object.total;
    }
  if (flags_.refineMaterial >= static_cast<int>(materials_.size()))
    root.requireChild("AMR").fail("the stretchRatio names material " +
                                  std::to_string(flags_.refineMaterial) + ", but there are " +
                                  std::to_string(materials_.size()));
  contact_ = Contact::fromInput(mpmMats, static_cast<int>(materials_.size()));
  const PhysicalBCs physical = readPhysicalBCs(root);
  diffusion_ = ReactiveFlow::fromInput(root, flags_, materials_, maxTime, physical);
  gridBCs_ = readGridBoundaryConditions(gridNode, static_cast<int>(materials_.size()),
                                        [this](const BCType& bc) {
                                          if (diffusion_)
                                            diffusion_->readConcentrationBC(bc);
                                          else
                                            ConcentrationBC::rejectWithoutDiffusion(bc);
                                        });
  for (size_t m = 0; m < materials_.size(); ++m)
    seeds_[m].checkPiecesInsideGrid(grid_, gridBCs_.symmetryPlanes(static_cast<int>(m)));
  swellingNotes_ = swellingRoomNotes(grid_, gridBCs_, materials_, seeds_, diffusion_.get());
  warnOfOverlaps(grid_, materials_, seeds_);
  if (problemRead) problemRead();

  // This rank's particles: those of its box (the whole grid on one rank) and, while the flux
  // particles are flagged, those setup needs around it.
  whole_ = grid_;
  const CellBox box = withParticles ? setupBox() : CellBox{};
  const CellBox region = grownBySetupReach(box);
  checkParticlesOfRank(region);
  for (size_t m = 0; m < materials_.size(); ++m) {
    materials_[m].placeParticles(seeds_[m], grid_, region);
    // A smooth piece's layout of every particle is no longer needed once they are placed (a
    // count for describeDecomposition keeps it).
    if (withParticles)
      for (MaterialSeeds::Object& object : seeds_[m].objects) object.smoothLayout = {};
    if (flags_.refineParticles &&
        (flags_.refineMaterial < 0 || flags_.refineMaterial == static_cast<int>(m)))
      materials_[m].particles.enable(Physics::Splitting);
    if (flags_.implicit && flags_.implicit->dynamic)
      materials_[m].particles.enable(Physics::Inertia);
  }
  checkProblemSize(gridNode, grid_, flags_, materials_.size(), numParticles(),
                   omp_get_max_threads());
  if (diffusion_) diffusion_->initialize(root, grid_, materials_, seeds_, box, region, initTime);
  if (region.lower != box.lower || region.upper != box.upper) keepParticlesOfBox(box);
  reordering_.resize(materials_.size());
  particlesToGridTask_ = timers_.task("interpolateParticlesToGrid");
  communicationTask_ = distributed_ ? timers_.task("communication") : -1;
}

void MPM::distributeOverRanks(Collective) {
  if (Communicator::size() == 1) {
    decompose(true);
  } else {
    // problemSetup drew the boxes and placed each rank's particles in its own.
    ++layoutGeneration_;
    ghostWidth_ = computeGhostWidth(false);
    layOutWindow();
  }
  if (diffusion_) diffusion_->completeSetup(Collective{}, materials_, initTime_);
  seeds_.clear();
}

void MPM::layOutGrid() {
  const int nodes = grid_.numNodes();
  fields_.assign(materials_.size(), {});
  for (GridFields& f : fields_) f.resize(nodes);
  weights_.resize(materials_.size());
  capacity_.resize(materials_.size());
  const size_t scatterQuads = static_cast<size_t>(nodes) * scatterQuadsPerNode(diffusion_.get());
  nodeQuads_.resize(std::max(scatterQuads, static_cast<size_t>(nodes) * kGatherQuads));
  threadScatter_.assign(std::max(omp_get_max_threads() - 1, 0),
                        std::vector<NodeQuad>(scatterQuads));
  if (diffusion_) diffusion_->layOutGrid(grid_, ghosts_.empty() ? nullptr : &ghosts_);
  active_ = {};
  previous_ = {};
}

template <class Concentration>
void MPM::scatterMaterial(size_t m, const Concentration& concentration, bool concentrationOnly) {
  // The mechanics' and the kernel's quads, or the kernel's alone (ParticleLoops.h).
  const int perNode = concentrationOnly ? kConcentrationScatterQuads
                                        : ScatterTerms<Concentration::scatterWeightQuads>::quads;
  const ParticleSet& p = materials_[m].particles;
  GridFields& g = fields_[m];
  const long n = static_cast<long>(p.count());
  // Each thread scatters a contiguous block of particles: the first into the step's node quads,
  // every other into its own, cleared on the active nodes its particles' range spans only (on a
  // small problem the active nodes are many times that). The threads' quads are then added in
  // thread order, so results do not depend on scheduling, and spread into the grid's fields.
  const int threads = static_cast<int>(threadScatter_.size()) + 1;
  std::vector<NodeRange> touched(threads);
  NodeQuad* const sums = nodeQuads_.data();
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    const long first = n * t / threads, last = n * (t + 1) / threads;
    forEachNodeOfThread(active_.rows, t, threads,
                        [&](long k) { clearQuads(sums + k * perNode, perNode); });
    NodeQuad* quads = sums;
    if (t > 0) {
      touched[t] = nodesTouched(weights_[m], first, last);
      quads = threadScatter_[t - 1].data();
      for (const NodeRange& r : active_.within(touched[t]))
        for (long k = r.begin; k < r.end; ++k) clearQuads(quads + k * perNode, perNode);
    }
#pragma omp barrier
    if (concentrationOnly)
      scatterConcentrationToNodes(weights_[m], first, last, quads, concentration);
    else
      scatterToNodes(p, weights_[m], first, last, quads, concentration);
#pragma omp barrier
    forEachNodeOfThread(active_.rows, t, threads, [&](long k) {
      NodeQuad* sum = sums + k * perNode;
      for (int u = 1; u < threads; ++u)
        if (touched[u].contains(k))
          addQuads(sum, threadScatter_[u - 1].data() + k * perNode, perNode);
      if (!concentrationOnly) {
        g.mass[k] = sum[0].value[ScatterLane::mass];
        g.momentum[k] = Vec3(sum[0].value + ScatterLane::momentum);
        g.internalForce[k] = Vec3(sum[perNode - 1].value + ScatterLane::internalForce);
      }
      concentration.spread(k, sum[perNode - 2], sum[perNode - 1]);
    });
  }
}

void MPM::interpolateParticlesToGrid(bool concentrationOnly) {
  {
    ScopedTimer s(timers_, particlesToGridTask_);
    scatterParticlesToGrid(concentrationOnly);
  }
  if (distributed_) {
    ScopedTimer s(timers_, communicationTask_);
    sumGhostNodes(concentrationOnly);
  }
}

void MPM::scatterParticlesToGrid(bool concentrationOnly) {
  const std::vector<NodeRange> cleared =
      ActiveNodes::of(grid_, hullOf(active_.box, previous_)).rows;
  for (size_t m = 0; m < materials_.size(); ++m) {
    if (!scatters(m, concentrationOnly)) continue;
    if (!concentrationOnly)
      forEachNodeRange(cleared, [&](long begin, long end) { fields_[m].clearAll(begin, end); });
    withScatterKernel(
        diffusion_.get(), m, materials_[m].particles, weights_[m], cleared,
        [&](const auto& concentration) { scatterMaterial(m, concentration, concentrationOnly); });
  }
}

void MPM::computeNodalVelocityAndConcentration() {
  for (size_t m = 0; m < materials_.size(); ++m) {
    GridFields& g = fields_[m];
    forEachNode(active_.rows, [&g](long k) {
      g.velocity[k] = g.mass[k] > 0 ? Vec3(g.momentum[k] / g.mass[k]) : Vec3::Zero();
    });
    applySymmetry(grid_, gridBCs_.symmetric, static_cast<int>(m), active_.box, g.velocity);
    applySymmetry(grid_, gridBCs_.symmetric, static_cast<int>(m), active_.box, g.internalForce);
  }
  if (diffusion_) computeNodalConcentration();
}

void MPM::computeNodalConcentration() {
  diffusion_->computeNodalConcentration(fields_, active_.rows);  // Eq. 5
}

void MPM::integrateConcentration(double dt) {
  diffusion_->integrateConcentration(fields_, dt, active_.rows);
}

void MPM::exchangeMomentumInterpolated() {
  if (contact_.exchangeInterpolated)
    contact_.exchange(fields_, &GridFields::velocity, active_.rows);
}

void MPM::integrateGridMomentum(double dt) {
  for (GridFields& g : fields_) {
    forEachNode(active_.rows, [&](long k) {
      // Below minimum_mass_for_acc only gravity accelerates a node, as in Uintah.
      Vec3 a = Vec3::Zero();
      if (g.mass[k] > flags_.minimumMassForAcc && g.mass[k] > 0)
        a = g.internalForce[k] / g.mass[k] + flags_.gravity -
            flags_.artificialDampingCoeff * g.velocity[k];
      else if (g.mass[k] > 0)
        a = flags_.gravity;
      g.velocityStar[k] = g.velocity[k] + a * dt;
    });
  }
}

void MPM::setGridBoundaryConditions(double dt) {
  contact_.exchange(fields_, &GridFields::velocityStar, active_.rows);
  for (size_t m = 0; m < fields_.size(); ++m) {
    GridFields& g = fields_[m];
    applyVelocityDirichlet(grid_, gridBCs_.velocity, static_cast<int>(m), g.velocityStar);
    applySymmetry(grid_, gridBCs_.symmetric, static_cast<int>(m), active_.box, g.velocityStar);
    forEachNode(active_.rows,
                [&g, dt](long k) { g.acceleration[k] = (g.velocityStar[k] - g.velocity[k]) / dt; });
  }
}

void MPM::interpolateToParticlesAndUpdate(double dt) {
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    const ConstitutiveModel& model = *mat.model;
    const ParticleUpdate update{nodeQuads_.data(),
                                weights_[m],
                                mat.density,
                                flags_.minimumSubcyclesForF,
                                diffusion_ && model.swells(),
                                dt};
    long firstInverted = 0;
    std::visit(
        [&](const auto* concrete) {
          withGatherKernel(diffusion_.get(), m, mat.particles, [&](const auto& concentration) {
            fillGatherQuads(fields_[m], concentration, active_.rows, nodeQuads_.data());
            firstInverted = updateParticles(mat.particles, update, *concrete, concentration);
          });
        },
        model.concrete().model);
    if (firstInverted < static_cast<long>(mat.particles.count())) {
      std::ostringstream s;
      s << describeParticle(mat, m, firstInverted)
        << " has det F = " << mat.particles.F[firstInverted].determinant()
        << " (inverted or degenerate deformation)";
      throw SimulationError(s.str());
    }
  }
}

void MPM::interpolateConcentrationChange(size_t m, double dt, std::vector<double>& dc) {
  ParticleSet& p = materials_[m].particles;
  withGatherKernel(diffusion_.get(), m, p, [&](const auto& kernel) {
    fillGatherQuads(fields_[m], kernel, active_.rows, nodeQuads_.data());
    updateConcentrationOnly(p, weights_[m], nodeQuads_.data(), kernel, dt, dc);
  });
}

void MPM::interpolateConcentrationGradient(size_t m) {
  gatherConcentrationGradient(materials_[m].particles, weights_[m],
                              diffusion_->gridFields()[m].concentration);
}

void MPM::splitParticles() {
  // The weights of the next step are laid out for the new particle count.
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    if (!p.has(Physics::Splitting)) continue;
    Reordering& r = reordering_[m];
    r.beforeSplitting = p.count();
    if (!distributed_) {
      r.split = splitStretchedParticles(p, grid_, flags_.stretchRatio, nextParticleId_);
      if (diffusion_) diffusion_->shareFluxFaces(p, r.split);
      continue;
    }
    // New IDs in the order of the parents' IDs over all ranks, as one rank would give them
    // (its particles stay in ID order), whatever rank holds a parent.
    // The IDs are gathered only in a step that splits some particle (a sum first).
    std::vector<int64_t> parents;
    const std::vector<int64_t> mine = stretchedParticleIds(p, grid_, flags_.stretchRatio);
    if (collective::sum(static_cast<int64_t>(mine.size())) == 0) {
      r.split.clear();
      continue;
    }
    for (const std::string& ids : collective::allGather(std::string(
             reinterpret_cast<const char*>(mine.data()), mine.size() * sizeof(int64_t)))) {
      const size_t at = parents.size();
      parents.resize(at + ids.size() / sizeof(int64_t));
      if (!ids.empty()) std::memcpy(parents.data() + at, ids.data(), ids.size());
    }
    std::sort(parents.begin(), parents.end());
    const int64_t first = nextParticleId_;
    r.split = splitStretchedParticles(p, grid_, flags_.stretchRatio, [&](int64_t parent) {
      const auto at = std::lower_bound(parents.begin(), parents.end(), parent) - parents.begin();
      return first + 3 * static_cast<int64_t>(at);
    });
    if (diffusion_) diffusion_->shareFluxFaces(p, r.split);
    nextParticleId_ += 3 * static_cast<int64_t>(parents.size());
  }
}

size_t MPM::numParticles() const {
  size_t n = 0;
  for (const auto& m : materials_) n += m.particles.count();
  return n;
}

StableTimestep MPM::computeStableTimestep(Collective) const {
  StableTimestep limits;
  double& dt = limits.bound[StableTimestep::Mechanics];
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
  if (diffusion_) diffusion_->boundTimestep(Collective{}, grid_, materials_, limits);
  collective::minimum(limits.bound.data(), 2);  // Eqs. 43 and 44 over ranks
  return limits;
}

void MPM::interpolateToGridForOutput(Collective) {
  computeWeightsAndActiveNodes();
  scatterParticlesToGrid();
  if (distributed_) sumGhostNodes();
  computeNodalVelocityAndConcentration();
}

void MPM::releaseInterpolationWeights() {
  for (InterpolationWeights& w : weights_) w = InterpolationWeights();
}

StepSummary MPM::summarize(Collective) const {
  StepSummary s;
  s.minJ = std::numeric_limits<double>::infinity();
  s.maxJ = -std::numeric_limits<double>::infinity();
  s.minConcentration = std::numeric_limits<double>::infinity();
  s.maxConcentration = -std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const double K = mat.model->bulkModulus(), G = mat.model->shearModulus();
    for (size_t i = 0; i < p.count(); ++i) {
      s.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
      s.elasticEnergy += p.volume[i] * ConstitutiveModel::elasticEnergyDensity(p.stress[i], K, G);
      const double J = p.volume[i] * mat.density / p.mass[i];
      s.minJ = std::min(s.minJ, J);
      s.maxJ = std::max(s.maxJ, J);
    }
    s.particles += p.count();
  }
  if (diffusion_) diffusion_->summarize(materials_, s);
  if (distributed_) {
    // One reduction of each kind: the totals, then each material's own.
    std::vector<double> sums = {
        s.kineticEnergy,     s.totalLithium,    static_cast<double>(s.particles),
        s.chargeableLithium, s.lithiumCapacity, s.elasticEnergy};
    std::vector<double> lows = {s.minJ, s.minConcentration}, highs = {s.maxJ, s.maxConcentration};
    for (const StepSummary::MaterialLithium& m : s.perMaterial) {
      sums.push_back(m.lithium);
      lows.push_back(m.minConcentration);
      highs.push_back(m.maxConcentration);
    }
    collective::sum(sums.data(), static_cast<int>(sums.size()));
    collective::minimum(lows.data(), static_cast<int>(lows.size()));
    collective::maximum(highs.data(), static_cast<int>(highs.size()));
    s.kineticEnergy = sums[0], s.totalLithium = sums[1], s.particles = static_cast<size_t>(sums[2]);
    s.chargeableLithium = sums[3], s.lithiumCapacity = sums[4], s.elasticEnergy = sums[5];
    s.minJ = lows[0], s.minConcentration = lows[1], s.maxJ = highs[0],
    s.maxConcentration = highs[1];
    for (size_t k = 0; k < s.perMaterial.size(); ++k)
      s.perMaterial[k] = {sums[6 + k], lows[2 + k], highs[2 + k]};
  }
  return s;
}

}  // namespace anode
