#include "Components/MPM/MPM.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <type_traits>

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
  problem_.flags = MPMFlags::fromInput(root);
  initTime_ = initTime;
  const PSNode gridNode = root.requireChild("Grid");
  layout_.setProblemGrid(Grid::fromInput(gridNode), problem_.flags.interpolator);
  if (problem_.flags.interpolator != InterpolatorKind::Linear && (grid().extra.array() < 1).any())
    gridNode.requireChild("Level").requireChild("Box").fail(
        "interpolator \"" + interpolatorName(problem_.flags.interpolator) +
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
        MPMMaterial::fromInput(materialNodes[m], grid(), problem_.flags, pieces, seeds_[m]));
  // Each geom_object's particles are numbered on from the objects' before it, in input order.
  for (MaterialSeeds& s : seeds_)
    for (MaterialSeeds::Object& object : s.objects) {
      object.firstId = nextParticleId_;
      nextParticleId_ += object.total;
    }
  if (problem_.flags.refineMaterial >= static_cast<int>(materials_.size()))
    root.requireChild("AMR").fail("the stretchRatio names material " +
                                  std::to_string(problem_.flags.refineMaterial) +
                                  ", but there are " + std::to_string(materials_.size()));
  problem_.contact = Contact::fromInput(mpmMats, static_cast<int>(materials_.size()));
  const PhysicalBCs physical = readPhysicalBCs(root);
  std::vector<BCType> concentrationBCs;  // SD-Type, for the diffusion subcomponent
  problem_.gridBCs =
      readGridBoundaryConditions(gridNode, static_cast<int>(materials_.size()),
                                 [&](const BCType& bc) { concentrationBCs.push_back(bc); });
  diffusion_ = ReactiveFlow::fromInput(root, problem_.flags, materials_, maxTime, physical,
                                       concentrationBCs);
  if (diffusion_)
    for (size_t m = 0; m < materials_.size(); ++m)
      materials_[m].model->setMaxConcentration(diffusion_->model(m).maxConcentration);
  // A stress-driven flux's steps keep c's change to the range its linearized local response holds
  // (ReactiveFlow::stressDrivenConcentrationChange), or <max_concentration_change> where tighter.
  if (diffusion_ && problem_.flags.implicit) {
    double& cap = problem_.flags.implicit->maxConcentrationChange;
    const double bound = diffusion_->stressDrivenConcentrationChange();
    if (bound < (cap > 0 ? cap : std::numeric_limits<double>::infinity())) cap = bound;
  }
  for (size_t m = 0; m < materials_.size(); ++m)
    seeds_[m].checkPiecesInsideGrid(grid(), problem_.gridBCs.symmetryPlanes(static_cast<int>(m)));
  problem_.swellingNotes =
      swellingRoomNotes(grid(), problem_.gridBCs, materials_, seeds_, diffusion_.get());
  warnOfOverlaps(grid(), materials_, seeds_);
  if (problemRead) problemRead();

  // This rank's particles: those of its box (the whole grid on one rank) and, while the flux
  // particles are flagged, those setup needs around it.
  const CellBox box = withParticles ? layout_.drawSetupBoxes(seedCounts()) : CellBox{};
  const CellBox region =
      diffusion_ ? diffusion_->setupRegion(box, layout_.problemGrid(), seeds_) : box;
  checkParticlesOfRank(region);
  for (size_t m = 0; m < materials_.size(); ++m) {
    materials_[m].placeParticles(seeds_[m], grid(), region);
    // A smooth piece's layout of every particle is no longer needed once they are placed (a
    // count for describeDecomposition keeps it).
    if (withParticles)
      for (MaterialSeeds::Object& object : seeds_[m].objects) object.smoothLayout = {};
    if (problem_.flags.refineParticles &&
        (problem_.flags.refineMaterial < 0 || problem_.flags.refineMaterial == static_cast<int>(m)))
      materials_[m].particles.enable(Physics::Splitting);
    if (problem_.flags.implicit && problem_.flags.implicit->dynamic)
      materials_[m].particles.enable(Physics::Inertia);
    if (problem_.flags.implicit && problem_.flags.implicit->hourglassStabilization > 0)
      materials_[m].particles.enable(Physics::Hourglass);
    if (diffusion_ && problem_.flags.implicit && problem_.flags.implicit->errorTolerance > 0)
      materials_[m].particles.enable(Physics::CouplingHistory);
    if (diffusion_ && problem_.flags.implicit &&
        problem_.flags.implicit->swellingStrain == ImplicitOptions::SwellingStrain::CellMean)
      materials_[m].particles.enable(Physics::CellSwelling);
  }
  checkProblemSize(gridNode, grid(), problem_.flags, materials_.size(), countParticles(materials_),
                   omp_get_max_threads());
  if (diffusion_) diffusion_->initialize(root, grid(), materials_, seeds_, box, region, initTime);
  if (region.lower != box.lower || region.upper != box.upper) keepParticlesOfBox(box);
  reordering_.resize(materials_.size());
  particlesToGridTask_ = timers_.task("interpolateParticlesToGrid");
  communicationTask_ = layout_.distributed() ? timers_.task("communication") : -1;
}

