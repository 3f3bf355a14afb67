// A time integrator of MPM: one step of the state MPM holds, as its own list of MPM's tasks in
// order (ExplicitStep.h, Implicit/ImplicitStep.h), chosen once at setup by <time_integrator>
// (IntegratorFactory.h). docs/extending.md, "A new integrator", says what a new one takes.
#pragma once

#include <string>

#include "Components/MPM/StableTimestep.h"
#include "Core/Parallel/Communicator.h"

namespace anode {

// What a step took: its dt, and the dt the next step's limits grow from (<max_delt_increase>,
// ImpMPM's rule): an implicit step retaken with a smaller dt grows from that.
struct StepTaken {
  double dt = 0, ruleDt = 0;
};

// The last step's solver counts for history.csv; -1 where the integrator has none.
struct StepCounts {
  int newtonIterations = -1, krylovIterations = -1;
  // <concentration_coupling>trapezoidal: the lithium by which the step's two diffusion passes
  // differ (ImplicitStep::NewtonCounts::lastCouplingCorrection).
  double couplingCorrection = -1;
  // With <error_tolerance>: the step's error estimate (ImplicitStep::NewtonCounts::
  // lastErrorEstimate), the particles' largest sum of their estimates up to it
  // (accumulatedErrorEstimate) and the attempts rejected (retaken with a smaller dt) before it.
  double errorEstimate = -1, accumulatedErrorEstimate = -1;
  int rejectedAttempts = -1;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  // The limits on the next step's dt from the state after the last step (StableTimestep.h).
  virtual StableTimestep stableTimestep(Collective) const = 0;
  // Advances the state from time t by dt; ruleDt is the dt the limits chose, of which dt may be
  // a part (<clamp_time_to_output> shortens a step to end on an output time). Throws
  // SimulationError on every rank together when the step cannot be taken.
  virtual StepTaken advance(Collective, double t, double dt, double ruleDt) = 0;
  // The progress line's note on the last step, whose dt `limit` set.
  virtual std::string describeLastStep(StableTimestep::Limit limit) const = 0;
  virtual StepCounts lastStepCounts() const { return {}; }
  // The end summary's line on the solver over `steps` steps; empty when there is none.
  virtual std::string summary(long /*steps*/) const { return {}; }
};

}  // namespace anode
