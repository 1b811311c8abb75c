// The binding of a streaming model: constructor from its parameter struct, reset/step,
// and simulate() over whole NumPy arrays on a copy (the loop runs in C++, GIL released).
#pragma once

#include <nanobind/stl/optional.h>

#include <optional>
#include <string>
#include <tendonsheath/models/simulate.hpp>

#include "bindings.hpp"

namespace tsbind {

namespace ts = tendonsheath;
using namespace nb::literals;

// The outputs, or (outputs, per-sample Status flags as uint8) when with_status.
template <class Model>
nb::object simulate_copy(const Model& self, std::optional<InArray> t, InArray x, const char* name,
                         bool with_status) {
  const std::size_t n = x.shape(0);
  if (t && t->shape(0) != n)
    throw std::invalid_argument(std::string(name) + ": t and x have different lengths (" +
                                std::to_string(t->shape(0)) + " and " + std::to_string(n) + ")");
  auto [out, y] = new_array(n);
  auto [flags, fp] = new_bytes(with_status ? n : 0);
  Model model = self;
  const double* tp = t ? t->data() : nullptr;
  const double* xp = x.data();
  {
    nb::gil_scoped_release release;
    ts::simulate(model, tp, xp, y, n, name, with_status ? fp : nullptr);
  }
  if (with_status) return nb::make_tuple(out, flags);
  return nb::cast(out);
}

template <class Model>
nb::class_<Model> bind_model(nb::module_& m, const char* name) {
  nb::class_<Model> cls(m, name);
  cls.def(nb::init<const typename Model::Params&>(), "params"_a)
      .def_prop_ro("params", &Model::params)
      .def("reset", &Model::reset)
      .def("step", &Model::step, "x"_a, "dt"_a = 0.0)
      .def("output", &Model::output)
      .def("status", [](const Model& self) { return static_cast<unsigned>(self.status()); })
      .def(
          "simulate",
          [name](const Model& self, std::optional<InArray> t, InArray x, bool status) {
            return simulate_copy(self, t, x, name, status);
          },
          "t"_a.none(), "x"_a, "status"_a = false)
      .def_ro_static("rate_independent", &Model::rate_independent);
  bind_copy(cls);
  return cls;
}

}  // namespace tsbind
