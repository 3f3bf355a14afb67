// How a run's grid and particles are shared among its ranks (docs/parallel.md): the boxes of
// cells the ranks own (recursive bisection of the particles per cell), this rank's window of the
// grid (its box and the ghost layers around it), the nodes it shares with other ranks, and the
// moves that keep every particle in its owner's box. On one rank the window is the whole grid and
// nothing moves. The decomposition itself is Core/Parallel/Decomposition, the talking
// Core/Parallel/Communicator.
#pragma once

#include <functional>
#include <vector>

#include "Components/MPM/GhostNodes.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/SplitParticle.h"
#include "Core/Grid/Grid.h"
#include "Core/Parallel/Decomposition.h"
#include "Core/Util/BinaryStream.h"

namespace anode {

// How a step changed one material's particles on this rank, for per-particle histories kept
// elsewhere (StateChecks follows its own with it). First splitting: of the `beforeSplitting`
// particles, those listed in `split` (in this order) split, and each one's 3 children were
// appended in that order. Then migration (distributed runs; `migrated` is false when nothing
// moved): of the `beforeMigration` particles, those at the indices `kept` stayed, in that order,
// and `arrived` others follow them.
struct ParticleReordering {
  size_t beforeSplitting = 0;
  std::vector<SplitParticle> split;
  bool migrated = false;
  size_t beforeMigration = 0, arrived = 0;
  std::vector<long> kept;
};

class RankLayout {
 public:
  // The boxes of a distributed run as its checkpoint keeps them.
  struct Saved {
    Decomposition boxes;
    int ghostWidth = 0;
  };

  // `materials`: the particle sets it shares out (MPM's); `windowChanged` is called each time
  // this rank's window is laid out anew (MPM sizes its grid fields to it).
  RankLayout(std::vector<MPMMaterial>& materials, std::function<void()> windowChanged);

  // The problem's grid, and this rank's window of it until the boxes are drawn.
  void setProblemGrid(const Grid& whole, InterpolatorKind interpolator);
  // Setup per box: this rank's box, drawn from the particles the geom_objects lay out per cell
  // (`seeds`, counted on every rank before any particle is created); the whole grid on one rank.
  CellBox drawSetupBoxes(const Decomposition::ParticleCounts& seeds);
  // After setup placed each rank's particles in its own box (or, on one rank, all of them):
  // lays out this rank's window and its shared nodes.
  void completeSetup(Collective);

  // Shares the particles out anew among the ranks from their counts per cell plane (after a
  // restart, or when the particles per rank have drifted apart).
  void redistributeParticles(Collective);
  // Largest over mean particles per rank.
  double imbalance(Collective) const;
  // Particles that left this rank's box go to its owner; `reordering` (per material) records
  // who stayed and how many arrived. A particle that moved beyond the boxes next to its rank's
  // stops the run (SimulationError on every rank).
  void migrateParticles(Collective, std::vector<ParticleReordering>& reordering);

  // Checkpoints: save writes the boxes, read reads them back, adopt takes them after each rank
  // loaded its own part.
  void save(BinaryWriter& out) const;
  static Saved read(BinaryReader& in);
  void adopt(Collective, const Saved& saved);
  // After every rank loaded all particles (a one-rank checkpoint on several ranks): puts them in
  // ID order and keeps this rank's share under boxes drawn anew.
  void keepOwnShare(Collective);
  // After each rank loaded some parts of a distributed checkpoint of another rank count: shares
  // the particles out under boxes drawn anew, each rank's in ID order.
  void shareOutAnew(Collective);

  // Lays `window` out as this rank's (sus --decompose's grid of one cell, for the sizes of the
  // grid fields per node).
  void useWindow(const Grid& window);
  // The ghost layers of the interpolator for CPDI domains reaching `reach` cells.
  int ghostWidthFor(double reach) const;

  const Grid& problemGrid() const { return whole_; }
  // The nodes this rank stores (the whole grid on one rank).
  const Grid& window() const { return window_; }
  const Decomposition& boxes() const { return decomposition_; }
  // More than one rank; then ghosts() are the nodes this rank shares with others (null otherwise).
  bool distributed() const { return distributed_; }
  GhostNodes* ghosts() { return distributed_ ? &ghosts_ : nullptr; }
  int ghostWidth() const { return ghostWidth_; }
  // Counts the times the particles were shared out among the ranks (setup, restart, rebalance):
  // per-particle histories kept elsewhere start over when it changes.
  int generation() const { return generation_; }

 private:
  // Keeps this rank's particles (all of the problem's are here when `allHere`) under boxes drawn
  // anew from the particle counts per cell plane, and lays out its window.
  void decompose(Collective, bool allHere);
  // Lays out this rank's window and its shared nodes under decomposition_.
  void layOutWindow(Collective);
  int computeGhostWidth(Collective, bool allHere) const;
  // The boxes of this rank count by recursive bisection (`earlier`, when it has as many, where a
  // box cannot be cut) from the particles per cell.
  Decomposition drawBoxes(const Decomposition::ParticleCounts& counts,
                          const Decomposition* earlier) const;
  // The particles per cell of this rank's particles (summed over the ranks unless `allHere`).
  Decomposition::ParticleCounts particleCounts(Collective, bool allHere) const;
  // Rank of the box holding material m's particle i.
  int ownerOf(const ParticleSet& p, size_t i) const;

  std::vector<MPMMaterial>& materials_;
  std::function<void()> windowChanged_;
  InterpolatorKind interpolator_ = InterpolatorKind::Linear;
  Grid whole_;   // the problem's grid
  Grid window_;  // the nodes this rank stores
  Decomposition decomposition_;
  GhostNodes ghosts_;
  int ghostWidth_ = 0;
  bool distributed_ = false;
  int generation_ = 0;
};

// How far a CPDI domain of edge vectors `Fsize` (F times the particle's size, in cells) reaches
// from its particle along an axis: half its extent.
inline double domainReach(const Mat3& Fsize) {
  return 0.5 * Fsize.cwiseAbs().rowwise().sum().maxCoeff();
}

}  // namespace anode
