// The MPM component: owns the materials' particles and the grid fields and advances them one
// explicit step at a time in the paper's order (DESIGN.md §4, mechanics part).
#pragma once

#include <vector>

#include "Components/MPM/Contact/Contact.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/Diffusion/ScalarFluxBC.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/BinaryStream.h"
#include "Core/Util/Timers.h"

namespace anode {

struct StepSummary {
  double kineticEnergy = 0;
  double minJ = 1, maxJ = 1;
  size_t particles = 0;
  bool diffusion = false;
  double totalLithium = 0;  // sum m c over all materials
  double minConcentration = 0, maxConcentration = 0;
};


// A concentration may leave [min, max] by this much (relative to max - min) before the run is
// stopped: round-off of the explicit update, never a clamp.
constexpr double kConcentrationTolerance = 1e-6;

class MPM {
 public:
  // Reads <MPM>, <PhysicalConstants>, <Grid>, <MaterialProperties> and <PhysicalBC>; the
  // simulation starts at initTime and ends at maxTime.
  void problemSetup(const PSNode& root, double initTime, double maxTime);

  // Advances the state from time t by dt. Throws SimulationError when a particle leaves the
  // grid, J <= 0, or a concentration leaves [min, max] beyond kConcentrationTolerance.
  void timeAdvance(double t, double dt);
  // Largest stable dt of the current state before the multiplier: paper Eq. 45, the smaller of
  // the mechanical Eq. 43 and the diffusion Eq. 44, and the flux limit of the restriction.
  double computeStableTimestep() const;
  // Interpolation weights and the grid fields of the current state (for output of g.* labels).
  void interpolateToGridForOutput();
  // Frees the interpolation weights between steps so output can use the memory; the next step
  // lays them out again.
  void releaseInterpolationWeights();
  StepSummary summarize() const;

  // The state a step starts from (every particle array and the scalars carried between steps),
  // for checkpoints (MPMState.cc). loadState expects the materials of the same input and throws
  // std::runtime_error when the saved state does not fit them.
  void saveState(BinaryWriter& out) const;
  void loadState(BinaryReader& in);

  const Grid& grid() const { return grid_; }
  const MPMFlags& flags() const { return flags_; }
  const std::vector<MPMMaterial>& materials() const { return materials_; }
  std::vector<MPMMaterial>& materials() { return materials_; }
  const std::vector<GridFields>& gridFields() const { return fields_; }
  const std::vector<ScalarFluxBC>& fluxBCs() const { return fluxBCs_; }
  size_t numParticles() const;
  TaskTimers& timers() { return timers_; }
  const TaskTimers& timers() const { return timers_; }

 private:
  // Returns, per flux BC, the number of particles it flags.
  std::vector<size_t> assignFluxBCs();
  void findDirichletNodes();
  // The step's tasks, in order (DESIGN.md §4).
  void computeInterpolationWeights();
  void applyExternalScalarFlux(double t);
  void interpolateParticlesToGrid();
  void exchangeMomentumInterpolated();
  void integrateGridMomentum(double dt);
  void integrateConcentration(double dt);
  void setGridBoundaryConditions(double dt);
  void interpolateToParticlesAndUpdate(double dt);
  void computeDiffusivity(double t);
  void checkConcentrationRange(double t) const;
  void splitParticles();
  void updateAutoCycle();

  MPMFlags flags_;
  Grid grid_;
  std::vector<FaceBC> faceBCs_;
  Contact contact_;
  std::vector<MPMMaterial> materials_;
  std::vector<ScalarFluxBC> fluxBCs_;
  bool commonDiffusionInterface_ = false;
  std::vector<std::vector<double>> dirichletMask_;  // per material, per node: 1 on Dirichlet nodes
  double maxDiffusivity_ = 0;   // over all particles, for Eq. 44
  double maxFluxRateCoefficient_ = 0;  // max unrestricted J A/V over particles, for the flux limit
  int64_t nextParticleId_ = 0;
  // Nodes the particles touch this step (flat indices [begin, end)); grid loops run over them
  // only. Outside, nodal fields are zero (the previous step's range is cleared too) except the
  // values face boundary conditions set.
  struct NodeRange {
    long begin = 0, end = 0;
  } active_, previous_;
  double fluxSign_ = 1;  // do_auto_cycle_bc: +1 lithiates, -1 delithiates

  std::vector<GridFields> fields_;                 // per material
  std::vector<InterpolationWeights> weights_;      // per material, for the current step
  std::vector<std::vector<uint8_t>> capacity_;     // per material: weight entries per particle
  std::vector<GridFields> threadScatter_;          // per thread, for P2G without locks
  TaskTimers timers_;
};

}  // namespace anode
