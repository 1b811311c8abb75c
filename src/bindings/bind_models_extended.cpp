// Models for real loops: static polynomial output map and the generalized
// Prandtl-Ishlinskii model with its inverse.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"
#include "model_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

void bind_models_extended(nb::module_& m) {
  bind_params<ts::PolynomialParams>(m, "PolynomialParams");
  bind_model<ts::Polynomial>(m, "Polynomial");

  nb::class_<ts::Envelope>(m, "Envelope")
      .def(nb::init<>())
      .def_rw("a", &ts::Envelope::a)
      .def_rw("b", &ts::Envelope::b)
      .def_rw("c", &ts::Envelope::c)
      .def_rw("d", &ts::Envelope::d)
      .def_rw("lo", &ts::Envelope::lo)
      .def_rw("hi", &ts::Envelope::hi)
      .def("__call__", &ts::Envelope::operator(), nb::arg("x"))
      .def("slope_at", &ts::Envelope::slope_at, nb::arg("x"))
      .def("inverse", &ts::Envelope::inverse, nb::arg("g"));
  using G = ts::GeneralizedPrandtlIshlinskiiParams;
  bind_params<G>(m, "GeneralizedPrandtlIshlinskiiParams");
  bind_model<ts::GeneralizedPrandtlIshlinskii>(m, "GeneralizedPrandtlIshlinskii");
  bind_model<ts::GeneralizedPrandtlIshlinskiiInverse>(m, "GeneralizedPrandtlIshlinskiiInverse")
      .def("input_clamped", &ts::GeneralizedPrandtlIshlinskiiInverse::input_clamped);
}

}  // namespace tsbind
