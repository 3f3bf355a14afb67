// The integrator <MPM><time_integrator> names (Integrator.h): explicit (the default) or
// implicit.
#pragma once

#include <memory>

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"
#include "Components/MPM/TimestepController.h"

namespace anode {

// Once mpm.problemSetup has read the problem (its `problemRead`): the integrator of its flags;
// `dt`, the run's controller, outlives it. Reads what the integrator checks of `root`; calls no
// collective.
std::unique_ptr<Integrator> makeIntegrator(const PSNode& root, MPM& mpm,
                                           const TimestepController& dt);

}  // namespace anode
