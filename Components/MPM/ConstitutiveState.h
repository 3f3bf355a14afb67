// Particle arrays that others declare at setup with a ParticleField each, which the particle set
// then carries like its own arrays (checkpoints, splitting, migration, output) without knowing
// what they mean: the constitutive model's state and a subcomponent's arrays.
#pragma once

#include <variant>
#include <vector>

#include "Components/MPM/ParticleField.h"
#include "Core/Math/Types.h"

namespace anode {

template <class T>
struct StateArray {
  std::vector<T> values;
  ParticleField<T> field;
};

// The per-particle state of a material's constitutive model (its stress-update frame, plastic
// strain, swelling strain, ...), declared by ConstitutiveModel::initializeState.
struct ConstitutiveState {
  // In declaration order, tensors before scalars (the order of checkpoints and splitting).
  std::vector<StateArray<Mat3>> tensors;
  std::vector<StateArray<double>> scalars;

  // Calls f(values, field) for every array declared.
  template <class Self, class F>
  static void eachArray(Self& s, F& f) {
    for (auto& a : s.tensors) f(a.values, a.field);
    for (auto& a : s.scalars) f(a.values, a.field);
  }
};

// The per-particle arrays of a subcomponent (the diffusion subcomponent's concentration, flux
// faces, ...), declared at setup with a ParticleField each (ParticleSet::declareArray) and carried
// like the particle set's own arrays, in declaration order, without its knowing what they mean.
struct DeclaredArrays {
  using Array = std::variant<StateArray<double>, StateArray<Vec3>, StateArray<Vec3i>>;
  std::vector<Array> arrays;

  // Calls f(values, field) for every array declared, in declaration order.
  template <class Self, class F>
  static void eachArray(Self& s, F& f) {
    for (auto& a : s.arrays) std::visit([&f](auto& array) { f(array.values, array.field); }, a);
  }
  static const char* labelOf(const Array& a) {
    return std::visit([](const auto& array) { return array.field.label; }, a);
  }
};

}  // namespace anode
