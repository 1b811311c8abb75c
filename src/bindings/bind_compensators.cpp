// Compensators: parameter structs, streaming step() and batch command().
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

// Runs a copy of the compensator over a whole trajectory: y_d[k] at t[k]. Returns the commands,
// or (commands, per-sample Status flags as uint8) when with_status.
template <class Comp, class PerStep>
nb::object command_copy(const Comp& self, InArray t, InArray y_d, const char* where,
                        PerStep per_step, bool with_status = false) {
  const std::size_t n = y_d.shape(0);
  check_lengths(n, t.shape(0), "t", where);
  ts::check_series(t.data(), y_d.data(), n, where);
  auto [out, u] = new_array(n);
  auto [flags, fp] = new_bytes(with_status ? n : 0);
  std::uint8_t* status = with_status ? fp : nullptr;
  Comp comp = self;
  comp.reset();
  const double* tp = t.data();
  const double* yp = y_d.data();
  {
    nb::gil_scoped_release release;
    for (std::size_t k = 0; k < n; ++k) {
      const double dt = k == 0 ? 0.0 : tp[k] - tp[k - 1];
      per_step(comp, k);
      u[k] = comp.step(yp[k], dt);
      if (status) status[k] = static_cast<std::uint8_t>(comp.status());
    }
  }
  if (with_status) return nb::make_tuple(out, flags);
  return nb::cast(out);
}

template <class Comp>
unsigned status_of(const Comp& c) {
  return static_cast<unsigned>(c.status());
}

void bind_limits(nb::module_& m) {
  nb::class_<ts::CommandLimits>(m, "CommandLimits")
      .def(nb::init<>())
      .def_rw("min", &ts::CommandLimits::min)
      .def_rw("max", &ts::CommandLimits::max)
      .def_rw("max_rate", &ts::CommandLimits::max_rate);
}

