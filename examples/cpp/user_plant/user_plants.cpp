// The Python module `user_plants`: PlayPlant bound with tendonsheath_bind so that
// tendonsheath.bench.run (and `tendonsheath bench`, [plant] class = "user_plants:PlayPlant")
// steps it in the C++ closed loop, with no Python call per cycle.
#include <nanobind/nanobind.h>

#include <tendonsheath_bind/plant.hpp>

#include "play_plant.hpp"

namespace nb = nanobind;
using namespace nb::literals;

NB_MODULE(user_plants, m) {
  tendonsheath_bind::bind_plant<PlayPlant>(m, "PlayPlant")
      .def(nb::init<double>(), "half_width"_a = 0.05)
      .def("input", &PlayPlant::input)
      .def_prop_ro("kinematic_gain", [](const PlayPlant&) { return 1.0; })
      .def_prop_ro("params", [](const PlayPlant& p) {
        nb::dict d;
        d["half_width"] = p.half_width();
        return d;
      });
}
