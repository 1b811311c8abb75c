// Hysteresis models: parameter structs, streaming step() and batch simulate().
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "model_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

void bind_models(nb::module_& m) {
  nb::class_<ts::BacklashParams>(m, "BacklashParams")
      .def(nb::init<>())
      .def_rw("c_r", &ts::BacklashParams::c_r)
      .def_rw("c_l", &ts::BacklashParams::c_l)
      .def_rw("B_r", &ts::BacklashParams::B_r)
      .def_rw("B_l", &ts::BacklashParams::B_l);
  bind_model<ts::Backlash>(m, "Backlash").def("set_state", &ts::Backlash::set_state, "x"_a, "y"_a);

  using BWB = ts::BoucWenBacklashParams;
  nb::class_<BWB>(m, "BoucWenBacklashParams")
      .def(nb::init<>())
      .def_rw("c_r", &BWB::c_r)
      .def_rw("c_l", &BWB::c_l)
      .def_rw("B_r", &BWB::B_r)
      .def_rw("B_l", &BWB::B_l)
      .def_rw("rho", &BWB::rho)
      .def_rw("sigma", &BWB::sigma)
      .def_rw("n", &BWB::n)
      .def_rw("max_step", &BWB::max_step)
      .def_rw("max_substeps", &BWB::max_substeps);
  bind_model<ts::BoucWenBacklash>(m, "BoucWenBacklash")
      .def("state", &ts::BoucWenBacklash::state)
      .def("set_state", &ts::BoucWenBacklash::set_state, "x"_a, "w"_a);

  using BW = ts::BoucWenParams;
  nb::class_<BW>(m, "BoucWenParams")
      .def(nb::init<>())
      .def_rw("A", &BW::A)
      .def_rw("beta", &BW::beta)
      .def_rw("gamma", &BW::gamma)
      .def_rw("n", &BW::n)
      .def_rw("a", &BW::a)
      .def_rw("k", &BW::k)
      .def_rw("max_step", &BW::max_step)
      .def_rw("max_substeps", &BW::max_substeps);
  bind_model<ts::BoucWen>(m, "BoucWen")
      .def("state", &ts::BoucWen::state)
      .def("z_ultimate", &ts::BoucWen::z_ultimate);

  using HO = ts::HystereticOscillatorParams;
  nb::class_<HO>(m, "HystereticOscillatorParams")
      .def(nb::init<>())
      .def_rw("m", &HO::m)
      .def_rw("c", &HO::c)
      .def_rw("k", &HO::k)
      .def_rw("alpha", &HO::alpha)
      .def_rw("beta", &HO::beta)
      .def_rw("gamma", &HO::gamma)
      .def_rw("delta", &HO::delta)
      .def_rw("nu", &HO::nu)
      .def_rw("substeps", &HO::substeps)
      .def_rw("max_substeps", &HO::max_substeps)
      .def_rw("hold_input", &HO::hold_input);
  bind_model<ts::HystereticOscillator>(m, "HystereticOscillator")
      .def("velocity", &ts::HystereticOscillator::velocity)
      .def("hysteretic_force", &ts::HystereticOscillator::hysteretic_force);

  using PI = ts::PrandtlIshlinskiiParams;
  nb::class_<PI>(m, "PrandtlIshlinskiiParams")
      .def(nb::init<>())
      .def_rw("thresholds", &PI::thresholds)
      .def_rw("weights", &PI::weights);
  bind_model<ts::PrandtlIshlinskii>(m, "PrandtlIshlinskii")
      .def("play_states", &ts::PrandtlIshlinskii::play_states);
  bind_model<ts::PrandtlIshlinskiiInverse>(m, "PrandtlIshlinskiiInverse");
}

}  // namespace tsbind
