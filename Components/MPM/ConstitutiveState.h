// The per-particle state of a material's constitutive model (its stress-update frame, plastic
// strain, swelling strain, ...): arrays the model declares at setup (ConstitutiveModel::
// initializeState) with a ParticleField each, which the particle set then carries like its own
// arrays (checkpoints, splitting, migration, output) without knowing what they mean.
#pragma once

#include <vector>

#include "Components/MPM/ParticleField.h"
#include "Core/Math/Types.h"

namespace anode {

template <class T>
struct StateArray {
  std::vector<T> values;
  ParticleField<T> field;
};

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

}  // namespace anode
