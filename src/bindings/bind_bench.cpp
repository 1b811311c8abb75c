// The closed-loop virtual bench: one call runs the whole loop in C++, over any plant (the erased
// plant of bench_plant.hpp: a shipped engine, a compiled user plant or a Python one).
#include <nanobind/stl/optional.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/variant.h>
#include <nanobind/stl/vector.h>

#include <array>
#include <optional>
#include <string>
#include <variant>
#include <tendonsheath/bench/erased_compensator.hpp>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "bench_plant.hpp"
#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

using InMask = nb::ndarray<const std::uint8_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
// the optional loop around a controller's command: on the motor encoder or on the tip
using OuterLoop = std::variant<ts::EncoderLoop, ts::TipLoop>;

// A compensator written in Python: one call of its step (and status) per cycle, GIL held.
struct PythonLoop {
  nb::object self;
  nb::object step;
  nb::object status_fn;          // None: no status
  std::vector<int> inputs;       // 0: y_d, 1: measured, 2: motor (step_inputs order)
  std::string name;
  static constexpr bool needs_gil = true;

  void reset() { self.attr("reset")(); }
  void on_shape(const ts::ShapeIntegrals&) noexcept {}
  // a property (AdaptiveController.in_fallback) or a method; absent: never in fallback
  bool in_fallback() const {
    if (!nb::hasattr(self, "in_fallback")) return false;
    nb::object v = self.attr("in_fallback");
    if (PyCallable_Check(v.ptr())) v = v();
    return PyObject_IsTrue(v.ptr()) == 1;
  }
  ts::Status status() const {
    if (status_fn.is_none()) return ts::Status::ok;
    nb::object flags = status_fn();
    if (!PyLong_Check(flags.ptr()))  // tendonsheath.Status is an IntFlag
      throw nb::type_error(("bench.run: " + name + ".status() must return Status flags (an int), not " +
                            nb::cast<std::string>(nb::repr(flags))).c_str());
    return static_cast<ts::Status>(nb::cast<unsigned>(flags));
  }
  double command(double y_d, double measured, double motor, double dt) {
    const std::array<double, 3> v{y_d, measured, motor};
    nb::object r;
    switch (inputs.size()) {
      case 1: r = step(v[inputs[0]], dt); break;
      case 2: r = step(v[inputs[0]], v[inputs[1]], dt); break;
      default: r = step(v[inputs[0]], v[inputs[1]], v[inputs[2]], dt); break;
    }
    const double u = PyFloat_AsDouble(r.ptr());
    if (u == -1.0 && PyErr_Occurred()) {
      PyErr_Clear();
      throw nb::type_error(("bench.run: " + name + ".step returned " +
                            nb::cast<std::string>(nb::repr(r)) + ", not a number").c_str());
    }
    return u;
  }
};

template <class Controller, class = void>
struct NeedsGil : std::false_type {};
template <class Controller>
struct NeedsGil<Controller, std::void_t<decltype(Controller::needs_gil)>> : std::true_type {};
template <class Inner>
struct NeedsGil<ts::WithEncoderLoop<Inner>> : NeedsGil<Inner> {};
template <class Inner>
struct NeedsGil<ts::WithLearnedCorrection<Inner>> : NeedsGil<Inner> {};
template <class Inner>
struct NeedsGil<ts::WithTipLoop<Inner>> : NeedsGil<Inner> {};

template <class Controller>
nb::tuple run_loop(BenchPlant& plant, std::optional<ts::Motor> motor,
              std::optional<ts::Sensor> sensor, Controller controller, InArray t, InArray y_d,
              std::optional<InIndex> sidx, std::optional<InMatrix> sang,
              std::optional<InMatrix> shapes, std::optional<InMask> dropout) {
  const char* where = "bench.run";
  const std::size_t n = y_d.shape(0);
  if (t.shape(0) != n) throw std::invalid_argument("bench.run: t and the reference differ in length");
  if (dropout && dropout->shape(0) != n)
    throw std::invalid_argument("bench.run: the dropout mask and the reference differ in length");
  std::vector<std::size_t> idx;
  const ts::RouteSchedule sched = to_schedule(sidx, sang, idx, where);
  std::vector<ts::ShapeIntegrals> shape_rows;
  ts::ShapeSchedule shape_sched;
  if (shapes) {
    if (shapes->shape(0) != sched.count || shapes->shape(1) != 3)
      throw std::invalid_argument("bench.run: one (g, G, Theta) row is needed per route change");
    for (std::size_t i = 0; i < sched.count; ++i)
      shape_rows.push_back({shapes->data()[3 * i], shapes->data()[3 * i + 1], shapes->data()[3 * i + 2]});
    shape_sched.shapes = shape_rows.data();
  }
  auto [output, po] = new_array(n);
  auto [measured, pm] = new_array(n);
  auto [command, pc] = new_array(n);
  auto [motor_pos, pq] = new_array(n);
  auto [status, pst] = new_bytes(n);
  std::vector<unsigned char> slack(n), fallback(n);
  ts::ClosedLoopTrace trace{po, pm, pc, pq, slack.data(), fallback.data(), pst};
  auto loop = [&] {
    ts::run_closed_loop(plant.view, motor ? &*motor : nullptr, sensor ? &*sensor : nullptr, controller,
                        t.data(), y_d.data(), n, sched, shape_sched,
                        dropout ? dropout->data() : nullptr, trace, where);
  };
  if (NeedsGil<Controller>::value || plant.needs_gil) {
    loop();
  } else {
    nb::gil_scoped_release release;
    loop();
  }
  plant.rethrow();
  auto [slack_arr, ps] = new_array(n);
  auto [fallback_arr, pf] = new_array(n);
  for (std::size_t k = 0; k < n; ++k) {
    ps[k] = slack[k];
    pf[k] = fallback[k];
  }
  return nb::make_tuple(output, measured, command, motor_pos, slack_arr, fallback_arr, status);
}

