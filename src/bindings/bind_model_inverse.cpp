// The inverse of every identified model (ModelInverse) and the description it is built from.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <string>
#include <tendonsheath/compensators/make_model_inverse.hpp>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

void bind_parts(nb::module_& m) {
  using L = ts::LagInverseParams;
  bind_params<L>(m, "LagInverseParams");
  using A = ts::AngleLaws;
  nb::class_<A>(m, "AngleLaws")
      .def(nb::init<>())
      .def_rw("angle_friction", &A::angle_friction)
      .def_ro("count", &A::count)
      .def(
          "append",
          [](A& a, int law, double c0, double c1) {
            if (a.count >= A::kMaxParams) throw std::invalid_argument("AngleLaws: too many laws");
            if (law < 0 || law > 2) throw std::invalid_argument("AngleLaws: law must be 0, 1 or 2");
            a.law[a.count] = static_cast<ts::AngleLaw>(law);
            a.c0[a.count] = c0;
            a.c1[a.count] = c1;
            ++a.count;
          },
          "law"_a, "c0"_a, "c1"_a)
      .def(
          "at_angle",
          [](const A& a, double theta) {
            double v[A::kMaxParams];
            a.at_angle(theta, v);
            return std::vector<double>(v, v + a.count);
          },
          "theta"_a)
      .def(
          "at_shape",
          [](const A& a, const ts::ShapeIntegrals& s) {
            double v[A::kMaxParams];
            a.at_shape(s, v);
            return std::vector<double>(v, v + a.count);
          },
          "shape"_a);
  using P = ts::ModelPart;
  nb::class_<P> part(m, "ModelPart");
  part.def(nb::init<>()).def_rw("kind", &P::kind);
  ts::for_each_type(ts::Models{}, [&](auto tag) {  // a property per model of the list
    using Member = ts::PartMember<typename decltype(tag)::type>;
    part.def_rw(Member::name, Member::member);
  });
  part.def_rw("lag", &P::lag).def_rw("base", &P::base).def_rw("laws", &P::laws);
}

// The model list (model_list.hpp) as Python reads it: one dict per model, in the list's order
// (`m`: the module, whose batch kernels a model with a parameter vector has).
nb::list model_kinds(const nb::module_& m) {
  nb::list out;
  ts::for_each_type(ts::Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    nb::dict d;
    d["kind"] = ts::model_kind<M>();
    d["member"] = ts::PartMember<M>::name;  // the ModelPart property holding its parameters
    d["params"] = nb::borrow(nb::type<typename M::Params>());  // the bound parameter struct
    nb::handle model = nb::type<M>();  // the bound model class (PlantModel's: none, Python runs it)
    d["model"] = model.is_valid() ? nb::borrow(model) : nb::none();
    d["root_invertible"] = ts::root_invertible<M>::value;
    d["angle_dependent_base"] = ts::angle_dependent_base<M>;
    constexpr bool vector = ts::has_param_vector<M>::value;
    d["param_vector"] = vector;
    // its batch kernels (bind_batch.cpp binds them for every model with a parameter vector)
    nb::object cost = nb::none(), simulate = nb::none();
    if constexpr (vector) {
      const std::string kind = ts::model_kind<M>();
      cost = m.attr(("population_cost_" + kind).c_str());
      simulate = m.attr(("population_simulate_" + kind).c_str());
    }
    d["population_cost"] = cost;
    d["population_simulate"] = simulate;
    out.append(d);
  });
  return out;
}

