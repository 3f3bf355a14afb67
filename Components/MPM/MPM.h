// The MPM component: owns the materials' particles and the grid fields and advances them one
// explicit step at a time in the paper's order (DESIGN.md §4, mechanics part).
#pragma once

#include <vector>

#include "Components/MPM/Contact/Contact.h"
#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/MPMFlags.h"
#include "Components/MPM/Materials/MPMMaterial.h"
#include "Core/Grid/BoundaryConditions.h"
#include "Core/Grid/Grid.h"
#include "Core/Util/Timers.h"

namespace anode {

struct StepSummary {
  double kineticEnergy = 0;
  double minJ = 1, maxJ = 1;
  size_t particles = 0;
};

class MPM {
 public:
  // Reads <MPM>, <PhysicalConstants>, <Grid>, <MaterialProperties> and <PhysicalBC>.
  void problemSetup(const PSNode& root);

  // Advances the state by dt. Throws SimulationError when a particle leaves the grid or J <= 0.
  void timeAdvance(double dt);
  // Largest stable dt of the current state (paper Eq. 43), before the multiplier.
  double computeStableTimestep() const;
  // Interpolation weights and the grid fields of the current state (for output of g.* labels).
  void interpolateToGridForOutput();
  StepSummary summarize() const;

  const Grid& grid() const { return grid_; }
  const MPMFlags& flags() const { return flags_; }
  const std::vector<MPMMaterial>& materials() const { return materials_; }
  std::vector<MPMMaterial>& materials() { return materials_; }
  const std::vector<GridFields>& gridFields() const { return fields_; }
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
  void computeStressTensor(double dt);

  MPMFlags flags_;
  Grid grid_;
  std::vector<FaceBC> faceBCs_;
  Contact contact_;
  std::vector<MPMMaterial> materials_;

  std::vector<GridFields> fields_;                 // per material
  std::vector<InterpolationWeights> weights_;      // per material, for the current step
  std::vector<std::vector<Mat3>> velocityGradient_;  // per material scratch: L of the step
  std::vector<std::vector<Mat3>> newF_;              // per material scratch: F at the step's end
  std::vector<GridFields> threadScatter_;          // per thread, for P2G without locks
  TaskTimers timers_;
};

}  // namespace anode
