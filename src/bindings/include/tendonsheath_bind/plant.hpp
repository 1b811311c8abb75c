// Bind a user's own C++ plant into a Python module that tendonsheath.bench.run steps in its C++
// closed loop (no Python call per cycle), as tendonsheath_bind/compensator.hpp does for a
// compensator.
//
// What crosses from the user's module into tendonsheath's is the plain function table of
// tendonsheath/bench/erased_plant.hpp (see there for the contract a class must meet: reset(),
// step(input, dt) and output(), all noexcept, and optional input(), drive_reaction(), slack(),
// status(), n_node_angles()/set_node_angles()).
//
//   NB_MODULE(my_plants, m) {
//     tendonsheath_bind::bind_plant<MyPlant>(m, "MyPlant")
//         .def(nb::init<double>(), "half_width"_a);
//   }
//
// The Python class meets tendonsheath.protocols.Plant: reset(), step(command, dt), output(),
// simulate(t, command) (a tendonsheath.SimulationResult from rest, on a copy), params (an
// empty dict: define your own after this call to replace it), and
// _tendonsheath_plant(): a capsule holding a copy of the instance for the C++ loop. The class
// takes attributes (nb::dynamic_attr), so a motor or sensor can be given to it in Python
// (plant.motor = tendonsheath.Motor.position(...)): bench.run runs the motor between the
// command and step, and reads the output with the sensor.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>

#include <tendonsheath/bench/erased_plant.hpp>

namespace tendonsheath_bind {

namespace nb = nanobind;

namespace detail {

// A copy of the instance and its table; the capsule owns it.
template <class P>
struct OwnedPlant : tendonsheath::ErasedPlant {
  P copy;
  explicit OwnedPlant(const P& p) : copy(p) {
    table = &tendonsheath::plant_table<P>();
    self = &copy;
  }
  OwnedPlant(const OwnedPlant&) = delete;
  OwnedPlant& operator=(const OwnedPlant&) = delete;
};

inline double checked_plant_dt(double dt) {
  if (!(std::isfinite(dt) && dt >= 0.0))
    throw nb::value_error(("dt must be finite and >= 0 (got " + std::to_string(dt) + ")").c_str());
  return dt;
}

using PlantSamples = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

// simulate(t, command): a copy stepped from rest over the samples, as a SimulationResult.
template <class P>
nb::object simulate_copy(const P& plant, PlantSamples t, PlantSamples command) {
  const std::size_t n = command.shape(0);
  if (t.shape(0) != n)
    throw nb::value_error("simulate: t and command differ in length");
  P copy(plant);
  copy.reset();
  auto* out = new double[n > 0 ? n : 1];
  nb::capsule owner(out, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  for (std::size_t k = 0; k < n; ++k) {
    const double dt = k == 0 ? 0.0 : t.data()[k] - t.data()[k - 1];
    out[k] = copy.step(command.data()[k], checked_plant_dt(dt));
  }
  nb::ndarray<nb::numpy, double, nb::ndim<1>> q(out, {n}, owner);
  nb::object result = nb::module_::import_("tendonsheath.simulation_result").attr("SimulationResult");
  return result(q, nb::arg("t") = t, nb::arg("input") = command, nb::arg("command") = command);
}

}  // namespace detail

// Binds P as the Python class `name` in `scope`; add its constructor (and anything else) to the
// class_ returned.
template <class P>
nb::class_<P> bind_plant(nb::handle scope, const char* name) {
  using namespace nb::literals;
  static_assert(std::is_copy_constructible_v<P>, "bench.run steps a copy: P must be copyable");
  nb::class_<P> cls(scope, name, nb::dynamic_attr());
  cls.def("reset", [](P& p) { p.reset(); }, "Back to rest.");
  cls.def("step",
          [](P& p, double command, double dt) { return p.step(command, detail::checked_plant_dt(dt)); },
          "command"_a, "dt"_a = 0.0, "One sample: the output after the command over dt (s).");
  cls.def("output", [](const P& p) { return p.output(); }, "The output after the last step.");
  cls.def("simulate", &detail::simulate_copy<P>, "t"_a, "command"_a,
          "A whole record from rest (on a copy: the streaming state is left alone).");
  cls.def_prop_ro("params", [](const P&) { return nb::dict(); },
                  "The plant's settings (none declared: bind your own params).");
  cls.def(
      "_tendonsheath_plant",
      [](const P& p) {
        auto* owned = new detail::OwnedPlant<P>(p);
        return nb::capsule(static_cast<tendonsheath::ErasedPlant*>(owned),
                           tendonsheath::kPlantCapsuleName, [](void* q) noexcept {
                             delete static_cast<detail::OwnedPlant<P>*>(
                                 static_cast<tendonsheath::ErasedPlant*>(q));
                           });
      },
      "A copy of this plant for tendonsheath.bench.run's C++ loop.");
  return cls;
}

}  // namespace tendonsheath_bind
