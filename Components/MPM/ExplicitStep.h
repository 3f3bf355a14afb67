// The explicit step (DESIGN.md §4): MPM's tasks in the paper's order, dt bounded by the stable
// time step (Eq. 45).
#pragma once

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"

namespace anode {

class ExplicitStep : public Integrator {
 public:
  explicit ExplicitStep(MPM& mpm);
  // Eq. 45: the smallest of Eqs. 43 and 44 and the flux limit.
  StableTimestep stableTimestep(Collective) const override;
  // Throws SimulationError when a particle leaves the grid, J <= 0, or a concentration leaves
  // [min, max] beyond kConcentrationTolerance (in a distributed run on every rank together:
  // Core/Parallel/StopTogether.h).
  StepTaken advance(Collective, double t, double dt, double ruleDt) override;
  std::string describeLastStep(StableTimestep::Limit limit) const override {
    return StableTimestep::name(limit);
  }

 private:
  MPM& mpm_;
  struct Tasks {  // timer indices
    int interpolationWeights, particlesToGrid, gridIntegration, particleUpdate, splitting,
        diffusionState, communication;
  } tasks_;
};

}  // namespace anode
