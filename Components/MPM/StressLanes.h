// What the explicit G2P (ParticleLoops.h) and the equilibrium step (Implicit/ParticleEquilibrium.h)
// share of a particle's update: the lanes of the stress update's inputs for a block of particles
// (Core/Math/Simd.h), the write-back of a lane's stress and model state, and the particle moved
// with its new F.
#pragma once

#include "Components/MPM/ParticleSet.h"
#include "Core/Math/Simd.h"

namespace anode {

// The model's inputs one lane per particle besides the step's kinematics (L or H, kept by each
// block): the stress, F, the concentration change and the model's own state (Model::State). A
// lane without a particle, or with an inverted one, holds an unstrained placeholder.
template <class Model>
struct StressLanes {
  Mat3Pack stress, F;
  Pack dc;
  typename Model::template State<Pack> state;

  void setPlaceholder(int l) {
    setLane(stress, l, Mat3::Zero());
    setLane(F, l, Mat3::Identity());
    dc[l] = 0;
    Model::StateArrays::loadUnstrained(state, l);
  }
  // Lane l from particle i: its stress and state, the F the model sees and its change of c.
  void setParticle(int l, const ParticleSet& p, long i, const Mat3& deformation, double change,
                   const typename Model::StateArrays& arrays) {
    setLane(stress, l, p.stress[i]);
    setLane(F, l, deformation);
    dc[l] = change;
    arrays.load(state, l, i);
  }
};

// Particle i's stress and model state from lane l of the update.
template <class Model>
[[gnu::always_inline]] inline void storeStress(ParticleSet& p, long i,
                                               const typename Model::StateArrays& arrays,
                                               const Mat3Pack& stress,
                                               const typename Model::template State<Pack>& state,
                                               int l) {
  p.stress[i] = lane(stress, l);
  arrays.store(state, l, i);
}

// Particle i moved by `moved` to the deformation gradient F of determinant J: its position,
// displacement, F and volume V = m / rho0 J.
[[gnu::always_inline]] inline void moveParticle(ParticleSet& p, long i, const Vec3& moved,
                                                const Mat3& F, double J, double density) {
  p.x[i] += moved;
  p.displacement[i] += moved;
  p.F[i] = F;
  p.volume[i] = p.mass[i] / density * J;
}

}  // namespace anode
