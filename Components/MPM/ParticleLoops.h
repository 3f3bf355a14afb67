// The step's two fused particle loops (DESIGN.md §4 steps 2 and 7-8): the P2G scatter and the
// G2P update with the stress update. Each is compiled per diffusion kernel (ReactiveFlow's
// ConcentrationKernels.h; NoConcentration without diffusion) and the G2P loop per constitutive
// model type, so a loop carries only the work its material needs and calls nothing virtual.
#pragma once

#include <algorithm>

#include "Components/MPM/GridFields.h"
#include "Components/MPM/Interpolator.h"
#include "Components/MPM/ParticleSet.h"

namespace anode {

// Nodal accumulators one scatter writes into (the grid's own, or a thread's private copy).
struct MomentumScatterTarget {
  double* mass;
  Vec3* momentum;
  Vec3* force;

  static MomentumScatterTarget of(GridFields& g) {
    return {g.mass.data(), g.momentum.data(), g.internalForce.data()};
  }
};

// P2G of particles [begin, end): mass (Eq. 4), momentum, internal force f = -sum V sigma grad S,
// and the concentration kernel's quantities.
template <class Concentration>
void scatterToGrid(const ParticleSet& p, const InterpolationWeights& W, long begin, long end,
                   const MomentumScatterTarget& g, const Concentration& concentration) {
  for (long i = begin; i < end; ++i) {
    const double mp = p.mass[i];
    const Vec3 mv = mp * p.velocity[i];
    const Mat3 Vsigma = p.volume[i] * p.stress[i];
    const auto c = concentration.particle(i);
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      const int n = W.node[b + e];
      const double w = W.weight[b + e];
      const Vec3& grad = W.gradient[b + e];
      g.mass[n] += mp * w;
      g.momentum[n] += mv * w;
      g.force[n] -= Vsigma * grad;
      concentration.scatter(c, n, w, grad);
    }
  }
}

// What the G2P update of one material needs besides its particles and kernels.
struct ParticleUpdate {
  const GridFields& grid;
  const InterpolationWeights& W;
  double density;  // rho0: V = m / rho0 J
  int minimumSubcyclesForF;
  bool swells;  // the stress sees the concentration change
  double dt;
};

// G2P and the stress update of particles [0, n) (Eqs. 8, 25-39): velocity, position and F from
// the grid, volume, the concentration kernel's update, then the model's stress. Returns the
// first particle whose det F is not positive (n if none); its stress is not updated.
template <class Model, class Concentration>
long updateParticles(ParticleSet& p, const ParticleUpdate& u, const Model& model,
                     const Concentration& concentration) {
  const InterpolationWeights& W = u.W;
  const GridFields& g = u.grid;
  const bool yields = model.canYield();
  const double dt = u.dt;
  const long n = static_cast<long>(p.count());
  long firstInverted = n;
#pragma omp parallel for schedule(static) reduction(min : firstInverted)
  for (long i = 0; i < n; ++i) {
    Mat3 gradV = Mat3::Zero();
    Vec3 acc = Vec3::Zero(), vel = Vec3::Zero();
    typename Concentration::Particle c{};
    const size_t b = W.offset[i];
    for (int e = 0; e < W.count[i]; ++e) {
      const int k = W.node[b + e];
      const double w = W.weight[b + e];
      gradV.noalias() += g.velocityStar[k] * W.gradient[b + e].transpose();
      acc += g.acceleration[k] * w;
      vel += g.velocityStar[k] * w;
      concentration.gather(c, k, w, W.gradient[b + e]);
    }
    // F^{n+1} = (I + L dt/N)^N F^n, subcycled when L dt is large (Uintah's rule).
    const int cycles =
        std::min(std::max(u.minimumSubcyclesForF, 2 * static_cast<int>(gradV.norm() * dt)), 10000);
    const Mat3 increment = Mat3::Identity() + gradV * (dt / cycles);
    Mat3 F = p.F[i];
    for (int s = 0; s < cycles; ++s) F = increment * F;
    const double J = F.determinant();
    p.velocity[i] += acc * dt;
    p.x[i] += vel * dt;
    p.displacement[i] += vel * dt;
    p.volume[i] = p.mass[i] / u.density * J;
    const double dc = concentration.update(i, c, dt);
    if (!(J > 0)) {  // no stress update for an inverted particle: the caller stops the run
      firstInverted = std::min(firstInverted, i);
      p.F[i] = F;
      continue;
    }
    double ep = 0, epdot = 0;
    if (yields) {
      ep = p.plasticStrain[i];
      epdot = p.plasticStrainRate[i];
    }
    p.stress[i] = model.updateStress(p.stress[i], p.rotation[i], F, gradV, u.swells ? dc : 0.0, dt,
                                     ep, epdot);
    if (yields) {
      p.plasticStrain[i] = ep;
      p.plasticStrainRate[i] = epdot;
    }
    p.F[i] = F;
  }
  return firstInverted;
}

}  // namespace anode
