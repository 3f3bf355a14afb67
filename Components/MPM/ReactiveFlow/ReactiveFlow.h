// ReactiveFlow: the diffusion subcomponent of MPM (paper §2, Eqs. 2-8, 16-18, 23-24, 44; the
// method step by step in docs/diffusion.md). It exists only with <do_scalar_diffusion>true and
// owns everything diffusion: its particle arrays (DiffusionParticles, declared on each material's
// particles), its grid fields, each material's diffusivity model, the flux BCs with their
// restriction and receivers, the SD-Type conditions, the diffusion interface, its time-step limit
// and its checkpoint state. MPM calls it at named points of the step; the per-particle work runs
// inside MPM's fused particle loops through the kernels it hands out (ConcentrationKernels.h), so
// diffusion adds no pass over the particles.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/PhysicalBCs.h"
#include "Components/MPM/ReactiveFlow/ConcentrationBCs.h"
#include "Components/MPM/ReactiveFlow/ConcentrationKernels.h"
#include "Components/MPM/ReactiveFlow/DiffusionGridFields.h"
#include "Components/MPM/ReactiveFlow/DiffusionInterface.h"
#include "Components/MPM/ReactiveFlow/ExternalScalarFlux.h"
#include "Components/MPM/StableTimestep.h"
#include "Components/MPM/StepSummary.h"
#include "Core/Util/BinaryStream.h"

namespace anode {

class ReactiveFlow {
 public:
  // --- What MPM and the driver ask of it. At setup, in this order: ---

  // With <do_scalar_diffusion>true: reads <diffusion_interface>, the <scalar_flux> blocks of
  // `physical`, each material's <diffusion_model> (`maxTime` bounds its diff_curve) and the
  // SD-Type <BCType>s of <Grid><BoundaryConditions> (`concentrationBCs`, in file order). Without
  // it: null, and the tags that would need diffusion are errors, not silently dropped (an SD-Type
  // condition: ConcentrationBC::rejectWithoutDiffusion); the diffusion tags of the materials are
  // read as Uintah reads them then (not at all).
  static std::unique_ptr<ReactiveFlow> fromInput(const PSNode& root, const MPMFlags& flags,
                                                 const std::vector<MPMMaterial>& materials,
                                                 double maxTime, const PhysicalBCs& physical,
                                                 const std::vector<BCType>& concentrationBCs);
  // The cells whose particles a rank holds while it flags the flux particles of `box` (its box of
  // the problem's grid `whole`; `seeds`: what the geom_objects lay out): the box, and in a
  // distributed run where setup shares a BC's surface out among the particles near it (a curved
  // face of a grid-filled body, or a <surface>; FluxSurfaceArea.h) the cells within 3 particle
  // spacings of it as well.
  CellBox setupRegion(const CellBox& box, const Grid& whole,
                      const std::vector<MaterialSeeds>& seeds) const;
  // Declares the diffusion arrays on the materials' particles (this rank's, and in a distributed
  // run those around its box) and sets their initial state: each <geom_object>'s
  // <concentration> (`seeds`: which object laid out which particles) and the diffusivity D0;
  // flags the flux particles (`seeds` holds the surface particles), counting those in the cells
  // of `box` (this rank's; `region`, holding it, has the particles a shared surface can go to).
  // Calls no collective.
  void initialize(const PSNode& root, const Grid& grid, std::vector<MPMMaterial>& materials,
                  const std::vector<MaterialSeeds>& seeds, const CellBox& box,
                  const CellBox& region, double initTime);
  // Once each rank holds only its own particles: the flagged particles, their areas and the
  // capacities over every rank, the input errors they show (a BC flagging nothing) and the
  // initial flux rates. `everyMaterial`: the output saves a nodal concentration
  // (g.concentration*) or p.concentrationGradient, which are then computed for every material,
  // those whose concentration no step can change included. Returns the lines for the user: per
  // flux BC and material, the particles flagged and their area, and the materials that take up
  // no lithium (the same on every rank).
  std::vector<std::string> completeSetup(Collective, std::vector<MPMMaterial>& materials,
                                         double initTime, bool everyMaterial);
  // Lays out the grid fields on the nodes this rank stores (`grid`: the whole grid, or this
  // rank's window); `ghosts` completes the source marks on the nodes shared with other ranks
  // (none: a run of one rank). Returns them, per material (empty for one that does not compute
  // its concentration), for MPM's grid of the step to hold beside the mechanics' fields
  // (StepGrid::concentration), as the diffusion's particle arrays are held on MPM's particles:
  // the ghost sums after P2G complete those P2G summed there. The vector stays in place until the
  // next call; completeSetup may lay out more of its fields.
  std::vector<ConcentrationGridFields>& layOutGrid(const Grid& grid, const GhostNodes* ghosts);