// The loop, with an EncoderLoop or a TipLoop around the controller's command when one is given.
template <class Controller>
nb::tuple run_looped(BenchPlant& plant, std::optional<ts::Motor> motor,
                     std::optional<ts::Sensor> sensor, Controller controller, InArray t,
                     InArray y_d, std::optional<InIndex> sidx, std::optional<InMatrix> sang,
                     std::optional<InMatrix> shapes, std::optional<InMask> dropout,
                     std::optional<OuterLoop> outer_loop) {
  if (outer_loop) {
    if (const auto* e = std::get_if<ts::EncoderLoop>(&*outer_loop))
      return run_loop(plant, motor, sensor,
                      ts::WithEncoderLoop<Controller>{std::move(controller), *e}, t, y_d, sidx,
                      sang, shapes, dropout);
    return run_loop(plant, motor, sensor,
                    ts::WithTipLoop<Controller>{std::move(controller),
                                                std::get<ts::TipLoop>(*outer_loop)},
                    t, y_d, sidx, sang, shapes, dropout);
  }
  return run_loop(plant, motor, sensor, std::move(controller), t, y_d, sidx, sang, shapes, dropout);
}

// The loop, with a learned correction table added to the controller's command (inside the
// encoder or tip loop, whose target it corrects) when one is given.
template <class Controller>
nb::tuple run(BenchPlant& plant, std::optional<ts::Motor> motor,
              std::optional<ts::Sensor> sensor, Controller controller, InArray t, InArray y_d,
              std::optional<InIndex> sidx, std::optional<InMatrix> sang,
              std::optional<InMatrix> shapes, std::optional<InMask> dropout,
              std::optional<OuterLoop> outer_loop, std::optional<ts::LearnedCorrection> learned) {
  if (learned)
    return run_looped(plant, motor, sensor,
                      ts::WithLearnedCorrection<Controller>{std::move(controller), *learned}, t,
                      y_d, sidx, sang, shapes, dropout, outer_loop);
  return run_looped(plant, motor, sensor, std::move(controller), t, y_d, sidx, sang, shapes,
                    dropout, outer_loop);
}

template <class Make>
void def_run(nb::module_& m, const char* name, Make make) {
  m.def(
      name,
      [make](nb::handle plant, std::optional<ts::Motor> motor,
             std::optional<ts::Sensor> sensor, const typename Make::argument_type& c, InArray t,
             InArray y_d, std::optional<InIndex> sidx, std::optional<InMatrix> sang,
             std::optional<InMatrix> shapes, std::optional<InMask> dropout,
             std::optional<OuterLoop> outer_loop, std::optional<ts::LearnedCorrection> learned) {
        BenchPlant bench_plant(plant);
        return run(bench_plant, motor, sensor, make(c), t, y_d, sidx, sang, shapes, dropout,
                   outer_loop, learned);
      },
      "plant"_a, "motor"_a.none(), "sensor"_a.none(), "controller"_a, "t"_a, "y_d"_a,
      "schedule_index"_a.none(), "schedule_angles"_a.none(), "shapes"_a.none(),
      "dropout"_a.none(), "outer_loop"_a.none() = nb::none(), "learned"_a.none() = nb::none());
}

template <class Arg, class Loop>
struct Maker {
  using argument_type = Arg;
  Loop operator()(const Arg& a) const { return Loop{a}; }
};

// The compensator in a capsule from tendonsheath_bind::bind_compensator (another module).
ts::ErasedLoop erased_loop(nb::handle capsule) {
  if (!PyCapsule_IsValid(capsule.ptr(), ts::kCompensatorCapsuleName))
    throw nb::type_error(
        "bench.run: _tendonsheath_compensator() must return a capsule named "
        "'tendonsheath.compensator.v1' (bind the class with tendonsheath_bind/compensator.hpp)");
  auto* c = static_cast<ts::ErasedCompensator*>(
      PyCapsule_GetPointer(capsule.ptr(), ts::kCompensatorCapsuleName));
  if (c->table == nullptr || c->table->version != ts::kCompensatorTableVersion)
    throw nb::type_error("bench.run: the compensator was built against another tendonsheath "
                         "version (function table version mismatch): rebuild it");
  return ts::ErasedLoop{*c};
}

