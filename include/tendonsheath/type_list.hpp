// A compile-time list of types and the few operations the core's registries need: visit each
// type (for_each_type), stop at the first that answers (any_type), make a std::variant (or any
// template) of them (apply_list), keep those a trait accepts (filter_list). C++17, no
// allocation, nothing at run time beyond the calls made for each type.
#pragma once

#include <cstddef>
#include <type_traits>

namespace tendonsheath {

/// A list of types, e.g. TypeList<Backlash, BoucWen>.
template <class... Ts>
struct TypeList {
  static constexpr std::size_t size = sizeof...(Ts);  ///< how many types
};

/// A value standing for type T (what for_each_type hands its function).
template <class T>
struct TypeTag {
  using type = T;  ///< the type
};

/// Two lists joined (what builds a list one entry at a time: TypeList<>{} + TypeList<A>{} + ...).
template <class... As, class... Bs>
constexpr TypeList<As..., Bs...> operator+(TypeList<As...>, TypeList<Bs...>) {
  return {};
}

/// Calls f(TypeTag<T>{}) for each type T of the list, in order.
template <class... Ts, class F>
constexpr void for_each_type(TypeList<Ts...>, F&& f) {
  (f(TypeTag<Ts>{}), ...);
}

/// Calls f(TypeTag<T>{}) for each type T of the list, in order, until one returns true.
/// @return whether one did
template <class... Ts, class F>
constexpr bool any_type(TypeList<Ts...>, F&& f) {
  return (f(TypeTag<Ts>{}) || ...);
}

/// To<Ts...> of the list's types (e.g. a std::variant of them): apply_list_t<L, std::variant>.
template <class L, template <class...> class To>
struct apply_list;
/// (see apply_list)
template <class... Ts, template <class...> class To>
struct apply_list<TypeList<Ts...>, To> {
  using type = To<Ts...>;  ///< To<Ts...>
};
/// To<Ts...> of list L's types.
template <class L, template <class...> class To>
using apply_list_t = typename apply_list<L, To>::type;

/// The types T of list L for which Keep<T>::value holds, in order.
template <class L, template <class> class Keep>
struct filter_list;
/// (see filter_list)
template <class... Ts, template <class> class Keep>
struct filter_list<TypeList<Ts...>, Keep> {
  /// the kept types, a TypeList
  using type = decltype((TypeList<>{} + ... +
                         std::conditional_t<Keep<Ts>::value, TypeList<Ts>, TypeList<>>{}));
};
/// The types of L that Keep accepts.
template <class L, template <class> class Keep>
using filter_list_t = typename filter_list<L, Keep>::type;

/// Whether T is one of list L's types.
template <class L, class T>
struct list_contains;
/// (see list_contains)
template <class... Ts, class T>
struct list_contains<TypeList<Ts...>, T> : std::disjunction<std::is_same<Ts, T>...> {};
/// Whether T is one of list L's types.
template <class L, class T>
inline constexpr bool list_contains_v = list_contains<L, T>::value;

}  // namespace tendonsheath
