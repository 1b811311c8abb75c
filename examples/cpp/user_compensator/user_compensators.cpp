// The Python module `user_compensators`: PIFeedforward bound with tendonsheath_bind so that
// tendonsheath.bench.run (and `tendonsheath bench`, class = "user_compensators:PIFeedforward")
// runs it in the C++ closed loop, with no Python call per cycle.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include <tendonsheath_bind/compensator.hpp>

#include "pi_feedforward.hpp"

namespace nb = nanobind;
using namespace nb::literals;

NB_MODULE(user_compensators, m) {
  tendonsheath_bind::bind_compensator<PIFeedforward>(m, "PIFeedforward")
      .def(nb::init<double, double, double, double>(), "gain"_a = 1.0, "kp"_a = 0.5,
           "ki"_a = 5.0, "integral_limit"_a = 0.2)
      .def_prop_ro("params", [](const PIFeedforward& c) {
        nb::dict d;
        d["gain"] = c.gain();
        d["kp"] = c.kp();
        d["ki"] = c.ki();
        d["integral_limit"] = c.integral_limit();
        return d;
      });
}
