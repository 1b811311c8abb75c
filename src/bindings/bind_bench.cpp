// The closed-loop virtual bench: one call (bench_run) runs the whole loop in C++, over any
// controller (AnyController) and any plant (the erased plant of bench_plant.hpp: a shipped
// engine, a compiled user plant or a Python one).
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

PythonLoop python_loop(nb::handle compensator, const std::vector<int>& inputs) {
  if (inputs.empty() || inputs.size() > 3)
    throw nb::value_error("bench_run: a Python compensator takes 1 to 3 step inputs");
  for (int i : inputs)
    if (i < 0 || i > 2) throw nb::value_error("bench_run: step input codes are 0, 1, 2");
  nb::object self = nb::borrow<nb::object>(compensator);
  nb::object status = nb::none();
  if (nb::hasattr(self, "status") && PyCallable_Check(self.attr("status").ptr()))
    status = self.attr("status");
  return PythonLoop{self, self.attr("step"), status, inputs,
                    nb::cast<std::string>(nb::type_name(self.type()))};
}

// The variant of AnyController: the uncompensated gain, the loop of each compensator of the list
// (compensators/compensator_list.hpp: Compensators), a compiled one's and a Python one's.
template <class L>
struct LoopVariant;
template <class... Cs>
struct LoopVariant<ts::TypeList<Cs...>> {
  using type = std::variant<ts::OpenLoop, ts::loop_of_t<Cs>..., ts::ErasedLoop, PythonLoop>;
};

// Every controller bench.run runs, as one type: the uncompensated gain, a shipped compensator
// (a copy, stepped in C++ without the GIL), a user's compiled one (its function table) or a
// Python one (its step called each cycle, the GIL held). One closed loop is compiled for it,
// and one for it inside each of the encoder loop, the tip loop and the learned table.
class AnyController {
 public:
  using Loop = LoopVariant<ts::Compensators>::type;
  explicit AnyController(Loop loop) : loop_(std::move(loop)) {}
  bool needs_gil() const noexcept { return std::holds_alternative<PythonLoop>(loop_); }
  void reset() { std::visit([](auto& c) { c.reset(); }, loop_); }
  void on_shape(const ts::ShapeIntegrals& s) {
    std::visit([&](auto& c) { c.on_shape(s); }, loop_);
  }
  bool in_fallback() const {
    return std::visit([](const auto& c) { return c.in_fallback(); }, loop_);
  }
  ts::Status status() const {
    return std::visit([](const auto& c) { return c.status(); }, loop_);
  }
  double command(double y_d, double measured, double motor, double dt) {
    return std::visit([&](auto& c) { return c.command(y_d, measured, motor, dt); }, loop_);
  }

 private:
  Loop loop_;
};

// The first compensator class C of the list (compensators/compensator_list.hpp: Compensators)
// that `c` is an instance of (a shipped Python compensator is one: it subclasses it), in C's loop.
std::optional<AnyController> shipped_loop(nb::handle c) {
  std::optional<AnyController> out;
  ts::any_type(ts::Compensators{}, [&](auto tag) {
    using C = typename decltype(tag)::type;
    if (!nb::isinstance<C>(c)) return false;
    out.emplace(ts::loop_of_t<C>{nb::cast<const C&>(c)});
    return true;
  });
  return out;
}

// The controller: None (uncompensated: gain * y_d), a shipped compensator, a capsule from a
// user's compiled one (_tendonsheath_compensator()), or any object with reset() and step() whose
// step takes the signals `inputs` (0: y_d, 1: measured, 2: motor) and dt.
AnyController any_controller(nb::handle c, double gain, const std::vector<int>& inputs) {
  if (c.is_none()) return AnyController{ts::OpenLoop{gain}};
  if (std::optional<AnyController> out = shipped_loop(c)) return std::move(*out);
  if (PyCapsule_CheckExact(c.ptr())) return AnyController{erased_loop(c)};
  return AnyController{python_loop(c, inputs)};
}

bool needs_gil(const AnyController& c) { return c.needs_gil(); }
template <class Inner>
bool needs_gil(const ts::WithEncoderLoop<Inner>& c) { return needs_gil(c.inner); }
template <class Inner>
bool needs_gil(const ts::WithLearnedCorrection<Inner>& c) { return needs_gil(c.inner); }
template <class Inner>
bool needs_gil(const ts::WithTipLoop<Inner>& c) { return needs_gil(c.inner); }

