// What the one list of particle arrays (ParticleSet::eachArray) says about each array.
#pragma once

#include <cstdint>

namespace anode {

// The physics a particle array belongs to: the array exists (one entry per particle) only when
// the material has that physics, and is empty otherwise.
enum class Physics : uint8_t {
  Mechanics,        // always
  Plasticity,       // a constitutive model that can yield
  Diffusion,        // <do_scalar_diffusion>true
  FluxBC,           // a material that diffuses, with <scalar_flux> blocks
  Splitting,        // <refine_particles>true for this material
  Inertia,          // implicit dynamics (<dynamic>true): the particles' acceleration
  Hourglass,        // implicit steps with <hourglass_stabilization> above 0: its memory
  CouplingHistory,  // quasi-static steps with diffusion under <error_tolerance>: the last step's
                    // coupling rate, the error estimate's history
  CellSwelling,     // implicit steps with diffusion and <swelling_strain>cell_mean: the
                    // concentration each particle's swelling has reached
  StressDrivenDiffusion,  // a <diffusion_model type="chemical_potential">: grad of the stress's
                          // part of the chemical potential
};

// What splitting a particle in four (ParticleSplitting.cc) does to an array: the children copy
// the parent's value, take a quarter of it each, or get values of their own there.
enum class OnSplit : uint8_t { Copy, Quarter, Own };

template <class T>
struct ParticleField {
  const char* label;  // the Uintah label it is saved under; nullptr: never saved
  Physics physics;
  T initial;  // before setup sets what the input gives
  OnSplit split;
};

}  // namespace anode
