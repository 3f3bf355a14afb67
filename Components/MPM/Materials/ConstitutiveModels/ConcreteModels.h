// Every constitutive model type the particle update is compiled for: the one list of them. A new
// model is its class (ConstitutiveModel's interface plus a State, eachStateField, StateArrays and
// an updateStress of RFElasticPlastic's form), one include and one entry here, and one branch in
// createConstitutiveModel.
#pragma once

#include <type_traits>
#include <utility>
#include <variant>

#include "Components/MPM/Materials/ConstitutiveModels/CompNeoHookean.h"
#include "Components/MPM/Materials/ConstitutiveModels/RFElasticPlastic.h"

namespace anode {

struct ConcreteModel {
  using Types = std::variant<const RFElasticPlastic*, const CompNeoHookean*>;
  Types model;
};

namespace detail {
template <class F, size_t... k>
void eachModelStateField(F& f, std::index_sequence<k...>) {
  using Types = ConcreteModel::Types;
  (std::remove_const_t<std::remove_pointer_t<std::variant_alternative_t<k, Types>>>::eachStateField(
       f),
   ...);
}
}  // namespace detail

// Calls f(field) for every per-particle array any model may declare (for the output labels).
template <class F>
void forEachModelStateField(F&& f) {
  detail::eachModelStateField(
      f, std::make_index_sequence<std::variant_size_v<ConcreteModel::Types>>{});
}

}  // namespace anode