  // --- In the step, in the order ExplicitStep::advance asks (P2G and G2P run the kernels of
  // withScatterKernel and withGatherKernel, below): ---

  // Eq. 5: c = (mc)/m, then the SD-Type conditions, per material; after all materials, the
  // interface. All on the nodes of `nodes` (the step's active nodes).
  void computeNodalConcentration(const std::vector<GridFields>& mechanics,
                                 const std::vector<NodeRange>& nodes);
  // Eq. 18: c* = c + (R + G)/m dt and the nodal rate that drives Eq. 8.
  void integrateConcentration(const std::vector<GridFields>& mechanics, double dt,
                              const std::vector<NodeRange>& nodes);
  // After particle splitting: the flux faces of the split particles shared among their children.
  void shareFluxFaces(ParticleSet& p, const std::vector<SplitParticle>& splits) const {
    flux_.shareFacesOnSplit(p, splits);
  }
  // After G2P at time t: the range diagnostic, the auto-cycle switch, and the new state's
  // diffusivity (Eq. 23 or 24) and flux rates (Eqs. 16-17), which output, the next time step
  // and the next step use.
  void updateDiffusionState(Collective, std::vector<MPMMaterial>& materials, double t);
  // The diffusion's bounds of the stable time step: Eq. 44 over this rank's particles, and the
  // flux limit over all ranks (diffusionTimestep, fluxTimestep).
  void boundTimestep(Collective every, const Grid& grid, const std::vector<MPMMaterial>& materials,
                     StableTimestep& limits) const {
    limits.bound[StableTimestep::Diffusion] = diffusionTimestep(grid);
    limits.bound[StableTimestep::Flux] = fluxTimestep(every, materials);
  }

  // --- For checkpoints and output: ---

  void saveState(BinaryWriter& out) const;
  // `merge`: a further part of a distributed checkpoint read by this rank (another rank count):
  // the largest diffusivity and flux rates are the largest of the parts', whose particles this
  // rank now holds some of (the time-step limits are minimums over the ranks).
  void loadState(BinaryReader& in, bool merge = false);
  // Adds the total lithium and the concentration range (initialised by the caller): the range
  // of the materials whose concentration can change (computesConcentration without output's
  // request), of every material when none can; with two or more such materials, each one's
  // sum and range (appended to StepSummary::perMaterial).
  void summarize(const std::vector<MPMMaterial>& materials, StepSummary& s) const;
  // Material m's diffusivity model.
  const ScalarDiffusionModel& model(size_t m) const { return *materials_[m].model; }
  // What happened in the steps since the last call that the user should know (a galvanostatic
  // BC's current ending); the same on every rank.
  std::vector<std::string> takeRunNotes() { return flux_.takeNotes(); }
  // The first time after t at which a flux BC's load curve changes its slope (infinity: none):
  // an error-controlled step ends there.
  double nextLoadChangeAfter(double t) const { return flux_.nextLoadCurveTimeAfter(t); }

  // --- What the diffusion folder asks of it: the kernel choice (withScatterKernel,
  // withGatherKernel) and the quasi-static step (DiffusionPass). ---

