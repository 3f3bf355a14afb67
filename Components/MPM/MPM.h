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
#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"
#include "Components/MPM/SplitParticle.h"
#include "Components/MPM/StableTimestep.h"
#include "Components/MPM/StepSummary.h"
#include "Core/Grid/Grid.h"
#include "Core/Parallel/Decomposition.h"
#include "Core/Util/BinaryStream.h"
#include "Core/Util/Timers.h"

namespace anode {

class MPM {
 public:
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
  // flux BCs' areas and capacities, their report).
  void distributeOverRanks(Collective);

  // --- the tasks a step is made of (DESIGN.md §4), in the explicit step's order ---

  // 1: S_ip and grad S_ip of every particle on every rank (a problem on one stops them all),
  // then the step's active nodes.
  void computeWeightsAndActiveNodes();
  // 2: P2G (Eqs. 4-5, 7, 18) and, distributed, its sums completed on the shared nodes (timed);
  // `concentrationOnly`: the concentration's sums alone, of the materials whose concentration
  // changes, after a full P2G of the same particles that changed nothing but their
  // concentration since (the diffusion of an implicit step).
  void interpolateParticlesToGrid(bool concentrationOnly = false);
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
  void splitParticles();
  // 11 (distributed): particles that left the rank's box go to its owner.
  void migrateParticles();

  // The explicit step's largest stable dt of the current state before the multiplier: paper Eq.
  // 45, the smallest of the mechanical Eq. 43 and the diffusion limits (Eq. 44 and the flux
  // limit).
  StableTimestep computeStableTimestep(Collective) const;
  // Shares the particles out anew among the ranks from their counts per cell plane (after a
  // restart, or when the particles per rank have drifted apart).
  void redistributeParticles(Collective);
  // Largest over mean particles per rank.
  double imbalance(Collective) const;
  // Interpolation weights and the grid fields of the current state (for output of g.* labels).
  void interpolateToGridForOutput(Collective);
  // Frees the interpolation weights between steps so output can use the memory; the next step
  // lays them out again.
  void releaseInterpolationWeights();
  // Totals over every rank's particles.
  StepSummary summarize(Collective) const;

  // The state a step starts from (every particle array and the scalars carried between steps),
  // for checkpoints (MPMState.cc). loadState expects the materials of the same input and throws
  // std::runtime_error when the saved state does not fit them.
  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in);
  // The same particles appended to this rank's (a distributed checkpoint read part by part).
  void appendState(BinaryReader& in);
  // The boxes of a distributed run, for its checkpoint; adoptLayout takes them back after each
  // rank loaded its own part.
  struct Layout {
    Decomposition boxes;
    int ghostWidth = 0;
  };
  void saveLayout(BinaryWriter& out) const;
  static Layout readLayout(BinaryReader& in);
  void adoptLayout(Collective, const Layout& layout);
  // After every rank loaded all particles (a one-rank checkpoint on several ranks): puts them in
  // ID order and keeps this rank's share under a decomposition drawn anew.
  void keepOwnShare(Collective);
  // After problemSetup without particles: the boxes `ranks` ranks would draw for the problem,
  // their particle counts and imbalance, and the ghost nodes and bytes of the ghost sums, beside
  // those of tensor-product cuts (sus --decompose N).
  std::string describeDecomposition(int ranks);
  // After each rank loaded some parts of a distributed checkpoint of another rank count: shares
  // the particles out under a decomposition drawn anew, each rank's in ID order.
  void shareOutAnew(Collective);
  // Drops this rank's particles (a part read only for the state every part holds).
  void dropParticles();