void bind_inverse(nb::module_& m) {
  using P = ts::BacklashInverseParams;
  bind_params<P>(m, "BacklashInverseParams");
  using B = ts::BacklashInverseFeedforward;
  bind_copy(nb::class_<B>(m, "BacklashInverseFeedforward"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &B::params)
      .def("reset", &B::reset)
      .def("step", &B::step, "y_d"_a, "dt"_a)
      .def("step_with_rate", &B::step_with_rate, "y_d"_a, "y_d_rate"_a, "dt"_a)
      .def("status", &status_of<B>)
      .def(
          "command",
          [](const B& self, InArray t, InArray y, bool status) {
            return command_copy(self, t, y, "BacklashInverseFeedforward",
                                [](B&, std::size_t) {}, status);
          },
          "t"_a, "y_d"_a, "status"_a = false);
  using PI = ts::PrandtlIshlinskiiFeedforward;
  bind_copy(nb::class_<PI>(m, "PrandtlIshlinskiiFeedforward"))
      .def(nb::init<const ts::PrandtlIshlinskiiParams&, const ts::CommandLimits&>(), "params"_a,
           "limits"_a)
      .def("reset", &PI::reset)
      .def("step", &PI::step, "y_d"_a, "dt"_a)
      .def("status", &status_of<PI>)
      .def(
          "command",
          [](const PI& self, InArray t, InArray y, bool status) {
            return command_copy(self, t, y, "PrandtlIshlinskiiFeedforward",
                                [](PI&, std::size_t) {}, status);
          },
          "t"_a, "y_d"_a, "status"_a = false);
}

void bind_curve_angle_feedforward(nb::module_& m) {
  using P = ts::CurveAngleFeedforwardParams;
  bind_params<P>(m, "CurveAngleFeedforwardParams");
  using C = ts::CurveAngleFeedforward;
  bind_copy(nb::class_<C>(m, "CurveAngleFeedforward"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &C::params)
      .def_prop_ro("shape", &C::shape)
      .def("reset", &C::reset)
      .def("set_curve_angle", &C::set_curve_angle, "curve_angle"_a)
      .def("angle_clamped", &C::angle_clamped)
      .def("angle_rejected", &C::angle_rejected)
      .def("status", [](const C& c) { return static_cast<unsigned>(c.status()); })
      .def("set_shape", &C::set_shape, "shape"_a)
      .def("step", &C::step, "y_d"_a, "dt"_a)
      .def("last_correction", &C::last_correction)
      .def("correction", &C::correction, "x_d"_a, "phi"_a)
      .def(
          "command",
          [](const C& self, InArray t, InArray y, std::optional<InArray> g, std::optional<InArray> G,
             std::optional<InArray> theta, bool status) {
            const std::size_t n = y.shape(0);
            const char* where = "CurveAngleFeedforward";
            if (theta) check_lengths(n, theta->shape(0), "curve_angle", where);
            if (g) check_lengths(n, g->shape(0), "g", where);
            if (G) check_lengths(n, G->shape(0), "G", where);
            if (theta) ts::check_series(nullptr, theta->data(), n, where);
            const double* gp = g ? g->data() : nullptr;
            const double* Gp = G ? G->data() : nullptr;
            const double* tp = theta ? theta->data() : nullptr;
            return command_copy(self, t, y, where, [=](C& c, std::size_t k) {
              if (gp && Gp && tp) c.set_shape({gp[k], Gp[k], tp[k]});
              else if (tp) c.set_curve_angle(tp[k]);
            }, status);
          },
          "t"_a, "y_d"_a, "g"_a.none(), "G"_a.none(), "curve_angle"_a.none(), "status"_a = false);
}

void bind_continuum(nb::module_& m) {
  nb::enum_<ts::ContinuumMode>(m, "ContinuumMode")
      .value("exact", ts::ContinuumMode::Exact)
      .value("published", ts::ContinuumMode::Published);
  using P = ts::ContinuumFeedforwardParams;
  bind_params<P>(m, "ContinuumFeedforwardParams");
  using C = ts::ContinuumFeedforward;
  bind_copy(nb::class_<C>(m, "ContinuumFeedforward"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &C::params)
      .def("reset", &C::reset)
      .def("step", &C::step, "theta_d"_a, "dt"_a)
      .def("bending_force", &C::bending_force, "theta_d"_a)
      .def("tendon_input", &C::tendon_input, "theta_d"_a, "direction"_a)
      .def("status", &status_of<C>)
      .def(
          "command",
          [](const C& self, InArray t, InArray y, bool status) {
            return command_copy(self, t, y, "ContinuumFeedforward", [](C&, std::size_t) {}, status);
          },
          "t"_a, "y_d"_a, "status"_a = false);
}

void bind_adaptive(nb::module_& m) {
  using P = ts::AdaptiveControllerParams;
  bind_params<P>(m, "AdaptiveControllerParams");
  nb::class_<ts::AdaptiveEstimates>(m, "AdaptiveEstimates")
      .def_ro("psi", &ts::AdaptiveEstimates::psi)
      .def_ro("phi", &ts::AdaptiveEstimates::phi)
      .def_ro("D", &ts::AdaptiveEstimates::D);
  using C = ts::AdaptiveController;
  bind_copy(nb::class_<C>(m, "AdaptiveController"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &C::params)
      .def_prop_ro("estimates", &C::estimates)
      .def("in_fallback", &C::in_fallback)
      .def("filtered_rate", &C::filtered_rate)
      .def("status", [](const C& c) { return static_cast<unsigned>(c.status()); })
      .def("reset", &C::reset)
      .def("step", &C::step, "y_d"_a, "y_measured"_a, "motor_position"_a, "dt"_a);
}

void bind_encoder_loop(nb::module_& m) {
  using P = ts::EncoderLoopParams;
  bind_params<P>(m, "EncoderLoopParams");
  using L = ts::EncoderLoop;
  bind_copy(nb::class_<L>(m, "EncoderLoop"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &L::params)
      .def("reset", &L::reset)
      .def("correct", &L::correct, "target"_a, "encoder"_a, "dt"_a)
      .def("correction", &L::correction)
      .def("integral", &L::integral)
      .def("error", &L::error)
      .def("status", &status_of<L>);
}

void bind_tip_loop(nb::module_& m) {
  using P = ts::TipLoopParams;
  // the schedule's arrays are bound by hand: read-only lists of schedule_size points, set
  // together by set_schedule (a table row would expose all kMaxSchedule slots)
  bind_params<P>(m, "TipLoopParams")
      .def_prop_ro("schedule_angles",
                   [](const P& p) {
                     return std::vector<double>(p.schedule_angles.begin(),
                                                p.schedule_angles.begin() + p.schedule_size);
                   })
      .def_prop_ro("schedule_gains",
                   [](const P& p) {
                     return std::vector<double>(p.schedule_gains.begin(),
                                                p.schedule_gains.begin() + p.schedule_size);
                   })
      .def(
          "set_schedule",
          [](P& p, const std::vector<double>& angles, const std::vector<double>& gains) {
            if (angles.size() != gains.size())
              throw std::invalid_argument("TipLoop: schedule_angles and schedule_gains differ in size (" +
                                          std::to_string(angles.size()) + " and " +
                                          std::to_string(gains.size()) + ")");
            if (angles.size() > P::kMaxSchedule)
              throw std::invalid_argument("TipLoop: the schedule holds at most " +
                                          std::to_string(P::kMaxSchedule) + " points (got " +
                                          std::to_string(angles.size()) + ")");
            p.schedule_size = angles.size();
            for (std::size_t i = 0; i < angles.size(); ++i) {
              p.schedule_angles[i] = angles[i];
              p.schedule_gains[i] = gains[i];
            }
          },
          "angles"_a, "gains"_a);
  using L = ts::TipLoop;
  bind_copy(nb::class_<L>(m, "TipLoop"))
      .def(nb::init<const P&>(), "params"_a)
      .def_prop_ro("params", &L::params)
      .def("reset", &L::reset)
      .def("correct", &L::correct, "target"_a, "y_d"_a, "measured"_a, "dt"_a)
      .def("set_curve_angle", &L::set_curve_angle, "angle"_a)
      .def("set_shape", &L::set_shape, "shape"_a)
      .def("correction", &L::correction)
      .def("integral", &L::integral)
      .def("error", &L::error)
      .def("gain_scale", &L::gain_scale)
      .def("curve_angle", &L::curve_angle)
      .def("in_fallback", &L::in_fallback)
      .def("status", &status_of<L>);
}

void bind_learned_feedforward(nb::module_& m) {
  using P = ts::LearnedFeedforwardParams;
  bind_params<P>(m, "LearnedFeedforwardParams");
  using L = ts::LearnedCorrection;
  bind_copy(nb::class_<L>(m, "LearnedCorrection"))
      .def(nb::init<std::vector<double>, const P&>(), "table"_a, "params"_a)
      .def_prop_ro("params", &L::params)
      .def_prop_ro("table", &L::table)
      .def("duration", &L::duration)
      .def("reset", &L::reset)
      .def("at", &L::at, "t"_a)
      .def("correct", &L::correct, "target"_a, "dt"_a)
      .def("time", &L::time)
      .def("correction", &L::correction)
      .def("status", &status_of<L>)
      .def(
          "play",
          [](const L& self, InArray t, InArray target) {
            // a copy from its reset state over a whole series, target[k] at t[k]: the commands
            // and each cycle's Status flags
            const char* where = "LearnedCorrection.play";
            const std::size_t n = target.shape(0);
            check_lengths(n, t.shape(0), "t", where);
            auto [out, u] = new_array(n);
            auto [flags, fp] = new_bytes(n);
            L copy = self;
            copy.reset();
            const double* tp = t.data();
            const double* xp = target.data();
            {
              nb::gil_scoped_release release;
              for (std::size_t k = 0; k < n; ++k) {
                u[k] = copy.correct(xp[k], k == 0 ? 0.0 : tp[k] - tp[k - 1]);
                fp[k] = static_cast<std::uint8_t>(copy.status());
              }
            }
            return nb::make_tuple(out, flags);
          },
          "t"_a, "target"_a);
}

void bind_load_play_inverse(nb::module_& m) {
  bind_copy(nb::class_<ts::LoadTerms>(m, "LoadTerms"))
      .def(nb::init<>())
      .def_rw("gain", &ts::LoadTerms::gain)
      .def_rw("slack", &ts::LoadTerms::slack)
      .def_rw("slack_load", &ts::LoadTerms::slack_load)
      .def_rw("friction", &ts::LoadTerms::friction)
      .def_rw("switch_travel", &ts::LoadTerms::switch_travel)
      .def("radius", &ts::LoadTerms::radius, "load"_a);
  bind_copy(nb::class_<ts::LoadPlayInverse>(m, "LoadPlayInverse"))
      .def(nb::init<const ts::LoadTerms&>(), "terms"_a)
      .def("reset", &ts::LoadPlayInverse::reset)
      .def("step", &ts::LoadPlayInverse::step, "z"_a, "load"_a)
      .def(
          "command",
          [](const ts::LoadPlayInverse& self, InArray z, InArray load) {
            const std::size_t n = z.shape(0);
            check_lengths(n, load.shape(0), "load", "LoadPlayInverse.command");
            auto [out, u] = new_array(n);
            ts::LoadPlayInverse copy = self;
            copy.reset();
            const double* zp = z.data();
            const double* lp = load.data();
            {
              nb::gil_scoped_release release;
              for (std::size_t k = 0; k < n; ++k) u[k] = copy.step(zp[k], lp[k]);
            }
            return out;
          },
          "z"_a, "load"_a);
}

// Whether C has params() (the parameters it was built with).
template <class C, class = void>
struct has_params : std::false_type {};
template <class C>
struct has_params<C, std::void_t<decltype(std::declval<const C&>().params())>> : std::true_type {};

// Compensator C of the list bound from its table and its step's signature: C(params), params,
// reset(), step(<signals>, dt), status(), step_inputs, and command(t, y_d) for a feedforward; its
// Params as "<owner>Params" (bind_params) unless bound already.
template <class C>
void bind_from_table(nb::module_& m) {
  using P = typename C::Params;
  static const std::string params_name = std::string(ts::compensator_kind<C>()) + "Params";
  if (!nb::type<P>().is_valid()) bind_params<P>(m, params_name.c_str());
  auto cls = bind_copy(nb::class_<C>(m, ts::compensator_kind<C>()));
  cls.def(nb::init<const P&>(), "params"_a).def("reset", &C::reset).def("status", &status_of<C>);
  if constexpr (has_params<C>::value) cls.def_prop_ro("params", &C::params);
  constexpr int n = ts::compensator_step_inputs<C>();
  static_assert(n >= 1, "a compensator of the list needs step(y_d, [measured, [motor,]] dt)");
  if constexpr (n == 1) {
    cls.def("step", [](C& c, double r, double dt) { return c.step(r, dt); }, "y_d"_a, "dt"_a);
    cls.def(
        "command",
        [](const C& self, InArray t, InArray y, bool status) {
          return command_copy(self, t, y, ts::compensator_kind<C>(), [](C&, std::size_t) {},
                              status);
        },
        "t"_a, "y_d"_a, "status"_a = false);
  } else if constexpr (n == 2) {
    cls.def("step", [](C& c, double r, double y, double dt) { return c.step(r, y, dt); },
            "y_d"_a, "y"_a, "dt"_a);
    cls.attr("step_inputs") = nb::make_tuple("y_d", "y");
  } else {
    cls.def("step",
            [](C& c, double r, double y, double q, double dt) { return c.step(r, y, q, dt); },
            "y_d"_a, "y"_a, "q"_a, "dt"_a);
    cls.attr("step_inputs") = nb::make_tuple("y_d", "y", "q");
  }
}

}  // namespace

// Every compensator of the list (compensator_list.hpp: Compensators) that has no binding of its
// own above (or in bind_model_inverse.cpp) bound from its table (bind_from_table), after those;
// and compensator_kinds(): the Python class names of the list, in its order.
void bind_compensator_list(nb::module_& m) {
  std::vector<std::string> kinds;
  ts::for_each_type(ts::Compensators{}, [&](auto tag) {
    using C = typename decltype(tag)::type;
    if (!nb::type<C>().is_valid()) {
      if constexpr (ts::has_params_table<C>::value) bind_from_table<C>(m);
      else throw std::logic_error("a compensator of the list has neither a binding nor a table");
    }
    kinds.push_back(nb::cast<std::string>(nb::type<C>().attr("__name__")));
  });
  m.def("compensator_kinds", [kinds]() { return kinds; },
        "The Python class names of the core's compensator list (compensator_list.hpp), in its "
        "order: the compensators bench.run steps in its C++ loop.");
  m.def(
      "compensator_classes",
      []() {
        nb::dict out;
        ts::for_each_type(ts::Compensators{}, [&](auto tag) {
          using C = typename decltype(tag)::type;
          nb::handle cls = nb::type<C>();
          out[cls.attr("__name__")] = cls;
          if constexpr (ts::has_params_table<C>::value) {
            nb::handle params = nb::type<typename C::Params>();
            out[params.attr("__name__")] = params;
          }
        });
        return out;
      },
      "The classes of the core's compensator list and their parameter structs, by name.");
}

void bind_compensators(nb::module_& m) {
  bind_limits(m);
  bind_inverse(m);
  bind_curve_angle_feedforward(m);
  bind_continuum(m);
  bind_adaptive(m);
  bind_encoder_loop(m);
  bind_learned_feedforward(m);
  bind_tip_loop(m);
  bind_load_play_inverse(m);
}

}  // namespace tsbind
