// The plant of a bench run, behind the one erased interface (tendonsheath/bench/erased_plant.hpp)
// that run_closed_loop steps: a shipped plant engine (a copy), a user's compiled plant (the
// capsule of tendonsheath_bind/plant.hpp) or a plant written in Python (the adapter
// tendonsheath.bench.plant_loop builds), stepped from C++ with the GIL held.
#pragma once

#include <cmath>
#include <exception>
#include <optional>
#include <string>
#include <type_traits>
#include <tendonsheath/bench/erased_plant.hpp>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;

// A plant written in Python: its members as callables (None: the default of the contract). The
// table's functions are noexcept: the first Python error is kept (the plant is then stepped no
// more) and raised by rethrow() after the loop.
struct PythonPlant {
  nb::object reset_fn, step_fn, output_fn, input_fn, reaction_fn, slack_fn, status_fn, route_fn;
  std::string name;
  std::exception_ptr error;
  double last_output = 0.0;

  double number(nb::handle value, const char* what) const {
    const double v = PyFloat_AsDouble(value.ptr());
    if (v == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw nb::type_error(("bench.run: " + name + "." + what + " returned " +
                            nb::cast<std::string>(nb::repr(value)) + ", not a number")
                               .c_str());
    }
    return v;
  }
  // f(), or `fallback` once an error is kept (the error is kept here)
  template <class F>
  std::invoke_result_t<F&> guarded(F f, std::invoke_result_t<F&> fallback) noexcept {
    if (error) return fallback;
    try {
      return f();
    } catch (...) {
      error = std::current_exception();
      return fallback;
    }
  }
  double optional_number(const nb::object& fn, const char* what, double fallback) {
    if (fn.is_none()) return fallback;
    return guarded([&] { return number(fn(), what); }, fallback);
  }
};

inline const ts::PlantTable& python_plant_table() noexcept {
  using P = PythonPlant;
  static const ts::PlantTable table{
      ts::kPlantTableVersion,
      [](void* s) noexcept {
        auto& p = *static_cast<P*>(s);
        p.guarded([&] { return (p.reset_fn(), 0); }, 0);
        p.last_output = p.optional_number(p.output_fn, "output()", 0.0);
      },
      [](void* s, double input, double dt) noexcept {
        auto& p = *static_cast<P*>(s);
        p.last_output = p.guarded([&] { return p.number(p.step_fn(input, dt), "step"); }, NAN);
        return p.last_output;
      },
      [](const void* s) noexcept { return static_cast<const P*>(s)->last_output; },
      [](const void* s) noexcept {
        auto& p = *const_cast<P*>(static_cast<const P*>(s));
        return p.optional_number(p.input_fn, "input()", 0.0);
      },
      [](const void* s) noexcept {
        auto& p = *const_cast<P*>(static_cast<const P*>(s));
        return p.optional_number(p.reaction_fn, "drive_reaction()", 0.0);
      },
      [](const void* s) noexcept {
        auto& p = *const_cast<P*>(static_cast<const P*>(s));
        if (p.slack_fn.is_none()) return false;
        return p.guarded([&] { return PyObject_IsTrue(p.slack_fn().ptr()) == 1; }, false);
      },
      [](const void* s) noexcept {
        auto& p = *const_cast<P*>(static_cast<const P*>(s));
        if (p.status_fn.is_none()) return 0u;
        return p.guarded([&] { return nb::cast<unsigned>(p.status_fn()); }, 0u);
      },
      [](const void* s) noexcept {
        return static_cast<const P*>(s)->route_fn.is_none() ? std::size_t{0} : std::size_t{1};
      },
      [](void* s, const double* row) noexcept {  // row[0]: the index of the route to set
        auto& p = *static_cast<P*>(s);
        p.guarded([&] { return (p.route_fn(static_cast<std::size_t>(row[0])), 0); }, 0);
      },
  };
  return table;
}

// The plant of one bench run, as run_closed_loop sees it (view); it owns what view points to,
// so it is built in place and never moved.
struct BenchPlant {
  std::optional<ts::PullPullPlant> pull_pull;  // a copy of a shipped engine (a ContinuumPlant
  std::optional<ts::SingleTendonPlant> single;  //   runs as the pull-pull pair it is)
  std::optional<PythonPlant> python;
  nb::object owner;  // keeps a user's capsule alive
  ts::ErasedPlantLoop view;
  bool needs_gil = false;

  BenchPlant() = default;
  BenchPlant(const BenchPlant&) = delete;
  BenchPlant& operator=(const BenchPlant&) = delete;

  explicit BenchPlant(nb::handle plant) {
    if (nb::isinstance<ts::PullPullPlant>(plant)) {
      pull_pull.emplace(nb::cast<const ts::PullPullPlant&>(plant));
      view.plant = {&ts::plant_table<ts::PullPullPlant>(), &*pull_pull};
    } else if (nb::isinstance<ts::SingleTendonPlant>(plant)) {
      single.emplace(nb::cast<const ts::SingleTendonPlant&>(plant));
      view.plant = {&ts::plant_table<ts::SingleTendonPlant>(), &*single};
    } else if (PyCapsule_CheckExact(plant.ptr())) {
      view.plant = compiled(plant);
      owner = nb::borrow(plant);
    } else {
      python.emplace(adapter(plant));
      view.plant = {&python_plant_table(), &*python};
      needs_gil = true;
    }
  }
  // A Python error a plant written in Python raised in the loop.
  void rethrow() const {
    if (python && python->error) std::rethrow_exception(python->error);
  }

 private:
  static ts::ErasedPlant compiled(nb::handle capsule) {
    if (!PyCapsule_IsValid(capsule.ptr(), ts::kPlantCapsuleName))
      throw nb::type_error(
          "bench.run: a plant's _tendonsheath_plant() must return a capsule named "
          "'tendonsheath.plant.v1' (bind the class with tendonsheath_bind/plant.hpp)");
    auto* p = static_cast<ts::ErasedPlant*>(PyCapsule_GetPointer(capsule.ptr(), ts::kPlantCapsuleName));
    if (p->table == nullptr || p->table->version != ts::kPlantTableVersion)
      throw nb::type_error("bench.run: the plant was built against another tendonsheath version "
                           "(function table version mismatch): rebuild it");
    return *p;
  }
  static nb::object member(nb::handle plant, const char* name) {
    if (!nb::hasattr(plant, name))
      throw nb::type_error(("bench.run: the plant adapter has no '" + std::string(name) + "'").c_str());
    return plant.attr(name);
  }
  static PythonPlant adapter(nb::handle plant) {
    PythonPlant p;
    p.reset_fn = member(plant, "reset");
    p.step_fn = member(plant, "step");
    p.output_fn = member(plant, "output");
    p.input_fn = member(plant, "input");
    p.reaction_fn = member(plant, "drive_reaction");
    p.slack_fn = member(plant, "slack");
    p.status_fn = member(plant, "status");
    p.route_fn = member(plant, "set_route_index");
    p.name = nb::cast<std::string>(member(plant, "name"));
    if (p.reset_fn.is_none() || p.step_fn.is_none())
      throw nb::type_error("bench.run: a plant needs reset() and step(command, dt)");
    return p;
  }
};

}  // namespace tsbind
