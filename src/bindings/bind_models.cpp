// Hysteresis models: parameter structs, streaming step() and batch simulate(), for every model
// of the list (models/model_list.hpp).
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <string>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"
#include "model_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

// Every model of the list (models/model_list.hpp) is bound here, generically: its parameter
// struct from its table (param_binding.hpp) as <kind>Params, and the model class as <kind> with
// bind_model's constructor, reset/step/simulate (model_binding.hpp). A model with methods of its
// own adds them in a bind_extras() overload below; one whose class is not a one-input streaming
// model says so with a bind_list_model() specialisation.

void bind_extras(nb::class_<ts::Backlash>& c) {
  c.def("set_state", &ts::Backlash::set_state, "x"_a, "y"_a);
}

void bind_extras(nb::class_<ts::BoucWenBacklash>& c) {
  c.def("state", &ts::BoucWenBacklash::state)
      .def("set_state", &ts::BoucWenBacklash::set_state, "x"_a, "w"_a);
}

void bind_extras(nb::class_<ts::BoucWen>& c) {
  c.def("state", &ts::BoucWen::state).def("z_ultimate", &ts::BoucWen::z_ultimate);
}

void bind_extras(nb::class_<ts::PrandtlIshlinskii>& c) {
  c.def("play_states", &ts::PrandtlIshlinskii::play_states);
}

void bind_extras(nb::class_<ts::HystereticOscillator>& c) {
  using Osc = ts::HystereticOscillator;
  c.def("velocity", &Osc::velocity)
      .def("hysteretic_force", &Osc::hysteretic_force)
      .def("delay", &Osc::delay)
      .def("diverged", &Osc::diverged)
      .def("diverged_at", &Osc::diverged_at)
      .def("substeps", &Osc::substeps, "dt"_a)
      .def("z_bound", &Osc::z_bound, "range"_a)
      .def(
          "simulate_dense",
          [](const Osc& self, double dt, std::size_t n, InArray x_fine, int fine) {
            if (fine < 1 || x_fine.shape(0) != n * static_cast<std::size_t>(fine))
              throw std::invalid_argument(
                  "HystereticOscillator: x_fine must have n * fine values (fine >= 1)");
            if (!(dt > 0.0) || !std::isfinite(dt))
              throw std::invalid_argument("HystereticOscillator: dt must be > 0");
            auto [out, y] = new_array(n);
            Osc model = self;
            const double* u = x_fine.data();
            {
              nb::gil_scoped_release release;
              model.reset();
              for (std::size_t k = 0; k < n; ++k)
                y[k] = model.step_dense(u + (k > 0 ? (k - 1) * fine : 0), fine, dt);
            }
            if (model.diverged())
              throw std::invalid_argument(
                  "HystereticOscillator: the state diverged (overflowed) at sample " +
                  std::to_string(model.diverged_at()) + " of " + std::to_string(n));
            return out;
          },
          "dt"_a, "n"_a, "x_fine"_a, "fine"_a,
          "Simulate from an input given on a grid `fine` times finer than the samples.");
}

// The oscillator's sensitivities and its band-limited input on a finer grid.
void bind_oscillator_dense(nb::module_& m) {
  using HO = ts::HystereticOscillatorParams;
  m.def(
      "oscillator_sensitivity_dense",
      [](const HO& params, double dt, std::size_t n, InArray x_fine, int fine) {
        if (fine < 1 || x_fine.shape(0) != n * static_cast<std::size_t>(fine))
          throw std::invalid_argument(
              "oscillator_sensitivity_dense: x_fine must have n * fine values (fine >= 1)");
        if (!(dt > 0.0) || !std::isfinite(dt))
          throw std::invalid_argument("oscillator_sensitivity_dense: dt must be > 0");
        ts::OscillatorSensitivity sens(params);
        auto [out_y, y] = new_array(n);
        auto [out_s, S] = new_matrix(n, ts::OscillatorSensitivity::kParams);
        const double* u = x_fine.data();
        {
          nb::gil_scoped_release release;
          for (std::size_t k = 0; k < n; ++k)
            y[k] = sens.step_dense(u + (k > 0 ? (k - 1) * fine : 0), fine, dt,
                                   S + k * ts::OscillatorSensitivity::kParams);
        }
        return nb::make_tuple(out_y, out_s);
      },
      "params"_a, "dt"_a, "n"_a, "x_fine"_a, "fine"_a,
      "HystereticOscillator displacement and its derivatives with respect to (m, c, k, alpha, "
      "beta, gamma, delta, nu) (n x 8), for an input on a grid `fine` times finer (forward "
      "sensitivities of the RK4 scheme of simulate_dense).");
  m.def(
      "reconstruct_bandlimited",
      [](InArray x, int fine, int lookahead) {
        const std::size_t n = x.shape(0);
        ts::SincKernel kernel(lookahead);
        if (fine < 1) throw std::invalid_argument("reconstruct_bandlimited: fine must be >= 1");
        auto [out, y] = new_array(n * static_cast<std::size_t>(fine));
        ts::reconstruct_bandlimited(kernel, x.data(), n, fine, y);
        return out;
      },
      "x"_a, "fine"_a, "lookahead"_a,
      "The windowed-sinc reconstruction of x on a grid `fine` times finer (input held at the "
      "ends): the values HystereticOscillator's band-limited step() uses.");
}

// A model of the list with no methods of its own beyond bind_model's.
template <class M>
void bind_extras(nb::class_<M>&) {}

// The Python name of model M's parameter struct: <kind>Params.
template <class M>
const char* params_name() {
  static const std::string name = std::string(ts::model_kind<M>()) + "Params";
  return name.c_str();
}
template <>
const char* params_name<ts::CurveAngleModel>() {
  return "CurveAngleParams";
}

// The model class M of the list, bound as a one-input streaming model (and its extras).
template <class M>
void bind_list_model(nb::module_& m) {
  auto cls = bind_model<M>(m, ts::model_kind<M>());
  bind_extras(cls);
}
// Python runs the PlantModel's plant (models/plant_model.py): the core holds its parameters only.
template <>
void bind_list_model<ts::PlantModel>(nb::module_&) {}
// Two inputs, motor angle and curve angle: its own binding (bind_curve_angle.cpp).
template <>
void bind_list_model<ts::CurveAngleModel>(nb::module_& m) {
  bind_curve_angle_model(m);
}

// Model-specific classes beside the list: the GPI's envelopes (before its parameters, whose
// rising/falling fields are Envelopes) and the exact inverses of the two PI models.
void bind_envelope(nb::module_& m) {
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
}

void bind_play_inverses(nb::module_& m) {
  bind_model<ts::PrandtlIshlinskiiInverse>(m, "PrandtlIshlinskiiInverse")
      .def("input_clamped", &ts::PrandtlIshlinskiiInverse::input_clamped);
  bind_model<ts::GeneralizedPrandtlIshlinskiiInverse>(m, "GeneralizedPrandtlIshlinskiiInverse")
      .def("input_clamped", &ts::GeneralizedPrandtlIshlinskiiInverse::input_clamped);
}

}  // namespace

void bind_models(nb::module_& m) {
  bind_envelope(m);
  ts::for_each_type(ts::Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    bind_params<typename M::Params>(m, params_name<M>());
    bind_list_model<M>(m);
  });
  bind_play_inverses(m);
  bind_oscillator_dense(m);
}

}  // namespace tsbind