template <class Controller>
nb::tuple run_loop(BenchPlant& plant, std::optional<ts::Motor> motor,
              std::optional<ts::Sensor> sensor, std::optional<ts::Sensor> encoder, Controller controller, InArray t, InArray y_d,
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
                        dropout ? dropout->data() : nullptr, trace, where,
                        encoder ? &*encoder : nullptr);
  };
  if (needs_gil(controller) || plant.needs_gil) {
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
                     std::optional<ts::Sensor> sensor, std::optional<ts::Sensor> encoder, Controller controller, InArray t,
                     InArray y_d, std::optional<InIndex> sidx, std::optional<InMatrix> sang,
                     std::optional<InMatrix> shapes, std::optional<InMask> dropout,
                     std::optional<OuterLoop> outer_loop) {
  if (outer_loop) {
    if (const auto* e = std::get_if<ts::EncoderLoop>(&*outer_loop))
      return run_loop(plant, motor, sensor, encoder,
                      ts::WithEncoderLoop<Controller>{std::move(controller), *e}, t, y_d, sidx,
                      sang, shapes, dropout);
    return run_loop(plant, motor, sensor, encoder,
                    ts::WithTipLoop<Controller>{std::move(controller),
                                                std::get<ts::TipLoop>(*outer_loop)},
                    t, y_d, sidx, sang, shapes, dropout);
  }
  return run_loop(plant, motor, sensor, encoder, std::move(controller), t, y_d, sidx, sang, shapes, dropout);
}

// The loop, with a learned correction table added to the controller's command (inside the
// encoder or tip loop, whose target it corrects) when one is given.
template <class Controller>
nb::tuple run(BenchPlant& plant, std::optional<ts::Motor> motor,
              std::optional<ts::Sensor> sensor, std::optional<ts::Sensor> encoder, Controller controller, InArray t, InArray y_d,
              std::optional<InIndex> sidx, std::optional<InMatrix> sang,
              std::optional<InMatrix> shapes, std::optional<InMask> dropout,
              std::optional<OuterLoop> outer_loop, std::optional<ts::LearnedCorrection> learned) {
  if (learned)
    return run_looped(plant, motor, sensor, encoder,
                      ts::WithLearnedCorrection<Controller>{std::move(controller), *learned}, t,
                      y_d, sidx, sang, shapes, dropout, outer_loop);
  return run_looped(plant, motor, sensor, encoder, std::move(controller), t, y_d, sidx, sang, shapes,
                    dropout, outer_loop);
}

}  // namespace

void bind_bench(nb::module_& m) {
  m.def(
      "bench_run",
      [](nb::handle plant, std::optional<ts::Motor> motor, std::optional<ts::Sensor> sensor,
         nb::handle controller, InArray t, InArray y_d, std::optional<InIndex> sidx,
         std::optional<InMatrix> sang, std::optional<InMatrix> shapes,
         std::optional<InMask> dropout, std::optional<OuterLoop> outer_loop,
         std::optional<ts::LearnedCorrection> learned, double gain, std::vector<int> inputs,
         std::optional<ts::Sensor> encoder) {
        BenchPlant bench_plant(plant);
        return run(bench_plant, motor, sensor, encoder, any_controller(controller, gain, inputs), t, y_d,
                   sidx, sang, shapes, dropout, outer_loop, learned);
      },
      "plant"_a, "motor"_a.none(), "sensor"_a.none(), "controller"_a.none(), "t"_a, "y_d"_a,
      "schedule_index"_a.none() = nb::none(), "schedule_angles"_a.none() = nb::none(),
      "shapes"_a.none() = nb::none(), "dropout"_a.none() = nb::none(),
      "outer_loop"_a.none() = nb::none(), "learned"_a.none() = nb::none(), "gain"_a = 1.0,
      "inputs"_a = std::vector<int>{}, "encoder"_a.none() = nb::none(),
      "The closed loop controller -> motor -> plant -> sensor in C++ (bench.run): any plant,\n"
      "and a controller that is None (uncompensated: gain * y_d), a shipped compensator, a\n"
      "capsule of a compiled one, or a Python object whose step takes `inputs` and dt; the\n"
      "encoder (a Sensor, or None: exact) reads the motor shaft for the controller and the record.\n"
      "Returns (output, measured, command, motor, slack, fallback, status).");
}

}  // namespace tsbind
