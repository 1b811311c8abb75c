// Hysteresis models: parameter structs, streaming step() and batch simulate().
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

namespace {

void bind_backlash(nb::module_& m) {
  bind_params<ts::BacklashParams>(m, "BacklashParams");
  bind_model<ts::Backlash>(m, "Backlash").def("set_state", &ts::Backlash::set_state, "x"_a, "y"_a);
}

// Bouc-Wen backlash and the classic Bouc-Wen model.
void bind_bouc_wen(nb::module_& m) {
  using BWB = ts::BoucWenBacklashParams;
  bind_params<BWB>(m, "BoucWenBacklashParams");
  bind_model<ts::BoucWenBacklash>(m, "BoucWenBacklash")
      .def("state", &ts::BoucWenBacklash::state)
      .def("set_state", &ts::BoucWenBacklash::set_state, "x"_a, "w"_a);

  using BW = ts::BoucWenParams;
  bind_params<BW>(m, "BoucWenParams");
  bind_model<ts::BoucWen>(m, "BoucWen")
      .def("state", &ts::BoucWen::state)
      .def("z_ultimate", &ts::BoucWen::z_ultimate);
}

void bind_oscillator(nb::module_& m) {
  using HO = ts::HystereticOscillatorParams;
  bind_params<HO>(m, "HystereticOscillatorParams");
  using Osc = ts::HystereticOscillator;
  bind_model<Osc>(m, "HystereticOscillator")
      .def("velocity", &Osc::velocity)
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

void bind_prandtl_ishlinskii(nb::module_& m) {
  using PI = ts::PrandtlIshlinskiiParams;
  bind_params<PI>(m, "PrandtlIshlinskiiParams");
  bind_model<ts::PrandtlIshlinskii>(m, "PrandtlIshlinskii")
      .def("play_states", &ts::PrandtlIshlinskii::play_states);
  bind_model<ts::PrandtlIshlinskiiInverse>(m, "PrandtlIshlinskiiInverse")
      .def("input_clamped", &ts::PrandtlIshlinskiiInverse::input_clamped);
}

}  // namespace

void bind_models(nb::module_& m) {
  bind_backlash(m);
  bind_bouc_wen(m);
  bind_oscillator(m);
  bind_oscillator_dense(m);
  bind_prandtl_ishlinskii(m);
}

}  // namespace tsbind
