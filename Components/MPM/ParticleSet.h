// Particle state of one material, stored as structure-of-arrays. Every array is declared once:
// the mechanics arrays in eachArray below, the constitutive model's by the model at setup
// (declareModelArray, ConstitutiveState.h) and a subcomponent's by the subcomponent at setup
// (declareArray; the diffusion subcomponent's in ReactiveFlow/DiffusionParticles.h), each with its
// Uintah label (the name it is saved under), the physics it belongs to (it exists only when the
// material has that physics), its initial value and what particle splitting does to it.
// Checkpoints, output, splitting and setup all go through that one list, so a new array is one
// member and one line.
#pragma once

#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <variant>
#include <vector>

#include "Components/MPM/ConstitutiveState.h"
#include "Components/MPM/ParticleField.h"
#include "Core/Math/Types.h"

namespace anode {

// The displacement that is not linear over a particle's support, as the particle's hourglass
// stabilization has accumulated it over the steps (Implicit/HourglassStabilization.h), on the
// nodes of the 4 x 4 x 4 box whose lowest node is `origin`.
struct HourglassMemory {
  int32_t origin[3];
  double displacement[64][3];
};

struct ParticleSet {
  std::vector<int64_t> id;            // p.particleID, stable for the run
  std::vector<Vec3> x;                // p.x
  std::vector<Vec3> velocity;         // p.velocity
  std::vector<Vec3> displacement;     // p.displacement
  std::vector<double> mass;           // p.mass (constant)
  std::vector<double> volume;         // p.volume = mass/rho0 * det F
  std::vector<Mat3> F;                // p.deformationMeasure
  std::vector<Mat3> stress;           // p.stress (Cauchy, lab frame)
  std::vector<Mat3> size;             // p.size: reference domain edge vectors in grid-cell units
  ConstitutiveState modelState;       // the arrays the material's constitutive model declared
  DeclaredArrays subcomponentArrays;  // the arrays subcomponents declared (declareArray)
  // Particle splitting (only with <refine_particles>true): 1 once a particle or its parent split.
  std::vector<uint8_t> refined;
  // Implicit dynamics only (Implicit/Newmark.h): the acceleration of the last step's end.
  std::vector<Vec3> acceleration;
  // Implicit steps with hourglass stabilization only.
  std::vector<HourglassMemory> hourglassMemory;
  // Quasi-static steps with diffusion under <error_tolerance> only: the last step's coupling rate
  // (dc_2 - dc_1) / dt^2 of its two diffusion passes, and the sum of the particle's signed local
  // error estimates of c / c_max over the steps (Implicit/TrapezoidalCoupling.cc; saved as
  // p.concentrationErrorEstimate).
  std::vector<double> couplingRate, concentrationErrorEstimate;
  // Implicit steps with diffusion and <swelling_strain>cell_mean only: the cell-mean
  // concentration the particle's swelling has reached (NaN before its first step;
  // Implicit/CellMeanSwelling.h).
  std::vector<double> swellingConcentration;

  size_t count() const { return x.size(); }

  // Calls f(array, field) for every array, in declaration order (the one list of them).
  template <class F>
  void forEachField(F&& f) {
    eachArray(*this, f);
  }
  template <class F>
  void forEachField(F&& f) const {
    eachArray(*this, f);
  }
  // Calls f(array) for every array.
  template <class F>
  void forEachArray(F&& f) {
    forEachField([&f](auto& v, const auto&) { f(v); });
  }
  template <class F>
  void forEachArray(F&& f) const {
    forEachField([&f](const auto& v, const auto&) { f(v); });
  }

  bool has(Physics physics) const { return physics_ & bit(physics); }
  // Creates the arrays of `physics`, each holding its initial value for every particle.
  void enable(Physics physics) {
    physics_ |= bit(physics);
    const size_t n = count();
    forEachField([&](auto& v, const auto& field) {
      if (field.physics == physics) v.assign(n, field.initial);
    });
  }
  // Makes room for n particles in every array that exists; new entries get the initial value.
  void resize(size_t n) {
    forEachField([&](auto& v, const auto& field) {
      if (has(field.physics)) v.resize(n, field.initial);
    });
  }

