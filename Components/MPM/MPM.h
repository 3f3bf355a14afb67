// The MPM component: owns the materials' particles and the grid fields, and the tasks a step is
// made of (interpolation weights, P2G, the grid's equations, G2P); an integrator (Integrator.h:
// ExplicitStep.h, Implicit/ImplicitStep.h) takes them in its order. Its diffusion subcomponent,
// ReactiveFlow, exists only with <do_scalar_diffusion>true.
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/Contact/Contact.h"
#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/GridBoundaryConditions.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/NodeQuads.h"
#include "Components/MPM/RankLayout.h"
#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"
#include "Components/MPM/SplitParticle.h"
#include "Components/MPM/StableTimestep.h"
#include "Components/MPM/StepSummary.h"
#include "Core/Grid/Grid.h"
#include "Core/Parallel/Decomposition.h"
#include "Core/Util/BinaryStream.h"
#include "Core/Util/Timers.h"

namespace anode {

// The problem as setup read it, fixed for the run.
struct MPMProblem {
  MPMFlags flags;
  GridBoundaryConditions gridBCs;
  Contact contact;
  // Setup's notes on bodies that would swell into a Symmetric face (SwellingRoom.h).
  std::vector<std::string> swellingNotes;
  // Setup's lines on diffusion: per flux BC and material, the particles flagged and their area,
  // and the materials that take up no lithium (ReactiveFlow::completeSetup).
  std::vector<std::string> diffusionNotes;
};

// The grid's part of a step: per material the nodal fields and the particles' interpolation
// weights, and the nodes the particles touch. Grid loops run over those nodes only; outside,
// nodal fields are zero (the previous step's box is cleared too) except the values face boundary
// conditions set.
struct StepGrid {
  std::vector<GridFields> fields;
  std::vector<InterpolationWeights> weights;
  ActiveNodes active;
  // With diffusion, its nodal fields per material (ReactiveFlow's, laid out with the others:
  // ReactiveFlow::layOutGrid); null without.
  std::vector<ConcentrationGridFields>* concentration = nullptr;
};

class MPM {
 public:
  MPM() = default;
  MPM(const MPM&) = delete;  // its RankLayout holds its particles
  MPM& operator=(const MPM&) = delete;

  // Reads <MPM>, <PhysicalConstants>, <Grid>, <MaterialProperties> and <PhysicalBC>; the
  // simulation starts at initTime and ends at maxTime. In a distributed run each rank counts the
  // particles the geom_objects lay out per cell, draws the boxes from the counts and creates
  // only the particles of its own box (docs/parallel.md, "Setup per box"). Calls no collective:
  // the ranks agree on its errors after it.
  // Without `withParticles`, the particles are counted, not created (describeDecomposition).
  // `problemRead` is called once the problem is read (flags, grid, materials, contact, diffusion,
  // boundary conditions), before any particle is created: where the driver chooses the
  // integrator, which checks what it does not support of the input (IntegratorFactory.h).
  void problemSetup(const PSNode& root, double initTime, double maxTime, bool withParticles = true,
                    const std::function<void()>& problemRead = {});
  // After problemSetup: lays out this rank's grid and completes the setup over the ranks (the
  // flux BCs' areas and capacities, their notes). `concentrationOfEveryMaterial`: the output
  // saves the nodal concentration or p.concentrationGradient, which diffusion then computes for
  // every material (ReactiveFlow::completeSetup).
  void distributeOverRanks(Collective, bool concentrationOfEveryMaterial);

  // --- the tasks a step is made of (DESIGN.md §4), in the explicit step's order ---

  // 1: S_ip and grad S_ip of every particle on every rank (a problem on one stops them all),
  // then the step's active nodes.
  void computeWeightsAndActiveNodes(Collective);
  // 2: P2G (Eqs. 4-5, 7, 18) and, distributed, its sums completed on the shared nodes (timed);
  // `concentrationOnly`: the concentration's sums alone, of the materials whose concentration
  // changes, after a full P2G of the same particles that changed nothing but their
  // concentration since (the diffusion of an implicit step).
  void interpolateParticlesToGrid(Collective, bool concentrationOnly = false);
  // 2: the nodal velocity and, with diffusion, computeNodalConcentration.
  void computeNodalVelocityAndConcentration();
  // Eq. 5 and the diffusion interface (diffusion on).
  void computeNodalConcentration();
  // 3: contact on the interpolated velocity.
  void exchangeMomentumInterpolated();
  // 4: a = f/m + g, v* = v + a dt.
  void integrateGridMomentum(double dt);
  // 5: c* and the nodal rate of c over dt (Eq. 18; diffusion on).
  void integrateConcentration(double dt);
  // 6: contact, velocity BCs, the nodal acceleration.
  void setGridBoundaryConditions(double dt);
  // 7-8: G2P (Eq. 8), F, stress. Throws SimulationError (this rank's) when J <= 0.
  void interpolateToParticlesAndUpdate(double dt);
  // G2P of c alone over dt (diffusion on, after integrateConcentration): the change of material
  // m's particles' c added to dc, their position, F and stress as they are.
  void interpolateConcentrationChange(size_t m, double dt, std::vector<double>& dc);
  // grad c of material m's particles from the nodal c (diffusion on).
  void interpolateConcentrationGradient(size_t m);
  // 9: particles stretched beyond <stretchRatio> split in four (<refineParticles>).
  void splitParticles(Collective);
  // 11 (distributed): particles that left the rank's box go to its owner.
  void migrateParticles(Collective);

