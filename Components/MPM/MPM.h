// The MPM component: owns the materials' particles and the grid fields and advances them one
// explicit step at a time in the paper's order (DESIGN.md §4); its diffusion subcomponent,
// ReactiveFlow, exists only with <do_scalar_diffusion>true.
#pragma once

#include <memory>
#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/Contact/Contact.h"
#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/GridBoundaryConditions.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Implicit/EquilibriumSolver.h"
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
  void problemSetup(const PSNode& root, double initTime, double maxTime, bool withParticles = true);
  // After problemSetup: lays out this rank's grid and completes the setup over the ranks (the
  // flux BCs' areas and capacities, their report).
  void distributeOverRanks(Collective);

  // Advances the state from time t by dt (DESIGN.md §4). Throws SimulationError when a particle
  // leaves the grid, J <= 0, or a concentration leaves [min, max] beyond kConcentrationTolerance
  // (in a distributed run on every rank together: Core/Parallel/StopTogether.h).
  void timeAdvance(Collective, double t, double dt);
  // The quasi-static step of an implicit run (DESIGN.md §4b, MPMQuasiStatic.cc): diffusion over
  // dt in sub-steps of substepMultiplier times its explicit limits, then Newton on the grid for
  // the equilibrium at t + dt; a step Newton does not converge in is retaken with dt times
  // <delT_decrease_factor>, and below dtMin the run stops (SimulationError). Returns the dt taken.
  // ruleDt: the dt the limits chose, of which dt may be a part (<clamp_time_to_output> shortens
  // a step to end on an output time); the next step's dt follows Newton's iterations from it.
  double advanceQuasiStatic(Collective, double t, double dt, double ruleDt, double dtMin,
                            double substepMultiplier);
  // The last quasi-static step's ruleDt (its dt where it was retaken).
  double lastRuleDt() const { return newtonRuleDt_; }
  // Newton's iterations: of the last step, and the totals of the steps (and retaken attempts)
  // of this process.
  struct NewtonCounts {
    // The last step's: its equilibrium's Newton iterations (those the dt rule counts), the
    // prediction's (<concentration_coupling>trapezoidal) and the Krylov iterations of both.
    int lastIterations = 0, lastPredictorIterations = 0, lastKrylov = 0;
    // The last step's coupling correction (<concentration_coupling>trapezoidal; -1 otherwise):
    // sum m |dc_2 - dc_1| / 2 over every rank's particles, dc_1 and dc_2 the two passes' changes
    // of c, the lithium by which the step's mean differs from either pass.
    double lastCouplingCorrection = -1;
    long iterations = 0, krylov = 0, retakes = 0, diffusionSubsteps = 0, preconditionerSetUps = 0,
         newTangents = 0;
    std::vector<std::pair<double, double>> lastRatios;  // NewtonReport::ratios of the last step
    std::vector<double> lastLinearTolerances;           // and its linearTolerances
    // One Newton solve's iterations, new tangents, Krylov iterations and set-ups into the totals.
    void add(const NewtonReport& r) {
      iterations += r.iterations;
      krylov += r.krylovIterations;
      preconditionerSetUps += r.preconditionerSetUps;
      newTangents += r.newTangents;
    }
    // "Newton 4, Krylov 31" ("Newton 4 + 2 predicting, ..."): the last step, for the progress
    // line.
    std::string lastStep() const;
    // The totals over `steps` steps, for the end summary.
    std::string summary(long steps) const;
  };
  const NewtonCounts& newtonCounts() const { return newton_; }
  // Largest stable dt of the current state before the multiplier: paper Eq. 45, the smallest of
  // the mechanical Eq. 43 and the diffusion limits (Eq. 44 and the flux limit).
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
  // The step's tasks, in order (DESIGN.md §4).
  // The weights on every rank (a problem on one stops them all), then the step's active nodes.
  void computeWeightsAndActiveNodes();
  // This rank's weights; returns the box of nodes they touch.
  NodeBox computeInterpolationWeights();
  // Particle i's weights on grid g (the count, or -1 beyond its stored nodes).
  int computeWeights(const Grid& g, const ParticleSet& p, long i, int32_t* node, double* w,
                     Vec3* grad) const;
  // Material m's particle i reaches beyond the stored nodes: off the grid, or (distributed)
  // beyond the ghost layer.
  [[noreturn]] void throwOutsideWindow(size_t m, long i) const;
  // P2G; `concentrationOnly`: the concentration's sums alone, of the materials whose
  // concentration changes (diffusion on), after a full P2G of the same particles that changed
  // nothing but their concentration since (the diffusion sub-steps of a quasi-static step).
  void interpolateParticlesToGrid(bool concentrationOnly = false);
  // Material m takes part in that P2G (and its ghost sums).
  bool scatters(size_t m, bool concentrationOnly) const {
    return !concentrationOnly || diffusion_->computesConcentration(m);
  }
  void exchangeMomentumInterpolated();
  void integrateGridMomentum(double dt);
  void setGridBoundaryConditions(double dt);
  void interpolateToParticlesAndUpdate(double dt);
  void splitParticles();
  void migrateParticles();
  // Completes the nodal sums of P2G on the nodes shared with other ranks (`concentrationOnly`:
  // as interpolateParticlesToGrid's).
  void sumGhostNodes(bool concentrationOnly = false);
  void computeNodalVelocityAndConcentration();
  // Eq. 5 and the diffusion interface (diffusion on).
  void computeNodalConcentration();
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
  // The equilibrium problem of the step: fields, nodal masses, the displacement increments the
  // Velocity and Symmetric faces prescribe over dt.
  EquilibriumProblem equilibriumProblem(double dt);
  // Implicit dynamics: the problem's nodal velocities and accelerations of the step's start, from
  // the particles (momentum from the P2G of the step, sum m a S here; Implicit/Newmark.h).
  void addStartOfStepMotion(EquilibriumProblem& problem, double dt);
  // A quasi-static step's predicted increments: the start-of-step nodal velocity times dt.
  void addPredictedIncrement(EquilibriumProblem& problem, double dt);
  // P2G and, distributed, its sums completed on the shared nodes (`concentrationOnly`: as
  // interpolateParticlesToGrid's, for a diffusion sub-step after the first of a pass).
  void interpolateAndSumOverRanks(bool concentrationOnly = false);
  // Diffusion over the quasi-static step in explicit sub-steps on its start-of-step configuration;
  // concentrationChange_ receives each particle's change.
  // Collective: a diffusion sub-step's length, substepMultiplier times the smaller of Eq. 44 and
  // the flux limit over all ranks.
  double diffusionSubstepLimit(double substepMultiplier) const;
  void diffuseOverStep(double t, double dt, double substepMultiplier);
  // <diffusion_integrator>rkl2: diffuseOverStep's pass as one RKL2 step over dt, its stages as
  // many as the sub-steps' limit at the start needs (Implicit/RungeKuttaLegendre.h).
  void diffuseInLegendreStages(double t, double dt, double substepMultiplier);
  // <subcell_concentration_relaxation>: the particles drawn towards the grid's c of their P2G over
  // dt (ReactiveFlow/SubcellRelaxation.h), their change added to concentrationChange_.
  void relaxSubcellConcentration(double dt);
  // <concentration_coupling>trapezoidal: after diffuseOverStep on the step's start (`start`, the
  // diffusion's `atStart`), a Newton solve to kPredictorConvergence predicts the step's end; the
  // sub-steps run again on those particles from the start's c, and the particles are set back to
  // the start with c changed by the mean of the two passes (concentrationChange_ too). Returns the
  // prediction's Newton (a failed one: the step is retaken), its increments by field in
  // `predicted`, the final solve's first iterate, and the coupling correction in `correction`
  // (NewtonCounts::lastCouplingCorrection).
  NewtonReport averageConcentrationChangeOverStep(double t, double dt, double substepMultiplier,
                                                  const std::vector<ParticleSet>& start,
                                                  const ReactiveFlow::StepState& atStart,
                                                  std::vector<std::vector<Vec3>>& predicted,
                                                  double& correction);
  // The largest |dc| of a particle over the diffusion of the step.
  double largestConcentrationChange() const;
  // The particles after the converged step (positions, F, stress, the models' state).
  void updateParticlesFromEquilibrium(double dt);
  // The setup checks of an implicit run: what it does not support is an input error.
  void checkImplicitSetup(const PSNode& root) const;
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
  // Implicit runs: the Newton solver, the field of each material (single_velocity members share
  // one), the last step's dt and counts.
  EquilibriumSolver equilibrium_;
  std::vector<int> fieldOf_;
  std::vector<std::vector<double>> concentrationChange_;  // per material: dc of the step
  std::vector<double> nodeMassDiffusivity_;               // relaxSubcellConcentration's sum S m D
  double lastQuasiStaticDt_ = 0;
  double newtonRuleDt_ = 0;  // what ImpMPM's rule scales: the last step's dt, or its ruleDt
  // The largest |dc| of a particle in the last quasi-static step (with diffusion).
  double maxConcentrationChange_ = 0;
  NewtonCounts newton_;
  TaskTimers timers_;
  struct StepTasks {  // timer indices of the step's tasks
    int interpolationWeights, particlesToGrid, gridIntegration, particleUpdate, splitting,
        diffusionState, communication;
  } tasks_{};
};

}  // namespace anode
