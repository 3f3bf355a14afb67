#include "Components/MPM/IntegratorFactory.h"

#include "Components/MPM/ExplicitStep.h"
#include "Components/MPM/Implicit/ImplicitStep.h"

namespace anode {

std::unique_ptr<Integrator> makeIntegrator(const PSNode& root, MPM& mpm,
                                           const TimestepController& dt) {
  if (mpm.problem().flags.implicit) return std::make_unique<ImplicitStep>(root, mpm, dt);
  return std::make_unique<ExplicitStep>(mpm);
}

}  // namespace anode
