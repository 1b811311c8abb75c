// A plant behind a table of plain function pointers: how run_closed_loop steps any plant
// through one loop: a shipped plant (PullPullPlant, ContinuumPlant, SingleTendonPlant), a
// user's plant compiled in another shared object (bound to Python with
// tendonsheath_bind/plant.hpp), or a plant written in Python (the bindings give it a table).
// Only this table crosses a module boundary, never a C++ class layout.
//
// A plant class P meets the contract when it has
//   void reset() noexcept;                          // back to rest
//   double step(double input, double dt) noexcept;  // the pulley angle (m for a single
//                                                   // tendon) in, the output out
//   double output() const noexcept;                 // the output after the last step
// and optionally
//   double input() const noexcept;           // the input of the last step (default: 0)
//   double drive_reaction() const noexcept;  // torque of the tendons on the motor (default: 0)
//   bool slack() const noexcept;             // a tendon went slack (default: false)
//   Status status() const noexcept;          // the last step's flags (default: Status::ok)
//   std::size_t n_node_angles() const noexcept;       // route changes: the row width, and
//   void set_node_angles(const double* a) noexcept;   //   a route's node angles (default: none)
#pragma once

#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "../status.hpp"

namespace tendonsheath {

/// Layout version of PlantTable: bumped when the table's layout changes; the Python capsule's
/// name carries it too.
inline constexpr std::uint32_t kPlantTableVersion = 1;
/// Name of the Python capsule that holds an ErasedPlant.
inline constexpr const char* kPlantCapsuleName = "tendonsheath.plant.v1";

/// @brief A plant's operations as plain function pointers. Every pointer is noexcept and
/// allocates nothing (a plant written in Python aside: its table holds the GIL's caller).
struct PlantTable {
  std::uint32_t version = kPlantTableVersion;  ///< layout version (kPlantTableVersion)
  /// Resets the instance `self` to rest.
  void (*reset)(void* self) noexcept = nullptr;
  /// One sample: the output after the input (pulley angle, rad; m for a single tendon) over dt.
  double (*step)(void* self, double input, double dt) noexcept = nullptr;
  /// The output after the last step.
  double (*output)(const void* self) noexcept = nullptr;
  /// The input of the last step.
  double (*input)(const void* self) noexcept = nullptr;
  /// The tendons' torque (force for a single tendon) on the drive, along the input.
  double (*drive_reaction)(const void* self) noexcept = nullptr;
  /// Whether the last step left a tendon slack.
  bool (*slack)(const void* self) noexcept = nullptr;
  /// The last step's Status flags, as unsigned.
  unsigned (*status)(const void* self) noexcept = nullptr;
  /// The number of node angles a route change sets (0: the plant takes no route changes).
  std::size_t (*n_node_angles)(const void* self) noexcept = nullptr;
  /// Sets a route's node angles (n_node_angles() of them).
  void (*set_node_angles)(void* self, const double* angles) noexcept = nullptr;
};

/// @brief One plant instance and its table (what the Python capsule points to).
struct ErasedPlant {
  const PlantTable* table = nullptr;  ///< the instance's operations
  void* self = nullptr;               ///< the instance, owned by the module that made it
};

namespace detail {

template <class P, class = void>
struct plant_has_input : std::false_type {};
template <class P>
struct plant_has_input<P, std::void_t<decltype(std::declval<const P&>().input())>>
    : std::true_type {};

template <class P, class = void>
struct plant_has_reaction : std::false_type {};
template <class P>
struct plant_has_reaction<P, std::void_t<decltype(std::declval<const P&>().drive_reaction())>>
    : std::true_type {};

template <class P, class = void>
struct plant_has_slack : std::false_type {};
template <class P>
struct plant_has_slack<P, std::void_t<decltype(std::declval<const P&>().slack())>>
    : std::true_type {};

template <class P, class = void>
struct plant_has_status : std::false_type {};
template <class P>
struct plant_has_status<P, std::void_t<decltype(std::declval<const P&>().status())>>
    : std::true_type {};

template <class P, class = void>
struct plant_has_routes : std::false_type {};
template <class P>
struct plant_has_routes<P, std::void_t<decltype(std::declval<const P&>().n_node_angles()),
                                       decltype(std::declval<P&>().set_node_angles(
                                           static_cast<const double*>(nullptr)))>>
    : std::true_type {};

template <class P>
double erased_plant_input(const void* self) noexcept {
  if constexpr (plant_has_input<P>::value) return static_cast<const P*>(self)->input();
  return 0.0;
}

template <class P>
double erased_plant_reaction(const void* self) noexcept {
  if constexpr (plant_has_reaction<P>::value) return static_cast<const P*>(self)->drive_reaction();
  return 0.0;
}

template <class P>
bool erased_plant_slack(const void* self) noexcept {
  if constexpr (plant_has_slack<P>::value) return static_cast<const P*>(self)->slack();
  return false;
}

template <class P>
unsigned erased_plant_status(const void* self) noexcept {
  if constexpr (plant_has_status<P>::value)
    return static_cast<unsigned>(static_cast<const P*>(self)->status());
  return static_cast<unsigned>(Status::ok);
}

template <class P>
std::size_t erased_plant_width(const void* self) noexcept {
  if constexpr (plant_has_routes<P>::value) return static_cast<const P*>(self)->n_node_angles();
  return 0;
}

template <class P>
void erased_plant_set_angles(void* self, const double* a) noexcept {
  if constexpr (plant_has_routes<P>::value) static_cast<P*>(self)->set_node_angles(a);
}

}  // namespace detail

/// The table for plant class P (one static instance per P; see the file's comment).
template <class P>
const PlantTable& plant_table() noexcept {
  static_assert(noexcept(std::declval<P&>().reset()), "P::reset must be noexcept");
  static_assert(noexcept(std::declval<P&>().step(0.0, 0.0)), "P::step(input, dt) must be noexcept");
  static_assert(noexcept(std::declval<const P&>().output()), "P::output must be noexcept");
  static const PlantTable table{
      kPlantTableVersion,
      [](void* self) noexcept { static_cast<P*>(self)->reset(); },
      [](void* self, double input, double dt) noexcept {
        return static_cast<P*>(self)->step(input, dt);
      },
      [](const void* self) noexcept { return static_cast<const P*>(self)->output(); },
      &detail::erased_plant_input<P>,
      &detail::erased_plant_reaction<P>,
      &detail::erased_plant_slack<P>,
      &detail::erased_plant_status<P>,
      &detail::erased_plant_width<P>,
      &detail::erased_plant_set_angles<P>,
  };
  return table;
}

/// @brief run_closed_loop's view of an erased plant: the members it calls on a plant.
struct ErasedPlantLoop {
  ErasedPlant plant;  ///< the instance and its table
  /// Back to rest.
  void reset() noexcept { plant.table->reset(plant.self); }
  /// One sample (see PlantTable::step).
  double step(double input, double dt) noexcept { return plant.table->step(plant.self, input, dt); }
  /// The output after the last step.
  double output() const noexcept { return plant.table->output(plant.self); }
  /// The input of the last step.
  double input() const noexcept { return plant.table->input(plant.self); }
  /// The tendons' reaction on the drive.
  double drive_reaction() const noexcept { return plant.table->drive_reaction(plant.self); }
  /// Whether the last step left a tendon slack.
  bool slack() const noexcept { return plant.table->slack(plant.self); }
  /// The last step's Status flags.
  Status status() const noexcept { return static_cast<Status>(plant.table->status(plant.self)); }
  /// The number of node angles a route change sets.
  std::size_t n_node_angles() const noexcept { return plant.table->n_node_angles(plant.self); }
  /// Sets a route's node angles.
  void set_node_angles(const double* a) noexcept { plant.table->set_node_angles(plant.self, a); }
};

}  // namespace tendonsheath
