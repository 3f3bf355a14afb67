#include "Components/MPM/ExplicitStep.h"

#include <algorithm>
#include <cmath>

#include "Core/Parallel/StopTogether.h"

namespace anode {

ExplicitStep::ExplicitStep(MPM& mpm) : mpm_(mpm) {
  TaskTimers& timers = mpm.timers();
  tasks_ = {timers.task("computeInterpolationWeights"),
            timers.task("interpolateParticlesToGrid"),
            timers.task("integrateGrid"),
            timers.task("interpolateToParticlesAndUpdate"),
            timers.task("splitParticles"),
            timers.task("updateDiffusionState"),
            mpm.layout().distributed() ? timers.task("communication") : -1};
}

StableTimestep ExplicitStep::stableTimestep(Collective every) const {
  const Grid& grid = mpm_.grid();
  const ReactiveFlow* diffusion = mpm_.diffusion();
  StableTimestep limits;
  double& dt = limits.bound[StableTimestep::Mechanics];
  for (const MPMMaterial& mat : mpm_.materials()) {
    const ParticleSet& p = mat.particles;
    const double modulus = mat.model->dilatationalModulus();
    const long n = static_cast<long>(p.count());
    double wx = 0, wy = 0, wz = 0;
#pragma omp parallel for schedule(static) reduction(max : wx, wy, wz)
    for (long i = 0; i < n; ++i) {
      const double c = std::sqrt(modulus * p.volume[i] / p.mass[i]);  // Eq. 41 with rho = m/V
      wx = std::max(wx, c + std::abs(p.velocity[i].x()));
      wy = std::max(wy, c + std::abs(p.velocity[i].y()));
      wz = std::max(wz, c + std::abs(p.velocity[i].z()));
    }
    dt = std::min({dt, grid.dx.x() / wx, grid.dx.y() / wy, grid.dx.z() / wz});  // Eq. 43
  }
  if (diffusion) diffusion->boundTimestep(every, grid, mpm_.materials(), limits);
  collective::minimum(every, limits.bound.data(), 2);  // Eqs. 43 and 44 over ranks
  return limits;
}

StepTaken ExplicitStep::advance(Collective every, double t, double dt, double) {
  // The tasks in order (docs/diffusion.md lists the diffusion part of each). DESIGN.md §4 has the
  // same ones but computes D and the flux rate at the start of a step: here task 10 computes
  // them for the new state, which its output and its time step (Eq. 44) need as well. In a
  // distributed run the ranks meet where they agree on the nodes some rank's particles reach (1),
  // where P2G's sums are completed on the shared nodes (2), where particles move to the rank
  // owning their cell (11), and where a problem found on one rank stops them all (stopTogether).
  TaskTimers& timers = mpm_.timers();
  ReactiveFlow* diffusion = mpm_.diffusion();
  {
    ScopedTimer s(timers, tasks_.interpolationWeights);
    mpm_.computeWeightsAndActiveNodes(every);  // 1: S_ip, grad S_ip (CPDI: F size)
  }
  mpm_.interpolateParticlesToGrid(every);  // 2: P2G, Eqs. 4-5, 7, 18, and its sums over the ranks
  {
    ScopedTimer s(timers, tasks_.particlesToGrid);
    mpm_.computeNodalVelocityAndConcentration();  // 2: nodal velocity and concentration (Eq. 5)
  }
  {
    ScopedTimer s(timers, tasks_.gridIntegration);
    mpm_.exchangeMomentumInterpolated();             // 3: contact on the interpolated velocity
    mpm_.integrateGridMomentum(dt);                  // 4: a = f/m + g, v* = v + a dt
    if (diffusion) mpm_.integrateConcentration(dt);  // 5: c* and the nodal rate (Eq. 18)
    mpm_.setGridBoundaryConditions(dt);              // 6: contact, velocity BCs, acceleration
  }
  {
    ScopedTimer s(timers, tasks_.particleUpdate);
    // 7-8: G2P (Eq. 8), F, stress
    collective::stopTogether(every, [&] { mpm_.interpolateToParticlesAndUpdate(dt); });
  }
  if (mpm_.problem().flags.refineParticles) {
    ScopedTimer s(timers, tasks_.splitting);
    mpm_.splitParticles(every);  // 9: particles stretched beyond the ratio split in four
  }
  if (diffusion) {
    // 10: the range check of c, then D (Eqs. 23-24) and the flux rates (Eqs. 16-17) at t + dt
    ScopedTimer s(timers, tasks_.diffusionState);
    diffusion->updateDiffusionState(every, mpm_.materials(), t + dt);
  }
  if (mpm_.layout().distributed()) {
    ScopedTimer s(timers, tasks_.communication);
    mpm_.migrateParticles(every);  // 11: particles that left the rank's box go to its owner
  }
  return {dt, dt};
}

}  // namespace anode
