// The MPM component: owns the materials' particles and the grid fields and advances them one
// explicit step at a time in the paper's order (DESIGN.md §4); its diffusion subcomponent,
// ReactiveFlow, exists only with <do_scalar_diffusion>true.
#pragma once

#include <memory>
#include <vector>

#include "Components/MPM/Contact/Contact.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Components/MPM/ReactiveFlow/ReactiveFlow.h"
#include "Components/MPM/StepSummary.h"
#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/BinaryStream.h"
#include "Core/Util/Timers.h"

namespace anode {

class MPM {
 public:
  // Reads <MPM>, <PhysicalConstants>, <Grid>, <MaterialProperties> and <PhysicalBC>; the
  // simulation starts at initTime and ends at maxTime.
  void problemSetup(const PSNode& root, double initTime, double maxTime);

  // Advances the state from time t by dt (DESIGN.md §4). Throws SimulationError when a particle
  // leaves the grid, J <= 0, or a concentration leaves [min, max] beyond kConcentrationTolerance.
  void timeAdvance(double t, double dt);
  // Largest stable dt of the current state before the multiplier: paper Eq. 45, the smaller of
  // the mechanical Eq. 43 and the diffusion limits (Eq. 44 and the flux limit).
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
  const std::vector<FaceBC>& faceBCs() const { return faceBCs_; }
  // The diffusion subcomponent; null without <do_scalar_diffusion>true.
  const ReactiveFlow* diffusion() const { return diffusion_.get(); }
  size_t numParticles() const;
  TaskTimers& timers() { return timers_; }
  const TaskTimers& timers() const { return timers_; }

 private:
  // The step's tasks, in order (DESIGN.md §4).
  void computeInterpolationWeights();
  void interpolateParticlesToGrid();
  void exchangeMomentumInterpolated();
  void integrateGridMomentum(double dt);
  void setGridBoundaryConditions(double dt);
  void interpolateToParticlesAndUpdate(double dt);
  void splitParticles();
  template <class Concentration>
  void scatterMaterial(size_t m, const Concentration& concentration);
  template <class F>
  void withConcentrationScatter(size_t m, long begin, long end, F&& f);
  template <class F>
  void withConcentrationGather(size_t m, F&& f);

  MPMFlags flags_;
  Grid grid_;
  std::vector<FaceBC> faceBCs_;
  Contact contact_;
  std::vector<MPMMaterial> materials_;
  std::unique_ptr<ReactiveFlow> diffusion_;  // only with <do_scalar_diffusion>true
  int64_t nextParticleId_ = 0;
  // Nodes the particles touch this step (flat indices [begin, end)); grid loops run over them
  // only. Outside, nodal fields are zero (the previous step's range is cleared too) except the
  // values face boundary conditions set.
  struct NodeRange {
    long begin = 0, end = 0;
  } active_, previous_;

  std::vector<GridFields> fields_;              // per material
  std::vector<InterpolationWeights> weights_;   // per material, for the current step
  std::vector<std::vector<uint8_t>> capacity_;  // per material: weight entries per particle
  std::vector<GridFields> threadScatter_;       // per thread, for P2G without locks
  TaskTimers timers_;
  struct StepTasks {  // timer indices of the step's tasks
    int interpolationWeights, particlesToGrid, gridIntegration, particleUpdate, splitting,
        diffusionState;
  } tasks_{};
};

}  // namespace anode
