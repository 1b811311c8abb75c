// Bind a user's own C++ compensator into a Python module that tendonsheath.bench.run runs in
// its C++ closed loop (no Python call per cycle).
//
// This header needs nanobind, so it lives beside the bindings (src/bindings/include), not in
// the real-time tree include/tendonsheath/: the compensator class itself includes only the core,
// and what crosses from the user's module into tendonsheath's is the plain function table of
// tendonsheath/bench/erased_compensator.hpp (see there for the contract a class must meet).
//
//   NB_MODULE(my_compensators, m) {
//     tendonsheath_bind::bind_compensator<MyCompensator>(m, "MyCompensator")
//         .def(nb::init<double, double>(), "gain"_a, "kp"_a);
//   }
//
// The Python class gets reset(), step(...) (the same signals as the C++ step, then dt),
// step_inputs and control_output (what bench.run reads to feed and check it), and
// _tendonsheath_compensator(): a capsule holding a copy of the instance for the C++ loop.
#pragma once

#include <nanobind/nanobind.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include <tendonsheath/bench/erased_compensator.hpp>

namespace tendonsheath_bind {

namespace nb = nanobind;

namespace detail {

// A copy of the instance and its table; the capsule owns it.
template <class C>
struct Owned : tendonsheath::ErasedCompensator {
  C copy;
  explicit Owned(const C& c) : copy(c) {
    table = &tendonsheath::compensator_table<C>();
    self = &copy;
  }
  Owned(const Owned&) = delete;
  Owned& operator=(const Owned&) = delete;
};

inline double checked_dt(double dt) {
  if (!(std::isfinite(dt) && dt >= 0.0))
    throw nb::value_error(("dt must be finite and >= 0 (got " + std::to_string(dt) + ")").c_str());
  return dt;
}

template <class C>
void def_step(nb::class_<C>& cls) {
  using namespace nb::literals;
  constexpr int n = tendonsheath::compensator_step_inputs<C>();
  if constexpr (n == 1) {
    cls.def("step", [](C& c, double r, double dt) { return c.step(r, checked_dt(dt)); },
            "y_d"_a, "dt"_a, "One control cycle: the command for the desired output y_d.");
    cls.attr("step_inputs") = nb::make_tuple("y_d");
  } else if constexpr (n == 2) {
    cls.def("step",
            [](C& c, double r, double y, double dt) { return c.step(r, y, checked_dt(dt)); },
            "y_d"_a, "y"_a, "dt"_a, "One control cycle from y_d and the measured output y.");
    cls.attr("step_inputs") = nb::make_tuple("y_d", "y");
  } else {
    cls.def("step",
            [](C& c, double r, double y, double q, double dt) {
              return c.step(r, y, q, checked_dt(dt));
            },
            "y_d"_a, "y"_a, "q"_a, "dt"_a,
            "One control cycle from y_d, the measured output y and the motor angle q.");
    cls.attr("step_inputs") = nb::make_tuple("y_d", "y", "q");
  }
}

}  // namespace detail

// Binds C as the Python class `name` in `scope`; add its constructor (and anything else) to
// the class_ returned. `control_output` is "x" for a motor angle command, "torque" for a torque.
template <class C>
nb::class_<C> bind_compensator(nb::handle scope, const char* name,
                               const char* control_output = "x") {
  static_assert(std::is_copy_constructible_v<C>, "bench.run runs a copy: C must be copyable");
  const std::string output = control_output;
  if (output != "x" && output != "torque")
    throw std::invalid_argument("bind_compensator: control_output must be \"x\" or \"torque\"");
  nb::class_<C> cls(scope, name);
  cls.def("reset", [](C& c) { c.reset(); }, "Forget the streaming state.");
  detail::def_step(cls);
  cls.attr("control_output") = nb::str(control_output);
  cls.def(
      "_tendonsheath_compensator",
      [](const C& c) {
        auto* owned = new detail::Owned<C>(c);
        return nb::capsule(static_cast<tendonsheath::ErasedCompensator*>(owned),
                           tendonsheath::kCompensatorCapsuleName, [](void* p) noexcept {
                             delete static_cast<detail::Owned<C>*>(
                                 static_cast<tendonsheath::ErasedCompensator*>(p));
                           });
      },
      "A copy of this compensator for tendonsheath.bench.run's C++ loop.");
  return cls;
}

}  // namespace tendonsheath_bind
