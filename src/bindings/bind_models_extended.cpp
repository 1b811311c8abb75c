// Models for real loops: static polynomial output map and the generalized
// Prandtl-Ishlinskii model with its inverse.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

template <class Model>
void bind_extended_model(nb::module_& m, const char* name) {
  nb::class_<Model>(m, name)
      .def(nb::init<const typename Model::Params&>(), "params"_a)
      .def_prop_ro("params", &Model::params)
      .def("reset", &Model::reset)
      .def("step", &Model::step, "x"_a, "dt"_a = 0.0)
      .def("output", &Model::output)
      .def(
          "simulate",
          [name](const Model& self, std::optional<InArray> t, InArray x) {
            const std::size_t n = x.shape(0);
            if (t && t->shape(0) != n)
              throw std::invalid_argument(std::string(name) + ": t and x have different lengths");
            auto [out, y] = new_array(n);
            Model model = self;
            const double* tp = t ? t->data() : nullptr;
            const double* xp = x.data();
            {
              nb::gil_scoped_release release;
              ts::simulate(model, tp, xp, y, n, name);
            }
            return out;
          },
          "t"_a.none(), "x"_a)
      .def_ro_static("rate_independent", &Model::rate_independent);
}

void bind_models_extended(nb::module_& m) {
  nb::class_<ts::PolynomialParams>(m, "PolynomialParams")
      .def(nb::init<>())
      .def_rw("coefficients", &ts::PolynomialParams::coefficients)
      .def_rw("odd", &ts::PolynomialParams::odd);
  bind_extended_model<ts::Polynomial>(m, "Polynomial");

  nb::class_<ts::Envelope>(m, "Envelope")
      .def(nb::init<>())
      .def_rw("a", &ts::Envelope::a)
      .def_rw("b", &ts::Envelope::b)
      .def_rw("c", &ts::Envelope::c)
      .def_rw("d", &ts::Envelope::d);
  using G = ts::GeneralizedPrandtlIshlinskiiParams;
  nb::class_<G>(m, "GeneralizedPrandtlIshlinskiiParams")
      .def(nb::init<>())
      .def_rw("rising", &G::rising)
      .def_rw("falling", &G::falling)
      .def_rw("thresholds", &G::thresholds)
      .def_rw("weights", &G::weights);
  bind_extended_model<ts::GeneralizedPrandtlIshlinskii>(m, "GeneralizedPrandtlIshlinskii");
  bind_extended_model<ts::GeneralizedPrandtlIshlinskiiInverse>(m,
                                                               "GeneralizedPrandtlIshlinskiiInverse");
}

}  // namespace tsbind