  // Before P2G of material m: zeroes its fields on the nodes of `cleared` and marks the nodes
  // its flux sources reach; then calls f with the material's P2G kernel.
  template <class F>
  void withScatter(Collective, size_t m, const ParticleSet& p, const InterpolationWeights& W,
                   const std::vector<NodeRange>& cleared, F&& f);
  // Calls f with material m's G2P kernel (Eq. 8).
  template <class F>
  void withGather(size_t m, ParticleSet& p, F&& f);
  // False for a material whose concentration no step can change: no diffusivity, no constant
  // rate, no <scalar_flux>, no SD-Type condition, no common interface (docs/diffusion.md,
  // "Materials that take up no lithium"). Its P2G and G2P run without concentration, its
  // diffusivity stays 0 and it has no nodal concentration fields, unless the output saves them.
  bool computesConcentration(size_t m) const { return changes_[m] || everyMaterial_; }
  // Material m's flux has a stress part (chemical_potential with k > 0): its particles carry
  // p.stressPotentialGradient, which DiffusionPass sets at each pass's start.
  bool stressDriven(size_t m) const {
    return changes_[m] && model(m).stressPotentialPerStress() > 0;
  }
  // The largest change of c a quasi-static step may make where a stress-driven flux takes the
  // stress's local response linearized (ChemicalPotential.h): c_max / s, the step over which that
  // response moves phi by 1; infinity without one.
  double stressDrivenConcentrationChange() const;
  // The grid fields layOutGrid returned (DiffusionPass's sub-cell relaxation); outside the
  // folder the step's grid holds them (StepGrid::concentration).
  const std::vector<ConcentrationGridFields>& gridFields() const { return fields_; }
  // SD-Type concentration conditions (<BCType ... label="SD-Type">) on some grid face
  // (DiffusionPass::checkIntegrator).
  bool hasConcentrationBCs() const { return !concentrationBCs_.empty(); }
  // Eq. 44 over this rank's particles: dx^2 / (2 D_max), infinity without diffusivity.
  double diffusionTimestep(const Grid& grid) const;
  // The flux limit over all ranks (docs/diffusion.md, "Time step").
  double fluxTimestep(Collective every, const std::vector<MPMMaterial>& materials) const {
    return flux_.stableTimestep(every, materials, materials_);
  }
  // The state a quasi-static step retaken with a smaller dt starts again from (DiffusionPass):
  // the flux BCs' (the auto-cycle sign, the galvanostatic currents ended, their notes) and the
  // diffusivity models' (the interval a <diff_curve> is in) and the largest diffusivity: all
  // saveState writes, so a step dropped leaves the checkpoint of the step before.
  struct StepState {
    ExternalScalarFlux flux;
    std::vector<std::vector<uint64_t>> models;
    double maxDiffusivity = 0;
  };
  StepState stepState() const;
  void restoreStepState(const StepState& state);

 private:
  ReactiveFlow(const PSNode& root, const MPMFlags& flags, const std::vector<MPMMaterial>& materials,
               double maxTime, const PhysicalBCs& physical,
               const std::vector<BCType>& concentrationBCs);
  void computeDiffusivity(std::vector<MPMMaterial>& materials, double t);
  void checkConcentrationRange(const std::vector<MPMMaterial>& materials, double t) const;
  bool concentrationCanChange(size_t m, const ScalarDiffusionModel& model) const;
  // The <surface> BCs' material names exist, their bodies are grid-filled, no splitting.
  void checkSurfaceBCs(const PSNode& root, const std::vector<MPMMaterial>& materials,
                       const std::vector<MaterialSeeds>& seeds) const;