  // Creates a constitutive-model array holding field.initial for every particle; returns its
  // index in modelState's list of its type.
  template <class T>
  size_t declareModelArray(const ParticleField<T>& field) {
    physics_ |= bit(field.physics);
    auto& list = modelArrays<T>(modelState);
    list.push_back({std::vector<T>(count(), field.initial), field});
    return list.size() - 1;
  }
  template <class T>
  std::vector<T>& modelArray(size_t index) {
    return modelArrays<T>(modelState)[index].values;
  }
  template <class T>
  const std::vector<T>& modelArray(size_t index) const {
    return modelArrays<T>(modelState)[index].values;
  }

  // Creates a subcomponent's array: field.initial for every particle if the material has its
  // physics, empty until enable() otherwise.
  template <class T>
  void declareArray(const ParticleField<T>& field) {
    subcomponentArrays.arrays.push_back(StateArray<T>{
        has(field.physics) ? std::vector<T>(count(), field.initial) : std::vector<T>(), field});
  }
  // The subcomponent's array declared with `field` (found by its label); null if none was.
  template <class T>
  std::vector<T>* findArray(const ParticleField<T>& field) {
    auto* array = find(subcomponentArrays, field.label);
    return array ? &std::get<StateArray<T>>(*array).values : nullptr;
  }
  template <class T>
  const std::vector<T>* findArray(const ParticleField<T>& field) const {
    const auto* array = find(subcomponentArrays, field.label);
    return array ? &std::get<StateArray<T>>(*array).values : nullptr;
  }

  // Appends a copy of particle i (every array that exists) and returns its index.
  size_t duplicate(size_t i) {
    forEachArray([i](auto& v) {
      if (!v.empty()) v.push_back(v[i]);
    });
    return count() - 1;
  }

 private:
  template <class T, class State>
  static auto& modelArrays(State& state) {
    if constexpr (std::is_same_v<T, Mat3>)
      return state.tensors;
    else
      return state.scalars;
  }
  template <class Arrays>
  static auto* find(Arrays& a, const char* label) {
    for (auto& array : a.arrays) {
      const char* name = DeclaredArrays::labelOf(array);
      if (name && std::strcmp(name, label) == 0) return &array;
    }
    return static_cast<decltype(&a.arrays[0])>(nullptr);
  }
  static uint16_t bit(Physics physics) {
    return static_cast<uint16_t>(1u << static_cast<int>(physics));
  }

  template <class Self, class F>
  static void eachArray(Self& s, F& f) {
    using P = Physics;
    using S = OnSplit;
    const Mat3 I = Mat3::Identity(), zero = Mat3::Zero();
    f(s.id, ParticleField<int64_t>{"p.particleID", P::Mechanics, 0, S::Own});
    f(s.x, ParticleField<Vec3>{"p.x", P::Mechanics, Vec3::Zero(), S::Own});
    f(s.velocity, ParticleField<Vec3>{"p.velocity", P::Mechanics, Vec3::Zero(), S::Copy});
    f(s.displacement, ParticleField<Vec3>{"p.displacement", P::Mechanics, Vec3::Zero(), S::Copy});
    f(s.mass, ParticleField<double>{"p.mass", P::Mechanics, 0.0, S::Quarter});
    f(s.volume, ParticleField<double>{"p.volume", P::Mechanics, 0.0, S::Quarter});
    f(s.F, ParticleField<Mat3>{"p.deformationMeasure", P::Mechanics, I, S::Copy});
    f(s.stress, ParticleField<Mat3>{"p.stress", P::Mechanics, zero, S::Copy});
    f(s.size, ParticleField<Mat3>{"p.size", P::Mechanics, I, S::Own});
    ConstitutiveState::eachArray(s.modelState, f);
    DeclaredArrays::eachArray(s.subcomponentArrays, f);
    f(s.refined, ParticleField<uint8_t>{"p.refinedMPM", P::Splitting, 0, S::Own});
    f(s.acceleration, ParticleField<Vec3>{"p.acceleration", P::Inertia, Vec3::Zero(), S::Copy});
    f(s.hourglassMemory, ParticleField<HourglassMemory>{nullptr, P::Hourglass, {}, S::Copy});
    f(s.couplingRate, ParticleField<double>{nullptr, P::CouplingHistory, 0.0, S::Copy});
    f(s.concentrationErrorEstimate,
      ParticleField<double>{"p.concentrationErrorEstimate", P::CouplingHistory, 0.0, S::Copy});
    f(s.swellingConcentration,
      ParticleField<double>{nullptr, P::CellSwelling, std::numeric_limits<double>::quiet_NaN(),
                            S::Copy});
  }

  uint16_t physics_ = bit(Physics::Mechanics);
};

}  // namespace anode
