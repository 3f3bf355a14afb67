// The flux boundary conditions at work (paper Eqs. 16-17, docs/diffusion.md step 1): which
// particles each <scalar_flux> flags and with what area, their flux rate at time t, the nodes
// their sources reach, and the sign flips of <do_auto_cycle_bc>.
#pragma once

#include <string>
#include <vector>

#include "Components/MPM/ActiveNodes.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/ReactiveFlow/DiffusionParticles.h"
#include "Components/MPM/ReactiveFlow/FluxSurfaceArea.h"
#include "Components/MPM/ReactiveFlow/ScalarDiffusionModel.h"
#include "Components/MPM/ReactiveFlow/ScalarFluxBC.h"
#include "Components/MPM/SplitParticle.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/BinaryStream.h"

namespace anode {

class ExternalScalarFlux {
 public:
  ExternalScalarFlux() = default;
  explicit ExternalScalarFlux(std::vector<ScalarFluxBC> bcs) : bcs_(std::move(bcs)) {}

  const std::vector<ScalarFluxBC>& bcs() const { return bcs_; }
  // The first time after t at which a BC's load curve changes its slope (infinity: none).
  double nextLoadCurveTimeAfter(double t) const;

  // What one BC flagged in one material (the setup report).
  struct Flagged {
    size_t bc, material, particles = 0;
    double area = 0;         // the flagged particles' areas, summed
    double surfaceArea = 0;  // curved faces of grid-filled bodies: the BC surface's whole area,
    double bodyArea = 0;     // and the part of it on the body (FluxSurfaceArea.h); 0 otherwise
  };
  // Gives the surface particles of each material that diffuses (per material in `seeds`), per BC
  // that flags them, their area of the face that BC names (docs/diffusion.md, "Flux area at the
  // start"). Returns what each BC flagged in each material that diffuses, counting the
  // particles in the cells of `counted` (this rank's box; those in `kept` around it are there
  // for the sharing of a surface), and the areas of its box's part of the shared surfaces.
  std::vector<Flagged> assignToParticles(std::vector<MPMMaterial>& materials,
                                         const std::vector<DiffusionMaterial>& diffusion,
                                         const std::vector<MaterialSeeds>& seeds, const Grid& grid,
                                         const CellBox& counted, const CellBox& kept) const;
  // Eqs. 16-17: rate_p = R(c_p) sum_k J_k(t) A_k / V_p, the restriction applied once; also the
  // largest unrestricted inflow and outflow rates, sum J A / V over the BCs of either sign, for
  // the time-step limit. A galvanostatic BC's J_k is its lithium rate Q_k(t) over
  // sum_p m_p R(c_p) A_pk / V_p (its flagged particles, over every rank when `overRanks`; at
  // setup each rank holds them all): its particles take up Q_k in all, shared as a uniform flux
  // would share it.
  void computeFluxRates(Collective, std::vector<MPMMaterial>& materials,
                        const std::vector<DiffusionMaterial>& diffusion, double t, bool overRanks);
  // Per BC, the lithium its materials hold at max_concentration (sum m c_max over every particle
  // of each material it flags), to which a C-rate load refers. At setup, before the first rates.
  void setCapacities(std::vector<double> capacities) { capacities_ = std::move(capacities); }
  // The notes of galvanostatic BCs whose current ended since the last call (rank 0 prints them).
  std::vector<std::string> takeNotes();
  // Per BC, the electrode's potential (V) of a <surface_reaction> at the last flux rates; NaN
  // for the other BCs.
  const std::vector<double>& potentials() const { return potentials_; }
  // The flux limit (docs/diffusion.md, "Time step"): the longest step in which no particle of a
  // material the fluxes reach passes the restriction's root, taken at the fullest particle below
  // the root (the emptiest above the mirrored root for an outflow), as every particle's source
  // is at most R(c) times the largest rate; over all ranks, infinity without flux.
  double stableTimestep(Collective, const std::vector<MPMMaterial>& materials,
                        const std::vector<DiffusionMaterial>& diffusion) const;
  // <do_auto_cycle_bc>: flips the sign of every flux when the concentration of the materials
  // with <do_conc_reduction> crosses the thresholds.
  void updateAutoCycle(Collective, const std::vector<MPMMaterial>& materials,
                       const std::vector<DiffusionMaterial>& diffusion, const MPMFlags& flags);
  // Particle splitting: each split particle's flux faces shared among its children (a face
  // normal to the split goes whole to the child nearest it, one along it to all 4, a quarter
  // of its area each).
  void shareFacesOnSplit(ParticleSet& p, const std::vector<SplitParticle>& splits) const;

  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in, bool merge = false);  // merge: ReactiveFlow::loadState

