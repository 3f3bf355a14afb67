// The integrator <MPM><time_integrator> names (Integrator.h): explicit (the default) or
// implicit.
#pragma once

#include <memory>

#include "Components/MPM/Integrator.h"
#include "Components/MPM/MPM.h"

namespace anode {

// Once mpm.problemSetup has read the problem (its `problemRead`): the integrator of its flags.
// `multiplier`: <timestep_multiplier> (an implicit step's diffusion sub-steps take it); `dtMin`:
// <delt_min>. Reads what the integrator checks of `root`; calls no collective.
std::unique_ptr<Integrator> makeIntegrator(const PSNode& root, MPM& mpm, double multiplier,
                                           double dtMin);

}  // namespace anode