  MPMFlags flags_;
  std::vector<DiffusionMaterial> materials_;  // per material
  Grid grid_;
  std::vector<ConcentrationBC> concentrationBCs_;  // SD-Type, in file order
  DiffusionInterface interface_;
  ExternalScalarFlux flux_;
  std::vector<std::vector<double>> dirichletMask_;  // per material, per node: 1 on Dirichlet nodes
  std::vector<double> cmax_;                        // per material: max_concentration
  std::vector<double> constantRate_;             // per material: constant_rate (0 for the others)
  std::vector<bool> receivesFlux_;               // per material
  std::vector<bool> changes_;                    // per material: concentrationCanChange
  bool everyMaterial_ = false;                   // completeSetup's everyMaterial
  double maxDiffusivity_ = 0;                    // over all particles, for Eq. 44
  std::vector<ConcentrationGridFields> fields_;  // per material
  std::vector<ExternalScalarFlux::Flagged> flagged_;  // this rank's, between the two setup calls
  std::string inputFile_;                             // for the errors completeSetup finds
  const GhostNodes* ghosts_ = nullptr;
};

// The one place that chooses the diffusion kernels of MPM's fused particle loops: material m's
// P2G or G2P kernel, ReactiveFlow's or NoConcentration in a run without diffusion (`diffusion`
// null), handed to f, so that the caller's loop is compiled per kernel type.
template <class F>
void withScatterKernel(Collective every, ReactiveFlow* diffusion, size_t m, const ParticleSet& p,
                       const InterpolationWeights& W, const std::vector<NodeRange>& cleared,
                       F&& f) {
  if (diffusion)
    diffusion->withScatter(every, m, p, W, cleared, f);
  else
    f(NoConcentration{});
}
template <class F>
void withGatherKernel(ReactiveFlow* diffusion, size_t m, ParticleSet& p, F&& f) {
  if (diffusion)
    diffusion->withGather(m, p, f);
  else
    f(NoConcentration{});
}
// The node quads per node that P2G with these kernels adds into (NodeQuads.h).
inline int scatterQuadsPerNode(const ReactiveFlow* diffusion) {
  return diffusion ? ScatterTerms<ConcentrationScatter<true>::scatterWeightQuads>::quads
                   : ScatterTerms<NoConcentration::scatterWeightQuads>::quads;
}

template <class F>
void ReactiveFlow::withScatter(Collective every, size_t m, const ParticleSet& p,
                               const InterpolationWeights& W, const std::vector<NodeRange>& cleared,
                               F&& f) {
  if (!computesConcentration(m)) return f(NoConcentration{});
  ConcentrationGridFields& g = fields_[m];
  forEachNodeRange(cleared, [&g](long begin, long end) { g.clearAll(begin, end); });
  if (receivesFlux_[m]) {
    markSourceNodes(p, W, g.sourceReached, cleared);
    if (ghosts_) ghosts_->unionOverRanks(every, g.sourceReached);
    f(ConcentrationScatter<true>(p, W, g.sourceReached.data(), cmax_[m], g,
                                 flags_.restrictedFluxReceivers, model(m).D0));
  } else {
    f(ConcentrationScatter<false>(p, W, nullptr, cmax_[m], g, true, model(m).D0));
  }
}

template <class F>
void ReactiveFlow::withGather(size_t m, ParticleSet& p, F&& f) {
  if (!computesConcentration(m)) return f(NoConcentration{});
  // Particle treatment of SD-Type Dirichlet (docs/diffusion.md): a particle touching a boundary
  // node takes the grid solution instead of Uintah's nodal rate.
  const double* wall =
      flags_.particleDirichlet && !dirichletMask_.empty() ? dirichletMask_[m].data() : nullptr;
  const ConcentrationGridFields& g = fields_[m];
  if (receivesFlux_[m]) {
    if (wall)
      f(ConcentrationGather<true, true>(p, g, wall, cmax_[m], flags_.restrictedFluxReceivers));
    else
      f(ConcentrationGather<true, false>(p, g, wall, cmax_[m], flags_.restrictedFluxReceivers));
  } else {
    if (wall)
      f(ConcentrationGather<false, true>(p, g, wall, cmax_[m]));
    else
      f(ConcentrationGather<false, false>(p, g, wall, cmax_[m]));
  }
}

}  // namespace anode
