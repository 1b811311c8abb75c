// The closed-form statics (physics/pull_pull_statics.hpp): the shape integrals, PullPullStatics
// and the uniform-curvature closed forms, element by element over NumPy arrays, so that
// tendonsheath.physics and the models compute them from this one source.
#include <array>
#include <cstddef>
#include <string>
#include <tendonsheath/physics/pull_pull_statics.hpp>
#include <utility>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

template <class F, std::size_t N, std::size_t... I>
double apply_at(F f, const std::array<const double*, N>& p, std::size_t k,
                std::index_sequence<I...>) noexcept {
  return f(p[I][k]...);
}

// f(in[0][k], ..., in[N-1][k]) for every k: equal-length arrays (Python broadcasts first).
template <std::size_t N, class F>
OutArray elementwise(const std::array<InArray, N>& in, const char* where, F f) {
  const std::size_t n = in[0].shape(0);
  std::array<const double*, N> p{};
  for (std::size_t i = 0; i < N; ++i) {
    check_lengths(n, in[i].shape(0), ("argument " + std::to_string(i)).c_str(), where);
    p[i] = in[i].data();
  }
  auto [out, y] = new_array(n);
  for (std::size_t k = 0; k < n; ++k) y[k] = apply_at(f, p, k, std::make_index_sequence<N>{});
  return out;
}

void bind_shape(nb::module_& m) {
  nb::class_<ts::ShapeIntegrals>(m, "ShapeIntegrals")
      .def(nb::init<>())
      .def_rw("g", &ts::ShapeIntegrals::g)
      .def_rw("G", &ts::ShapeIntegrals::G)
      .def_rw("curve_angle", &ts::ShapeIntegrals::curve_angle)
      .def_prop_ro("total_angle", [](const ts::ShapeIntegrals& s) {
        // the old name of curve_angle, on the shapes compensate.shape_of returns
        if (PyErr_WarnEx(PyExc_DeprecationWarning,
                         "ShapeIntegrals: 'total_angle' is now called 'curve_angle' "
                         "(docs/vocabulary.md); 'total_angle' will be removed in a future release",
                         1) < 0)
          throw nb::python_error();
        return s.curve_angle;
      });
  m.def("uniform_shape", &ts::uniform_shape, "friction"_a, "curve_angle"_a);
  m.def(
      "shape_integrals",
      [](InArray s, InArray theta, double mu) {
        check_lengths(s.shape(0), theta.shape(0), "theta", "shape_integrals");
        return ts::shape_integrals(s.data(), theta.data(), s.shape(0), mu);
      },
      "s"_a, "theta"_a, "friction"_a);
}

void bind_pull_pull_statics(nb::module_& m) {
  using S = ts::PullPullStatics;
  using One = double (S::*)(const ts::ShapeIntegrals&, double) const noexcept;
  using Two = double (S::*)(const ts::ShapeIntegrals&, const ts::ShapeIntegrals&, double,
                            double) const noexcept;
  nb::class_<S>(m, "PullPullStatics")
      .def(nb::init<>())
      .def_rw("friction", &S::friction)
      .def_rw("compliance", &S::compliance)
      .def_rw("pretension", &S::pretension)
      .def("forward_elongation", static_cast<One>(&S::forward_elongation), "shape"_a, "load"_a)
      .def("backward_elongation", static_cast<One>(&S::backward_elongation), "shape"_a,
           "load"_a)
      .def("forward_elongation", static_cast<Two>(&S::forward_elongation), "shape1"_a,
           "shape2"_a, "length_ratio"_a, "load"_a)
      .def("backward_elongation", static_cast<Two>(&S::backward_elongation), "shape1"_a,
           "shape2"_a, "length_ratio"_a, "load"_a)
      .def("backlash_half_width", &S::backlash_half_width, "shape"_a, "load"_a = 0.0);
}

// Series helpers and the uniform closed forms, each over arrays.
void bind_closed_forms(nb::module_& m) {
  m.attr("series_switch") = ts::kSeriesSwitch;
  m.def("expm1_over", [](InArray x) { return elementwise<1>({x}, "expm1_over", ts::expm1_over); });
  m.def("tanh_half_over",
        [](InArray a) { return elementwise<1>({a}, "tanh_half_over", ts::tanh_half_over); });
  m.def("a_over_sinh",
        [](InArray a) { return elementwise<1>({a}, "a_over_sinh", ts::a_over_sinh); });
  m.def(
      "uniform_backlash_half_width",
      [](InArray L, InArray EA, InArray T0, InArray a) {
        return elementwise<4>({L, EA, T0, a}, "backlash_half_width",
                              ts::uniform::backlash_half_width);
      },
      "length"_a, "stiffness"_a, "pretension"_a, "a"_a);
  m.def(
      "uniform_load_compliance",
      [](InArray L, InArray EA, InArray a) {
        return elementwise<3>({L, EA, a}, "load_compliance", ts::uniform::load_compliance);
      },
      "length"_a, "stiffness"_a, "a"_a);
  m.def(
      "uniform_load_offset",
      [](InArray L, InArray EA, InArray F, InArray a) {
        return elementwise<4>({L, EA, F, a}, "load_offset", ts::uniform::load_offset);
      },
      "length"_a, "stiffness"_a, "load"_a, "a"_a);
  m.def(
      "uniform_spring_slope",
      [](InArray L, InArray EA, InArray k, InArray a) {
        return elementwise<4>({L, EA, k, a}, "spring_slope", ts::uniform::spring_slope);
      },
      "length"_a, "stiffness"_a, "spring"_a, "a"_a);
  m.def(
      "uniform_no_slack_limit",
      [](InArray T0, InArray a) {
        return elementwise<2>({T0, a}, "no_slack_limit", ts::uniform::no_slack_limit);
      },
      "pretension"_a, "a"_a);
}

}  // namespace

void bind_statics(nb::module_& m) {
  bind_shape(m);
  bind_pull_pull_statics(m);
  bind_closed_forms(m);
}

}  // namespace tsbind
