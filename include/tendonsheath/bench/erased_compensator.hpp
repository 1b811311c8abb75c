// A compensator behind a table of plain function pointers: how a compensator compiled in
// another shared object (a user's own, bound to Python with tendonsheath_bind/compensator.hpp)
// runs in run_closed_loop at C++ speed. Only this table crosses the module boundary, never a
// C++ class layout, so the two modules need not share a compiler's type information.
//
// A compensator class C meets the contract when it has
//   void reset() noexcept;
//   double step(double reference, double dt) noexcept;                    // feedforward, or
//   double step(double reference, double measured, double dt) noexcept;   // output feedback, or
//   double step(double reference, double measured, double motor, double dt) noexcept;
// and optionally  Status status() const noexcept;  bool in_fallback() const noexcept.
// `measured` is NaN during a sensor dropout; `motor` is the motor encoder's angle.
#pragma once

#include <cstdint>
#include <type_traits>
#include <utility>

#include "../status.hpp"

namespace tendonsheath {

/// Layout version of CompensatorTable: bumped when the table's layout changes; the Python
/// capsule's name carries it too.
inline constexpr std::uint32_t kCompensatorTableVersion = 1;
/// Name of the Python capsule that holds an ErasedCompensator.
inline constexpr const char* kCompensatorCapsuleName = "tendonsheath.compensator.v1";

/// @brief A compensator's operations as plain function pointers, the only thing that crosses
/// the boundary between a user's module and ours. Every pointer is noexcept and allocates
/// nothing.
struct CompensatorTable {
  std::uint32_t version = kCompensatorTableVersion;  ///< layout version (kCompensatorTableVersion)
  /// Resets the instance `self` to its initial state.
  void (*reset)(void* self) noexcept = nullptr;
  /// One cycle: the command (motor angle, rad) for the reference, the measured output (NaN
  /// during a sensor dropout), the motor encoder's angle and the time step dt (s).
  double (*command)(void* self, double reference, double measured, double motor,
                    double dt) noexcept = nullptr;
  /// The instance's Status flags of its last cycle, as unsigned.
  unsigned (*status)(const void* self) noexcept = nullptr;
  /// Whether the instance runs its fallback.
  bool (*in_fallback)(const void* self) noexcept = nullptr;
};

/// @brief One compensator instance and its table (what the Python capsule points to).
struct ErasedCompensator {
  const CompensatorTable* table = nullptr;  ///< the instance's operations
  void* self = nullptr;                     ///< the instance, owned by the module that made it
};

namespace detail {

template <class C, class = void>
struct has_feedforward_step : std::false_type {};
template <class C>
struct has_feedforward_step<C, std::void_t<decltype(std::declval<C&>().step(0.0, 0.0))>>
    : std::true_type {};

template <class C, class = void>
struct has_feedback_step : std::false_type {};
template <class C>
struct has_feedback_step<C, std::void_t<decltype(std::declval<C&>().step(0.0, 0.0, 0.0))>>
    : std::true_type {};

template <class C, class = void>
struct has_motor_step : std::false_type {};
template <class C>
struct has_motor_step<C, std::void_t<decltype(std::declval<C&>().step(0.0, 0.0, 0.0, 0.0))>>
    : std::true_type {};

template <class C, class = void>
struct reports_status : std::false_type {};
template <class C>
struct reports_status<C, std::void_t<decltype(std::declval<const C&>().status())>> : std::true_type {};

template <class C, class = void>
struct reports_fallback : std::false_type {};
template <class C>
struct reports_fallback<C, std::void_t<decltype(std::declval<const C&>().in_fallback())>>
    : std::true_type {};

}  // namespace detail

/// How many signals C's step takes before dt: 1 (reference), 2 (+ measured), 3 (+ motor).
template <class C>
constexpr int compensator_step_inputs() noexcept {
  if constexpr (detail::has_motor_step<C>::value) return 3;
  if constexpr (detail::has_feedback_step<C>::value) return 2;
  if constexpr (detail::has_feedforward_step<C>::value) return 1;
  return 0;
}

/// CompensatorTable::command for class C: calls the step C has (see the file's comment).
template <class C>
double erased_command(void* self, double reference, double measured, double motor,
                      double dt) noexcept {
  C& c = *static_cast<C*>(self);
  if constexpr (compensator_step_inputs<C>() == 3) {
    static_assert(noexcept(c.step(reference, measured, motor, dt)), "C::step must be noexcept");
    return c.step(reference, measured, motor, dt);
  } else if constexpr (compensator_step_inputs<C>() == 2) {
    static_assert(noexcept(c.step(reference, measured, dt)), "C::step must be noexcept");
    return c.step(reference, measured, dt);
  } else {
    static_assert(noexcept(c.step(reference, dt)), "C::step must be noexcept");
    return c.step(reference, dt);
  }
}

/// CompensatorTable::status for class C: C's status(), or Status::ok when C has none.
template <class C>
unsigned erased_status(const void* self) noexcept {
  if constexpr (detail::reports_status<C>::value)
    return static_cast<unsigned>(static_cast<const C*>(self)->status());
  return static_cast<unsigned>(Status::ok);
}

/// CompensatorTable::in_fallback for class C: C's in_fallback(), or false when C has none.
template <class C>
bool erased_in_fallback(const void* self) noexcept {
  if constexpr (detail::reports_fallback<C>::value)
    return static_cast<const C*>(self)->in_fallback();
  return false;
}

/// The table for class C (one static instance per C).
template <class C>
const CompensatorTable& compensator_table() noexcept {
  static_assert(compensator_step_inputs<C>() > 0,
                "a compensator needs step(reference, dt), step(reference, measured, dt) or "
                "step(reference, measured, motor, dt)");
  static_assert(noexcept(std::declval<C&>().reset()), "C::reset must be noexcept");
  static const CompensatorTable table{
      kCompensatorTableVersion,
      [](void* self) noexcept { static_cast<C*>(self)->reset(); },
      &erased_command<C>,
      &erased_status<C>,
      &erased_in_fallback<C>,
  };
  return table;
}

/// @brief run_closed_loop's view of an erased compensator (see closed_loop.hpp).
struct ErasedLoop {
  ErasedCompensator compensator;  ///< the instance and its table
  /// Resets the compensator.
  void reset() noexcept { compensator.table->reset(compensator.self); }
  /// A route shape update: an erased compensator takes none (it is told nothing).
  template <class Shape>
  void on_shape(const Shape&) noexcept {}
  /// Whether the compensator runs its fallback.
  bool in_fallback() const noexcept { return compensator.table->in_fallback(compensator.self); }
  /// The compensator's Status flags of its last cycle.
  Status status() const noexcept {
    return static_cast<Status>(compensator.table->status(compensator.self));
  }
  /// One cycle's command (see CompensatorTable::command).
  double command(double y_d, double measured, double motor, double dt) noexcept {
    return compensator.table->command(compensator.self, y_d, measured, motor, dt);
  }
};

}  // namespace tendonsheath