void MPM::distributeOverRanks(Collective every, bool concentrationOfEveryMaterial) {
  layout_.completeSetup(every);
  if (diffusion_)
    problem_.diffusionNotes =
        diffusion_->completeSetup(every, materials_, initTime_, concentrationOfEveryMaterial);
  seeds_.clear();
}

void MPM::layOutGrid() {
  const int nodes = grid().numNodes();
  step_.fields.assign(materials_.size(), {});
  for (GridFields& f : step_.fields) f.resize(nodes);
  step_.weights.resize(materials_.size());
  capacity_.resize(materials_.size());
  const size_t scatterQuads = static_cast<size_t>(nodes) * scatterQuadsPerNode(diffusion_.get());
  nodeQuads_.resize(std::max(scatterQuads, static_cast<size_t>(nodes) * kGatherQuads));
  threadScatter_.assign(std::max(omp_get_max_threads() - 1, 0),
                        std::vector<NodeQuad>(scatterQuads));
  GhostNodes* ghosts = layout_.ghosts();
  step_.concentration =
      diffusion_ ? &diffusion_->layOutGrid(grid(), ghosts && !ghosts->empty() ? ghosts : nullptr)
                 : nullptr;
  step_.active = {};
  previous_ = {};
}

template <class Concentration>
void MPM::scatterMaterial(size_t m, const Concentration& concentration, bool concentrationOnly) {
  // The mechanics' and the kernel's quads, or the kernel's alone (ParticleLoops.h).
  const int perNode = concentrationOnly ? kConcentrationScatterQuads
                                        : ScatterTerms<Concentration::scatterWeightQuads>::quads;
  const ParticleSet& p = materials_[m].particles;
  GridFields& g = step_.fields[m];
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
    forEachNodeOfThread(step_.active.rows, t, threads,
                        [&](long k) { clearQuads(sums + k * perNode, perNode); });
    NodeQuad* quads = sums;
    if (t > 0) {
      touched[t] = nodesTouched(step_.weights[m], first, last);
      quads = threadScatter_[t - 1].data();
      for (const NodeRange& r : step_.active.within(touched[t]))
        for (long k = r.begin; k < r.end; ++k) clearQuads(quads + k * perNode, perNode);
    }
#pragma omp barrier
    if (concentrationOnly)
      scatterConcentrationToNodes(step_.weights[m], first, last, quads, concentration);
    else
      scatterToNodes(p, step_.weights[m], first, last, quads, concentration);
#pragma omp barrier
    forEachNodeOfThread(step_.active.rows, t, threads, [&](long k) {
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

void MPM::interpolateParticlesToGrid(Collective every, bool concentrationOnly) {
  {
    ScopedTimer s(timers_, particlesToGridTask_);
    scatterParticlesToGrid(every, concentrationOnly);
  }
  if (layout_.distributed()) {
    ScopedTimer s(timers_, communicationTask_);
    sumGhostNodes(every, concentrationOnly);
  }
}

void MPM::scatterParticlesToGrid(Collective every, bool concentrationOnly) {
  const std::vector<NodeRange> cleared =
      ActiveNodes::of(grid(), hullOf(step_.active.box, previous_)).rows;
  for (size_t m = 0; m < materials_.size(); ++m) {
    if (!concentrationOnly)
      forEachNodeRange(cleared,
                       [&](long begin, long end) { step_.fields[m].clearAll(begin, end); });
    const auto scatter = [&](const auto& concentration) {
      // A material whose concentration is not computed (NoConcentration) has no sums in a P2G of
      // the concentration alone.
      using Kernel = std::decay_t<decltype(concentration)>;
      if (concentrationOnly && std::is_same_v<Kernel, NoConcentration>) return;
      scatterMaterial(m, concentration, concentrationOnly);
    };
    withScatterKernel(every, diffusion_.get(), m, materials_[m].particles, step_.weights[m],
                      cleared, scatter);
  }
}

void MPM::computeNodalVelocityAndConcentration() {
  for (size_t m = 0; m < materials_.size(); ++m) {
    GridFields& g = step_.fields[m];
    forEachNode(step_.active.rows, [&g](long k) {
      g.velocity[k] = g.mass[k] > 0 ? Vec3(g.momentum[k] / g.mass[k]) : Vec3::Zero();
    });
    applySymmetry(grid(), problem_.gridBCs.symmetric, static_cast<int>(m), step_.active.box,
                  g.velocity);
    applySymmetry(grid(), problem_.gridBCs.symmetric, static_cast<int>(m), step_.active.box,
                  g.internalForce);
  }
  if (diffusion_) computeNodalConcentration();
}

void MPM::computeNodalConcentration() {
  diffusion_->computeNodalConcentration(step_.fields, step_.active.rows);  // Eq. 5
}

void MPM::integrateConcentration(double dt) {
  diffusion_->integrateConcentration(step_.fields, dt, step_.active.rows);
}

void MPM::exchangeMomentumInterpolated() {
  if (problem_.contact.exchangeInterpolated)
    problem_.contact.exchange(step_.fields, &GridFields::velocity, step_.active.rows);
}

void MPM::integrateGridMomentum(double dt) {
  for (GridFields& g : step_.fields) {
    forEachNode(step_.active.rows, [&](long k) {
      // Below minimum_mass_for_acc only gravity accelerates a node, as in Uintah.
      Vec3 a = Vec3::Zero();
      if (g.mass[k] > problem_.flags.minimumMassForAcc && g.mass[k] > 0)
        a = g.internalForce[k] / g.mass[k] + problem_.flags.gravity -
            problem_.flags.artificialDampingCoeff * g.velocity[k];
      else if (g.mass[k] > 0)
        a = problem_.flags.gravity;
      g.velocityStar[k] = g.velocity[k] + a * dt;
    });
  }
}

void MPM::setGridBoundaryConditions(double dt) {
  problem_.contact.exchange(step_.fields, &GridFields::velocityStar, step_.active.rows);
  for (size_t m = 0; m < step_.fields.size(); ++m) {
    GridFields& g = step_.fields[m];
    applyVelocityDirichlet(grid(), problem_.gridBCs.velocity, static_cast<int>(m), g.velocityStar);
    applySymmetry(grid(), problem_.gridBCs.symmetric, static_cast<int>(m), step_.active.box,
                  g.velocityStar);
    forEachNode(step_.active.rows,
                [&g, dt](long k) { g.acceleration[k] = (g.velocityStar[k] - g.velocity[k]) / dt; });
  }
}

void MPM::interpolateToParticlesAndUpdate(double dt) {
  for (size_t m = 0; m < materials_.size(); ++m) {
    MPMMaterial& mat = materials_[m];
    const ConstitutiveModel& model = *mat.model;
    const ParticleUpdate update{nodeQuads_.data(),
                                step_.weights[m],
                                mat.density,
                                problem_.flags.minimumSubcyclesForF,
                                diffusion_ && model.swells(),
                                dt};
    long firstInverted = 0;
    std::visit(
        [&](const auto* concrete) {
          withGatherKernel(diffusion_.get(), m, mat.particles, [&](const auto& concentration) {
            fillGatherQuads(step_.fields[m], concentration, step_.active.rows, nodeQuads_.data());
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
    fillGatherQuads(step_.fields[m], kernel, step_.active.rows, nodeQuads_.data());
    updateConcentrationOnly(p, step_.weights[m], nodeQuads_.data(), kernel, dt, dc);
  });
}

void MPM::interpolateConcentrationGradient(size_t m) {
  gatherConcentrationGradient(materials_[m].particles, step_.weights[m],
                              (*step_.concentration)[m].concentration);
}

void MPM::splitParticles(Collective every) {
  // The weights of the next step are laid out for the new particle count.
  for (size_t m = 0; m < materials_.size(); ++m) {
    ParticleSet& p = materials_[m].particles;
    if (!p.has(Physics::Splitting)) continue;
    ParticleReordering& r = reordering_[m];
    r.beforeSplitting = p.count();
    if (!layout_.distributed()) {
      r.split = splitStretchedParticles(p, grid(), problem_.flags.stretchRatio, nextParticleId_);
      if (diffusion_) diffusion_->shareFluxFaces(p, r.split);
      continue;
    }
    // New IDs in the order of the parents' IDs over all ranks, as one rank would give them
    // (its particles stay in ID order), whatever rank holds a parent.
    // The IDs are gathered only in a step that splits some particle (a sum first).
    std::vector<int64_t> parents;
    const std::vector<int64_t> mine = stretchedParticleIds(p, grid(), problem_.flags.stretchRatio);
    if (collective::sum(every, static_cast<int64_t>(mine.size())) == 0) {
      r.split.clear();
      continue;
    }
    for (const std::string& ids :
         collective::allGather(every, std::string(reinterpret_cast<const char*>(mine.data()),
                                                  mine.size() * sizeof(int64_t)))) {
      const size_t at = parents.size();
      parents.resize(at + ids.size() / sizeof(int64_t));
      if (!ids.empty()) std::memcpy(parents.data() + at, ids.data(), ids.size());
    }
    std::sort(parents.begin(), parents.end());
    const int64_t first = nextParticleId_;
    r.split = splitStretchedParticles(p, grid(), problem_.flags.stretchRatio, [&](int64_t parent) {
      const auto at = std::lower_bound(parents.begin(), parents.end(), parent) - parents.begin();
      return first + 3 * static_cast<int64_t>(at);
    });
    if (diffusion_) diffusion_->shareFluxFaces(p, r.split);
    nextParticleId_ += 3 * static_cast<int64_t>(parents.size());
  }
}

void MPM::migrateParticles(Collective every) {
  layout_.migrateParticles(every, reordering_);
}

void MPM::interpolateToGridForOutput(Collective every) {
  computeWeightsAndActiveNodes(every);
  scatterParticlesToGrid(every);
  if (layout_.distributed()) sumGhostNodes(every);
  computeNodalVelocityAndConcentration();
}

void MPM::releaseInterpolationWeights() {
  for (InterpolationWeights& w : step_.weights) w = InterpolationWeights();
}

StepSummary MPM::summarize(Collective every) const {
  StepSummary s;
  s.minJ = std::numeric_limits<double>::infinity();
  s.maxJ = -std::numeric_limits<double>::infinity();
  s.minConcentration = std::numeric_limits<double>::infinity();
  s.maxConcentration = -std::numeric_limits<double>::infinity();
  for (const MPMMaterial& mat : materials_) {
    const ParticleSet& p = mat.particles;
    const double K = mat.model->bulkModulus(), G = mat.model->shearModulus();
    // The moduli at each particle's c where the laws depend on lithium.
    const std::vector<double>* c = concentrationOf(p);
    const bool lithiumDependent = c && mat.model->lithiumDependent();
    StepSummary::MaterialStress& stress = s.stress.emplace_back();
    const std::vector<double>* plasticRate = mat.model->plasticStrainRate(p);
    stress.yields = plasticRate != nullptr;
    for (size_t i = 0; i < p.count(); ++i) {
      s.kineticEnergy += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
      const double Ki = lithiumDependent ? mat.model->bulkModulusAt((*c)[i]) : K;
      const double Gi = lithiumDependent ? mat.model->shearModulusAt((*c)[i]) : G;
      s.elasticEnergy += p.volume[i] * ConstitutiveModel::elasticEnergyDensity(p.stress[i], Ki, Gi);
      const double J = p.volume[i] * mat.density / p.mass[i];
      s.minJ = std::min(s.minJ, J);
      s.maxJ = std::max(s.maxJ, J);
      const Mat3& sigma = p.stress[i];
      const double V = p.volume[i], vonMises = ConstitutiveModel::vonMises(sigma);
      stress.volume += V;
      const double components[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2),
                                    sigma(1, 2), sigma(0, 2), sigma(0, 1)};
      for (int k = 0; k < 6; ++k) stress.stressIntegral[k] += V * components[k];
      stress.vonMisesIntegral += V * vonMises;
      if (plasticRate) stress.plasticWorkRate += V * vonMises * (*plasticRate)[i];
    }
    s.particles += p.count();
  }
  if (diffusion_) diffusion_->summarize(materials_, s);
  if (layout_.distributed()) {
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
    const size_t stressSums = sums.size();
    for (const StepSummary::MaterialStress& m : s.stress) {
      sums.push_back(m.volume);
      sums.insert(sums.end(), m.stressIntegral, m.stressIntegral + 6);
      sums.push_back(m.vonMisesIntegral);
      sums.push_back(m.plasticWorkRate);
    }
    collective::sum(every, sums.data(), static_cast<int>(sums.size()));
    collective::minimum(every, lows.data(), static_cast<int>(lows.size()));
    collective::maximum(every, highs.data(), static_cast<int>(highs.size()));
    s.kineticEnergy = sums[0], s.totalLithium = sums[1], s.particles = static_cast<size_t>(sums[2]);
    s.chargeableLithium = sums[3], s.lithiumCapacity = sums[4], s.elasticEnergy = sums[5];
    s.minJ = lows[0], s.minConcentration = lows[1], s.maxJ = highs[0],
    s.maxConcentration = highs[1];
    for (size_t k = 0; k < s.perMaterial.size(); ++k) {
      StepSummary::MaterialLithium& m = s.perMaterial[k];
      m.lithium = sums[6 + k], m.minConcentration = lows[2 + k], m.maxConcentration = highs[2 + k];
    }
    for (size_t k = 0; k < s.stress.size(); ++k) {
      StepSummary::MaterialStress& m = s.stress[k];
      const double* sum = &sums[stressSums + 9 * k];
      m.volume = sum[0];
      std::copy(sum + 1, sum + 7, m.stressIntegral);
      m.vonMisesIntegral = sum[7];
      m.plasticWorkRate = sum[8];
    }
  }
  return s;
}

}  // namespace anode