PythonLoop python_loop(nb::object compensator, const std::vector<int>& inputs) {
  nb::object status = nb::none();
  if (nb::hasattr(compensator, "status") && PyCallable_Check(compensator.attr("status").ptr()))
    status = compensator.attr("status");
  return PythonLoop{compensator, compensator.attr("step"), status, inputs,
                    nb::cast<std::string>(nb::type_name(compensator.type()))};
}

template <class Loop>
nb::tuple run_any(nb::handle plant_handle, std::optional<ts::Motor> motor,
                  std::optional<ts::Sensor> sensor, Loop loop, InArray t, InArray y_d,
                  std::optional<InIndex> sidx, std::optional<InMatrix> sang,
                  std::optional<InMask> dropout, std::optional<OuterLoop> outer_loop,
                  std::optional<InMatrix> shapes, std::optional<ts::LearnedCorrection> learned) {
  BenchPlant plant(plant_handle);
  return run(plant, motor, sensor, std::move(loop), t, y_d, sidx, sang, shapes, dropout,
             outer_loop, learned);
}

}  // namespace

void bind_bench(nb::module_& m) {
  m.def(
      "bench_erased",
      [](nb::handle plant, std::optional<ts::Motor> motor,
         std::optional<ts::Sensor> sensor, nb::handle capsule, InArray t, InArray y_d,
         std::optional<InIndex> sidx, std::optional<InMatrix> sang,
         std::optional<InMask> dropout, std::optional<OuterLoop> outer_loop,
         std::optional<InMatrix> shapes, std::optional<ts::LearnedCorrection> learned) {
        return run_any(plant, motor, sensor, erased_loop(capsule), t, y_d, sidx, sang, dropout,
                       outer_loop, shapes, learned);
      },
      "plant"_a, "motor"_a.none(), "sensor"_a.none(), "capsule"_a, "t"_a, "y_d"_a,
      "schedule_index"_a.none(), "schedule_angles"_a.none(), "dropout"_a.none(),
      "outer_loop"_a.none() = nb::none(), "shapes"_a.none() = nb::none(),
      "learned"_a.none() = nb::none());
  m.def(
      "bench_python",
      [](nb::handle plant, std::optional<ts::Motor> motor,
         std::optional<ts::Sensor> sensor, nb::object compensator, std::vector<int> inputs,
         InArray t, InArray y_d, std::optional<InIndex> sidx, std::optional<InMatrix> sang,
         std::optional<InMask> dropout, std::optional<OuterLoop> outer_loop,
         std::optional<InMatrix> shapes, std::optional<ts::LearnedCorrection> learned) {
        if (inputs.empty() || inputs.size() > 3)
          throw nb::value_error("bench_python: 1 to 3 step inputs");
        for (int i : inputs)
          if (i < 0 || i > 2) throw nb::value_error("bench_python: step input codes are 0, 1, 2");
        return run_any(plant, motor, sensor, python_loop(compensator, inputs), t, y_d, sidx, sang,
                       dropout, outer_loop, shapes, learned);
      },
      "plant"_a, "motor"_a.none(), "sensor"_a.none(), "compensator"_a, "inputs"_a, "t"_a,
      "y_d"_a, "schedule_index"_a.none(), "schedule_angles"_a.none(), "dropout"_a.none(),
      "outer_loop"_a.none() = nb::none(), "shapes"_a.none() = nb::none(),
      "learned"_a.none() = nb::none());
  def_run(m, "bench_open_loop", [] {
    struct M {
      using argument_type = double;
      ts::OpenLoop operator()(double gain) const { return ts::OpenLoop{gain}; }
    };
    return M{};
  }());
  def_run(m, "bench_inverse", Maker<ts::BacklashInverseFeedforward,
                                          ts::FeedforwardLoop<ts::BacklashInverseFeedforward>>{});
  def_run(m, "bench_pi_inverse", Maker<ts::PrandtlIshlinskiiFeedforward,
                                             ts::FeedforwardLoop<ts::PrandtlIshlinskiiFeedforward>>{});
  def_run(m, "bench_curve_angle", Maker<ts::CurveAngleFeedforward, ts::CurveAngleLoop>{});
  def_run(m, "bench_model_inverse", Maker<ts::ModelInverse, ts::ModelInverseLoop>{});
  def_run(m, "bench_continuum", Maker<ts::ContinuumFeedforward,
                                            ts::FeedforwardLoop<ts::ContinuumFeedforward>>{});
  def_run(m, "bench_adaptive", Maker<ts::AdaptiveController, ts::AdaptiveLoop>{});
}

}  // namespace tsbind