  // Interpolation weights and the grid fields of the current state (for output of g.* labels).
  void interpolateToGridForOutput(Collective);
  // Frees the interpolation weights between steps so output can use the memory; the next step
  // lays them out again.
  void releaseInterpolationWeights();
  // Totals over every rank's particles.
  StepSummary summarize(Collective) const;

  // The state a step starts from (every particle array and the scalars carried between steps),
  // for checkpoints (MPMState.cc). loadState expects the materials of the same input and throws
  // std::runtime_error when the saved state does not fit them; it puts the particles it reads in
  // place of this rank's, after them (a distributed checkpoint read part by part), or drops them
  // (a part read only for the state every part holds).
  enum class ReadParticles { Replace, Append, Drop };
  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in, ReadParticles particles = ReadParticles::Replace);
  // After problemSetup without particles: the boxes `ranks` ranks would draw for the problem,
  // their particle counts and imbalance, and the ghost nodes and bytes of the ghost sums, beside
  // those of tensor-product cuts (sus --decompose N).
  std::string describeDecomposition(int ranks);

  // The nodes this rank stores (the whole grid on one rank; its window in a distributed run).
  const Grid& grid() const { return layout_.window(); }
  // How the grid and the particles are shared among the ranks.
  RankLayout& layout() { return layout_; }
  const RankLayout& layout() const { return layout_; }
  // How the last step changed each material's particles on this rank (splitting, migration).
  const std::vector<ParticleReordering>& lastReordering() const { return reordering_; }
  const MPMProblem& problem() const { return problem_; }
  const std::vector<MPMMaterial>& materials() const { return materials_; }
  std::vector<MPMMaterial>& materials() { return materials_; }
  const StepGrid& stepGrid() const { return step_; }
  // The diffusion subcomponent; null without <do_scalar_diffusion>true.
  const ReactiveFlow* diffusion() const { return diffusion_.get(); }
  ReactiveFlow* diffusion() { return diffusion_.get(); }
  TaskTimers& timers() { return timers_; }
  const TaskTimers& timers() const { return timers_; }

 private:
  // This rank's weights; returns the box of nodes they touch.
  NodeBox computeInterpolationWeights();
  // Particle i's weights on grid g (the count, or -1 beyond its stored nodes).
  int computeWeights(const Grid& g, const ParticleSet& p, long i, int32_t* node, double* w,
                     Vec3* grad) const;
  // Material m's particle i reaches beyond the stored nodes: off the grid, or (distributed)
  // beyond the ghost layer.
  [[noreturn]] void throwOutsideWindow(size_t m, long i) const;
  // P2G on this rank (`concentrationOnly`: as interpolateParticlesToGrid's).
  void scatterParticlesToGrid(Collective, bool concentrationOnly = false);
  // Completes the nodal sums of P2G on the nodes shared with other ranks (`concentrationOnly`:
  // as interpolateParticlesToGrid's).
  void sumGhostNodes(Collective, bool concentrationOnly = false);
  // Sizes the grid fields to this rank's window (RankLayout calls it when it lays one out).
  void layOutGrid();
  // Setup per box (MPMRanks.cc): the particles per cell seeds_ lay out (RankLayout draws the
  // setup's boxes from them); the particle count of a region against the memory budget; dropping
  // the particles beyond the box once the flux particles are flagged (ReactiveFlow::setupRegion).
  Decomposition::ParticleCounts seedCounts() const;
  void checkParticlesOfRank(const CellBox& region) const;
  void keepParticlesOfBox(const CellBox& box);
  // The grid arrays the ghost sums after P2G complete (`concentrationOnly`: the concentration's).
  std::vector<NodeArray> ghostSumArrays(bool concentrationOnly = false);
  template <class Concentration>
  void scatterMaterial(size_t m, const Concentration& concentration, bool concentrationOnly);

  MPMProblem problem_;
  std::vector<ParticleReordering> reordering_;
  std::vector<MPMMaterial> materials_;
  RankLayout layout_{materials_, [this] { layOutGrid(); }};
  std::unique_ptr<ReactiveFlow> diffusion_;  // only with <do_scalar_diffusion>true
  int64_t nextParticleId_ = 0;
  std::vector<MaterialSeeds> seeds_;  // setup only: what the geom_objects lay out
  double initTime_ = 0;
  StepGrid step_;
  NodeBox previous_;  // the nodes the particles touched in the step before
  std::vector<std::vector<uint8_t>> capacity_;  // per material: weight entries per particle
  // Node quads (NodeQuads.h): what P2G sums per node, then what G2P reads per node; and P2G's
  // sums per thread after the first (P2G without locks).
  std::vector<NodeQuad> nodeQuads_;
  std::vector<std::vector<NodeQuad>> threadScatter_;
  TaskTimers timers_;
  int particlesToGridTask_ = -1, communicationTask_ = -1;
};

}  // namespace anode