void bind_description(nb::module_& m) {
  using S = ts::ScaledMap;
  nb::class_<S>(m, "ScaledMap")
      .def(nb::init<>())
      .def_rw("input_offset", &S::input_offset)
      .def_rw("input_scale", &S::input_scale)
      .def_rw("output_offset", &S::output_offset)
      .def_rw("output_gain", &S::output_gain);
  nb::class_<ts::InputRange>(m, "InputRange")
      .def(nb::init<>())
      .def_rw("lo", &ts::InputRange::lo)
      .def_rw("hi", &ts::InputRange::hi)
      .def_static("identified", &ts::InputRange::identified, "lo"_a, "hi"_a, "margin"_a);
  nb::class_<ts::InverseModel>(m, "InverseModel")
      .def(nb::init<>())
      .def_rw("parts", &ts::InverseModel::parts)
      .def_rw("map", &ts::InverseModel::map);
  using IS = ts::InverseSettings;
  nb::class_<IS>(m, "InverseSettings")
      .def(nb::init<>())
      .def_rw("smoothing", &IS::smoothing)
      .def_rw("limits", &IS::limits)
      .def_rw("range", &IS::range)
      .def_rw("filter_hz", &IS::filter_hz);
  m.def("shape_dead_zone_factor", &ts::shape_dead_zone_factor, "g"_a, "G"_a, "a"_a);
}

// A copy over a whole trajectory; the route (shape rows, or curve angles) set before each step.
nb::object command(const ts::ModelInverse& self, InArray t, InArray y, std::optional<InArray> g,
                   std::optional<InArray> G, std::optional<InArray> theta, bool with_status) {
  const char* where = "InverseFeedforward";
  const std::size_t n = y.shape(0);
  check_lengths(n, t.shape(0), "t", where);
  if (theta) check_lengths(n, theta->shape(0), "curve_angle", where);
  if (g) check_lengths(n, g->shape(0), "g", where);
  if (G) check_lengths(n, G->shape(0), "G", where);
  ts::check_series(t.data(), y.data(), n, where);
  if (theta) ts::check_series(nullptr, theta->data(), n, where);
  auto [out, u] = new_array(n);
  auto [flags, fp] = new_bytes(with_status ? n : 0);
  const double* gp = g ? g->data() : nullptr;
  const double* Gp = G ? G->data() : nullptr;
  const double* hp = theta ? theta->data() : nullptr;
  const double* tp = t.data();
  const double* yp = y.data();
  ts::ModelInverse inv = self;
  inv.reset();
  {
    nb::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) {
      if (gp && Gp && hp) inv.set_shape({gp[k], Gp[k], hp[k]});
      else if (hp) inv.set_curve_angle(hp[k]);
      u[k] = inv.step(yp[k], k == 0 ? 0.0 : tp[k] - tp[k - 1]);
      if (with_status) fp[k] = static_cast<std::uint8_t>(inv.status());
    }
  }
  if (with_status) return nb::make_tuple(out, flags);
  return nb::cast(out);
}

void bind_inverse_engine(nb::module_& m) {
  using C = ts::ModelInverse;
  bind_copy(nb::class_<C>(m, "ModelInverse"))
      .def(
          "__init__",
          [](C* self, const ts::InverseModel& model, const ts::InverseSettings& settings) {
            new (self) C(ts::make_model_inverse(model, settings));
          },
          "model"_a, "settings"_a)
      .def("reset", &C::reset)
      .def("step", &C::step, "y_d"_a, "dt"_a)
      .def("status", [](const C& c) { return static_cast<unsigned>(c.status()); })
      .def("follows_route", &C::follows_route)
      .def("friction", &C::friction)
      .def("set_shape", &C::set_shape, "shape"_a)
      .def("set_curve_angle", &C::set_curve_angle, "curve_angle"_a)
      .def("core_index", [](const C& c) { return c.core().index(); })
      .def("command", &command, "t"_a, "y_d"_a, "g"_a.none() = nb::none(),
           "G"_a.none() = nb::none(), "curve_angle"_a.none() = nb::none(), "status"_a = false);
}

}  // namespace

void bind_model_inverse(nb::module_& m) {
  bind_parts(m);
  bind_description(m);
  bind_inverse_engine(m);
  m.def(
      "model_kinds", [m]() { return model_kinds(m); },
      "The core's model list: per model class a dict of its kind (class name), member (the\n"
      "ModelPart property holding its parameters), params (the parameter struct), model (the\n"
      "bound model class, or None where Python runs the model: PlantModel),\n"
      "root_invertible, angle_dependent_base, param_vector, and population_cost / population_simulate (its batch\n"
      "kernels when it has a parameter vector, else None).");
}

}  // namespace tsbind
