// The classes of the core's lists that step on one input, step(x, dt), and are built from their
// Params: the forward models and the feedforwards. The allocation and fuzz tests visit them, so
// a class added to a list is checked there without a line of its own.
#pragma once

#include <tendonsheath/tendonsheath.hpp>
#include <type_traits>
#include <utility>

namespace tendonsheath::cases {

/// A compensator that steps as a feedforward (step(y_d, dt)) and is built from its Params.
template <class C, class = void>
struct feedforward_from_params : std::false_type {};
/// (see feedforward_from_params)
template <class C>
struct feedforward_from_params<
    C, std::void_t<decltype(C(std::declval<const typename C::Params&>())),
                   decltype(std::declval<C&>().step(0.0, 0.0))>> : std::true_type {};

/// Calls f(TypeTag<C>{}, name) for each forward model (root_invertible) and each feedforward
/// of the lists, in list order; name is the class's model_kind or compensator_kind.
template <class F>
void for_each_listed_stepper(F&& f) {
  for_each_type(Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    if constexpr (root_invertible<M>::value) f(tag, model_kind<M>());
  });
  for_each_type(Compensators{}, [&](auto tag) {
    using C = typename decltype(tag)::type;
    if constexpr (feedforward_from_params<C>::value) f(tag, compensator_kind<C>());
  });
}

}  // namespace tendonsheath::cases
