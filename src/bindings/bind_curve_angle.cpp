// The closed-form curve-angle model (spec B): two inputs, motor angle and curve angle.
#include <nanobind/stl/optional.h>

#include <optional>
#include <string>
#include <tendonsheath/models/curve_angle.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

void bind_curve_angle_model(nb::module_& m) {
  using P = ts::CurveAngleParams;  // bound before, with the model list (bind_models.cpp)
  using M = ts::CurveAngleModel;
  bind_copy(nb::class_<M>(m, "CurveAngleModel"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &M::params)
      .def("reset", &M::reset)
      .def("step", nb::overload_cast<double, double, double>(&M::step), "x"_a, "dt"_a,
           "curve_angle"_a)
      .def("step", nb::overload_cast<double, double>(&M::step), "x"_a, "dt"_a = 0.0)
      .def("output", &M::output)
      .def("curve_angle", &M::curve_angle)
      .def("set_curve_angle", &M::set_curve_angle, "curve_angle"_a)
      .def("set_shape", &M::set_shape, "shape"_a)
      .def("shape", &M::shape)
      .def("uniform", &M::uniform)
      .def("slack", &M::slack)
      .def("status", [](const M& self) { return static_cast<unsigned>(self.status()); })
      .def("backlash_half_width", &M::backlash_half_width, "curve_angle"_a)
      .def("load_offset", &M::load_offset, "curve_angle"_a)
      .def("slope", &M::slope, "curve_angle"_a)
      .def(
          "simulate",
          [](const M& self, std::optional<InArray> t, InArray x, std::optional<InArray> theta,
             bool status) {
            const std::size_t n = x.shape(0);
            if (t && t->shape(0) != n)
              throw std::invalid_argument("CurveAngleModel: t and x have different lengths (" +
                                          std::to_string(t->shape(0)) + " and " +
                                          std::to_string(n) + ")");
            if (theta && theta->shape(0) != n)
              throw std::invalid_argument(
                  "CurveAngleModel: curve_angle and x have different lengths (" +
                  std::to_string(theta->shape(0)) + " and " + std::to_string(n) + ")");
            auto [out, y] = new_array(n);
            auto [flags, fp] = new_bytes(status ? n : 0);
            M model = self;
            const double* tp = t ? t->data() : nullptr;
            const double* thp = theta ? theta->data() : nullptr;  // None: the model's shape
            {
              nb::gil_scoped_release release;
              ts::simulate(model, tp, x.data(), thp, y, n, "CurveAngleModel",
                           status ? fp : nullptr);
            }
            if (status) return nb::object(nb::make_tuple(out, flags));
            return nb::cast(out);
          },
          "t"_a.none(), "x"_a, "curve_angle"_a.none(), "status"_a = false)
      .def_ro_static("rate_independent", &M::rate_independent);
}

}  // namespace tsbind