 private:
  // A <surface> BC b on material m: its free-surface particles flagged with their share of the
  // body's free surface (FluxSurfaceArea.h); adds to count, holding and slots as the geometry
  // BCs do.
  void flagFreeSurface(size_t b, size_t m, std::vector<MPMMaterial>& materials,
                       const std::vector<MaterialSeeds>& seeds, const Grid& grid,
                       const SampleRegion& region, size_t& count, std::vector<size_t>& holding,
                       std::vector<int>& slots, SurfaceShare& share) const;
  // The flux J_k of each BC at time t: its load (times the auto-cycle sign), or for a
  // galvanostatic BC the J that delivers its lithium rate (its load, or for a C-rate the load
  // times its capacity per hour; 0 from its cutoff to the end of its load curve's segment).
  std::vector<double> fluxes(Collective, const std::vector<MPMMaterial>& materials,
                             const std::vector<DiffusionMaterial>& diffusion, double t,
                             bool overRanks);

  // The potential at which surface-reaction BC b's particles take up `lithiumRate` (sum m c per
  // time) at time t, its cutoffs applied (the current ends, or resumes, as a restriction cutoff
  // does); over every rank when `overRanks`.
  double electrodePotential(Collective, const std::vector<MPMMaterial>& materials,
                            const std::vector<DiffusionMaterial>& diffusion, size_t b,
                            double lithiumRate, double t, bool overRanks);

  // Whether galvanostatic BC b, its current ended by a cutoff, may resume at t with the load's
  // `lithiumRate`: in a later segment (or auto-cycle sign), once the load runs the way the
  // segment ends (past a ramp's turn: a ramp's start may still run the finished way).
  bool mayResume(size_t b, double lithiumRate, double t) const;
  // endedIn_'s value for BC b at t: its load curve's segment times 2, plus 1 if the auto-cycle
  // sign is negative.
  long segmentOf(size_t b, double t) const;

  std::vector<ScalarFluxBC> bcs_;
  std::vector<double> potentials_;  // per BC: electrodePotential's, NaN for the others
  // Per BC: -1 while a galvanostatic BC's current runs; once its flagged surface reached its
  // cutoff, the load curve's segment (LoadCurve::segmentAt) at that time, times 2, plus 1 if the
  // auto-cycle sign was negative. The current resumes as mayResume allows once the surface's
  // mean restriction for the direction it then runs in is above the cutoff.
  std::vector<long> endedIn_;
  std::vector<double> capacities_;  // per BC (setCapacities)
  std::vector<std::string> notes_;
  double sign_ = 1;            // do_auto_cycle_bc: +1 lithiates, -1 delithiates
  double maxInflowRate_ = 0;   // max over particles of sum J A / V over the BCs with J > 0
  double maxOutflowRate_ = 0;  // the same for |J|, J < 0
};

// Marks the nodes the flux sources of this step reach (after zeroing the nodes of `cleared`):
// those of the particles with a nonzero flux rate, bit 1 for an inflow, bit 2 for an outflow.
void markSourceNodes(const ParticleSet& p, const InterpolationWeights& W,
                     std::vector<unsigned char>& reached, const std::vector<NodeRange>& cleared);

}  // namespace anode