  // The nodes this rank stores (the whole grid on one rank; its window in a distributed run).
  const Grid& grid() const { return grid_; }
  const Decomposition& decomposition() const { return decomposition_; }
  // More than one rank; then ghosts() are the nodes this rank shares with others (null otherwise).
  bool distributed() const { return distributed_; }
  GhostNodes* ghosts() { return distributed_ ? &ghosts_ : nullptr; }
  int ghostWidth() const { return ghostWidth_; }
  // How the last step changed material m's particles on this rank, for per-particle histories
  // kept elsewhere (StateChecks follows its own with it). First splitting: of the
  // `beforeSplitting` particles, those listed in `split` (in this order) split, and each one's 3
  // children were appended in that order. Then migration (distributed runs; `migrated` is false
  // when nothing moved): of the `beforeMigration` particles, those at the indices `kept` stayed,
  // in that order, and `arrived` others follow them.
  struct Reordering {
    size_t beforeSplitting = 0;
    std::vector<SplitParticle> split;
    bool migrated = false;
    size_t beforeMigration = 0, arrived = 0;
    std::vector<long> kept;
  };
  const std::vector<Reordering>& lastReordering() const { return reordering_; }
  // Counts the times the particles were shared out among the ranks (setup, restart, rebalance):
  // per-particle histories kept elsewhere start over when it changes.
  int layoutGeneration() const { return layoutGeneration_; }
  const MPMFlags& flags() const { return flags_; }
  const std::vector<MPMMaterial>& materials() const { return materials_; }
  std::vector<MPMMaterial>& materials() { return materials_; }
  const std::vector<GridFields>& gridFields() const { return fields_; }
  // The step's interpolation weights (per material) and the nodes its particles touch.
  const std::vector<InterpolationWeights>& weights() const { return weights_; }
  const ActiveNodes& activeNodes() const { return active_; }
  const Contact& contact() const { return contact_; }
  const GridBoundaryConditions& gridBCs() const { return gridBCs_; }
  // Setup's notes on bodies that would swell into a Symmetric face (SwellingRoom.h).
  const std::vector<std::string>& swellingNotes() const { return swellingNotes_; }
  // The diffusion subcomponent; null without <do_scalar_diffusion>true.
  const ReactiveFlow* diffusion() const { return diffusion_.get(); }
  ReactiveFlow* diffusion() { return diffusion_.get(); }
  // For an output that saves them: the concentration fields of every material, also of those
  // whose concentration cannot change (ReactiveFlow::computesConcentration).
  void computeConcentrationOfEveryMaterial() { diffusion_->computeEveryMaterial(); }
  size_t numParticles() const;  // on this rank
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
  void scatterParticlesToGrid(bool concentrationOnly = false);
  // Material m takes part in that P2G (and its ghost sums).
  bool scatters(size_t m, bool concentrationOnly) const {
    return !concentrationOnly || diffusion_->computesConcentration(m);
  }
  // Completes the nodal sums of P2G on the nodes shared with other ranks (`concentrationOnly`:
  // as interpolateParticlesToGrid's).
  void sumGhostNodes(bool concentrationOnly = false);
  // Keeps this rank's particles (all of the problem's are here when `allHere`) under a new
  // decomposition from the particle counts per cell plane, and lays out its window.
  void decompose(bool allHere);
  // Lays out this rank's window and its shared nodes under decomposition_.
  void layOutWindow();
  // Reads particle arrays and the scalars; appends to this rank's particles when `append`.
  void readState(BinaryReader& in, bool append);
  void layOutGrid();
  int computeGhostWidth(bool allHere) const;
  // Setup per box (MPMRanks.cc): this rank's box, drawn from the particle counts of seeds_ (the
  // whole grid on one rank); the box grown by what flagging the flux particles needs around it;
  // the particle count of a region against the memory budget; dropping the particles beyond the
  // box once flagged.
  CellBox setupBox();
  CellBox grownBySetupReach(const CellBox& box) const;
  void checkParticlesOfRank(const CellBox& region) const;
  void keepParticlesOfBox(const CellBox& box);
  // The boxes of this rank count by recursive bisection (`earlier`, when it has as many, where a
  // box cannot be cut) from the particles per cell: those of the particles (of every rank's
  // unless `allHere`), or of seeds_ (setup's, before any particle is created).
  Decomposition drawBoxes(const Decomposition::ParticleCounts& counts,
                          const Decomposition* earlier) const;
  Decomposition::ParticleCounts particleCounts(bool allHere) const;
  Decomposition::ParticleCounts seedCounts() const;
  // The ghost layers of the interpolator for CPDI domains reaching `reach` cells.
  int ghostWidthFor(double reach) const;
  // The grid arrays the ghost sums after P2G complete (`concentrationOnly`: the concentration's).
  std::vector<NodeArray> ghostSumArrays(bool concentrationOnly = false);
  // Rank of the box holding material m's particle i.
  int ownerOf(const ParticleSet& p, size_t i) const;
  template <class Concentration>
  void scatterMaterial(size_t m, const Concentration& concentration, bool concentrationOnly);

  MPMFlags flags_;
  Grid whole_;  // the problem's grid
  Grid grid_;   // the nodes this rank stores
  Decomposition decomposition_;
  GhostNodes ghosts_;
  int ghostWidth_ = 0;
  bool distributed_ = false;  // more than one rank
  std::vector<Reordering> reordering_;
  int layoutGeneration_ = 0;
  std::vector<std::string> swellingNotes_;
  GridBoundaryConditions gridBCs_;
  Contact contact_;
  std::vector<MPMMaterial> materials_;
  std::unique_ptr<ReactiveFlow> diffusion_;  // only with <do_scalar_diffusion>true
  int64_t nextParticleId_ = 0;
  std::vector<MaterialSeeds> seeds_;  // setup only: what the geom_objects lay out
  double initTime_ = 0;
  // The nodes the particles touch this step; grid loops run over them only. Outside, nodal
  // fields are zero (the previous step's box is cleared too) except the values face boundary
  // conditions set.
  ActiveNodes active_;
  NodeBox previous_;

  std::vector<GridFields> fields_;              // per material
  std::vector<InterpolationWeights> weights_;   // per material, for the current step
  std::vector<std::vector<uint8_t>> capacity_;  // per material: weight entries per particle
  // Node quads (NodeQuads.h): what P2G sums per node, then what G2P reads per node; and P2G's
  // sums per thread after the first (P2G without locks).
  std::vector<NodeQuad> nodeQuads_;
  std::vector<std::vector<NodeQuad>> threadScatter_;
  TaskTimers timers_;
  int particlesToGridTask_ = -1, communicationTask_ = -1;
};

}  // namespace anode
