// Physics plant: routes, the N-element plants, motor and sensor, and batch
// simulation with a compact route-change schedule (the loop runs in C++).
#include <nanobind/stl/optional.h>
#include <nanobind/stl/pair.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/tuple.h>
#include <nanobind/stl/vector.h>

#include <cstdint>
#include <optional>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"
#include "param_binding.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

using IntMatrix = nb::ndarray<nb::numpy, std::int8_t, nb::ndim<2>>;
using BoolArray = nb::ndarray<nb::numpy, bool, nb::ndim<1>>;

template <class T>
std::pair<nb::ndarray<nb::numpy, T>, T*> new_typed(std::initializer_list<std::size_t> shape) {
  std::size_t n = 1;
  for (auto s : shape) n *= s;
  T* data = new T[n > 0 ? n : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<T*>(p); });
  return {nb::ndarray<nb::numpy, T>(data, shape.size(), shape.begin(), owner), data};
}

OutArray copy_vector(const std::vector<double>& v) {
  auto [arr, p] = new_array(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) p[i] = v[i];
  return arr;
}

// Tensions as (rows x N) and slip states as (rows x (N-1)).
template <class Plant>
nb::ndarray<nb::numpy, double> tensions_of(const Plant& p, std::size_t rows) {
  auto [arr, d] = new_typed<double>({rows, p.elements()});
  p.tensions(d);
  return arr;
}
template <class Plant>
nb::ndarray<nb::numpy, std::int8_t> slip_of(const Plant& p, std::size_t rows) {
  std::vector<int> tmp(rows * (p.elements() - 1));
  p.slip_state(tmp.data());
  auto [arr, d] = new_typed<std::int8_t>({rows, p.elements() - 1});
  for (std::size_t i = 0; i < tmp.size(); ++i) d[i] = static_cast<std::int8_t>(tmp[i]);
  return arr;
}

template <class Plant>
void set_angles(Plant& p, InArray a) {
  ts::require(a.shape(0) == p.n_node_angles(), "set_node_angles",
              "expected " + std::to_string(p.n_node_angles()) + " node angles, got " +
                  std::to_string(a.shape(0)));
  for (std::size_t i = 0; i < a.shape(0); ++i)
    ts::require(std::isfinite(a.data()[i]) && a.data()[i] >= 0.0, "set_node_angles",
                "node angles must be finite and >= 0");
  p.set_node_angles(a.data());
}

// simulate(t, u, motor, sensor, schedule_index, schedule_angles)
//   -> (q_out, q_in, slack, measured, final tensions, nonconverged, q_motor, status flags)
template <class Plant>
nb::tuple simulate_plant(const Plant& self, std::optional<InArray> t, InArray u,
                         std::optional<ts::Motor> motor, std::optional<ts::Sensor> sensor,
                         std::optional<InIndex> sidx, std::optional<InMatrix> sang,
                         std::size_t rows, const char* name) {
  const std::size_t n = u.shape(0);
  if (t && t->shape(0) != n)
    throw std::invalid_argument(std::string(name) + ": t and the input have different lengths (" +
                                std::to_string(t->shape(0)) + " and " + std::to_string(n) + ")");
  std::vector<std::size_t> idx;
  const ts::RouteSchedule sched = to_schedule(sidx, sang, idx, name);
  Plant plant = self;
  auto [q_out, po] = new_array(n);
  auto [q_in, pi] = new_array(n);
  auto [slack, ps] = new_typed<bool>({n});
  auto [meas, pm] = new_array(n);
  auto [q_motor, pq] = new_array(n);
  auto [flags, pf] = new_bytes(n);
  std::vector<unsigned char> sl(n);
  ts::PlantTrace tr;
  tr.q_out = po;
  tr.q_in = pi;
  tr.slack = sl.data();
  tr.measured = pm;
  tr.q_motor = pq;
  tr.status = pf;
  ts::Motor* mp = motor ? &*motor : nullptr;
  ts::Sensor* sp = sensor ? &*sensor : nullptr;
  const double* tp = t ? t->data() : nullptr;
  const double* up = u.data();
  {
    nb::gil_scoped_release release;
    ts::simulate_plant(plant, mp, sp, tp, up, n, sched, tr, name);
  }
  for (std::size_t k = 0; k < n; ++k) ps[k] = sl[k] != 0;
  return nb::make_tuple(q_out, q_in, slack, meas, tensions_of(plant, rows),
                        plant.nonconverged(), q_motor, flags);
}

template <class Plant, class Cls>
void bind_common(Cls& cls, std::size_t rows, const char* name) {
  cls.def("reset", &Plant::reset)
      .def("step", &Plant::step, "x"_a, "dt"_a = 0.0)
      .def("output", &Plant::output)
      .def("input", &Plant::input)
      .def_prop_ro("elements", &Plant::elements)
      .def("tensions", [rows](const Plant& p) { return tensions_of(p, rows); })
      .def("slip_state", [rows](const Plant& p) { return slip_of(p, rows); })
      .def("slack", &Plant::slack)
      .def("min_tension", &Plant::min_tension)
      .def("nonconverged", &Plant::nonconverged)
      .def("time_dependent", &Plant::time_dependent)
      .def("input_clamped", [](const Plant& p) { return p.chain().input_clamped(); })
      .def("status", [](const Plant& p) { return static_cast<unsigned>(p.status()); })
      .def("last_converged", [](const Plant& p) { return p.chain().last_converged(); })
      .def("drive_reaction", &Plant::drive_reaction)
      .def_prop_ro("n_node_angles", &Plant::n_node_angles)
      .def("set_node_angles", [](Plant& p, InArray a) { set_angles(p, a); }, "angles"_a)
      .def(
          "simulate",
          [rows, name](const Plant& self, std::optional<InArray> t, InArray u,
                       std::optional<ts::Motor> motor, std::optional<ts::Sensor> sensor,
                       std::optional<InIndex> sidx, std::optional<InMatrix> sang) {
            return simulate_plant(self, t, u, motor, sensor, sidx, sang, rows, name);
          },
          "t"_a.none(), "u"_a, "motor"_a.none() = nb::none(), "sensor"_a.none() = nb::none(),
          "schedule_index"_a.none() = nb::none(), "schedule_angles"_a.none() = nb::none());
}

}  // namespace

namespace {

void bind_route(nb::module_& m) {
  // copyable (an immutable value): models that hold a plant (PlantModel) deep-copy, e.g. for
  // python-control's snapshots of an InverseFeedforward
  bind_copy(nb::class_<ts::Route>(m, "Route"))
      .def(nb::init<std::vector<double>, std::vector<double>>(), "s"_a, "theta"_a)
      .def_static("uniform", &ts::Route::uniform, "length"_a, "curve_angle"_a)
      .def_static("arcs", &ts::Route::arcs, "pieces"_a)
      .def_static("from_points",
                  [](InMatrix xyz) {
                    if (xyz.shape(1) != 3)
                      throw std::invalid_argument(
                          "Route.from_points: points must be K x 3 (got K x " +
                          std::to_string(xyz.shape(1)) + ")");
                    return ts::Route::from_points(xyz.data(), xyz.shape(0));
                  },
                  "xyz"_a)
      .def_static("from_curvature",
                  [](InArray s, InArray kappa) {
                    if (s.shape(0) != kappa.shape(0))
                      throw std::invalid_argument(
                          "Route.from_curvature: s and kappa have different lengths");
                    return ts::Route::from_curvature(s.data(), kappa.data(), s.shape(0));
                  },
                  "s"_a, "kappa"_a)
      .def_prop_ro("length", &ts::Route::length)
      .def_prop_ro("curve_angle", &ts::Route::curve_angle)
      .def("s_samples", [](const ts::Route& r) { return copy_vector(r.s()); })
      .def("theta_samples", [](const ts::Route& r) { return copy_vector(r.theta()); })
      .def("angle_at", &ts::Route::angle_at, "s"_a)
      .def(
          "angles_at",
          [](const ts::Route& r, InArray s) {
            auto [arr, p] = new_array(s.shape(0));
            for (std::size_t i = 0; i < s.shape(0); ++i) p[i] = r.angle_at(s.data()[i]);
            return arr;
          },
          "s"_a)
      .def(
          "element_angles",
          [](const ts::Route& r, std::size_t n) {
            ts::require(n >= 1, "Route.element_angles", "n must be >= 1");
            auto [arr, p] = new_array(n);
            r.element_angles(n, p);
            return arr;
          },
          "n"_a)
      .def(
          "node_angles",
          [](const ts::Route& r, std::size_t n) {
            ts::require(n >= 2, "Route.node_angles", "n must be >= 2");
            std::vector<double> work(n);
            auto [arr, p] = new_array(n - 1);
            r.node_angles(n, p, work.data());
            return arr;
          },
          "n"_a);
}

// The plants' parameter structs.
void bind_plant_params(nb::module_& m) {
  using CO = ts::ChainOptions;
  nb::class_<CO>(m, "ChainOptions")
      .def(nb::init<>())
      .def_rw("max_iterations", &CO::max_iterations)
      .def_rw("max_halvings", &CO::max_halvings)
      .def_rw("max_substeps", &CO::max_substeps)
      .def_rw("max_increment", &CO::max_increment)
      .def_rw("extra_iterations", &CO::extra_iterations)
      .def_rw("fast_path", &CO::fast_path);

  using SP = ts::SingleTendonParams;
  bind_params<SP>(m, "SingleTendonParams");

  using PP = ts::PullPullParams;
  bind_params<PP>(m, "PullPullParams");

  using CP = ts::ContinuumParams;
  bind_params<CP>(m, "ContinuumParams");
}

void bind_motor(nb::module_& m) {
  nb::enum_<ts::MotorKind>(m, "MotorKind")
      .value("Position", ts::MotorKind::Position)
      .value("Torque", ts::MotorKind::Torque);
  using MP = ts::MotorParams;
  bind_copy(bind_params<MP>(m, "MotorParams"));
  bind_copy(nb::class_<ts::Motor>(m, "Motor"))
      .def(nb::init<const MP&>(), "params"_a)
      .def_prop_ro("params", &ts::Motor::params)
      .def("reset", &ts::Motor::reset)
      .def("step", &ts::Motor::step, "u"_a, "dt"_a, "tau_ext"_a = 0.0)
      .def("position", &ts::Motor::position)
      .def("output", &ts::Motor::output)
      .def("clamped", &ts::Motor::clamped)
      .def("status", [](const ts::Motor& m) { return static_cast<unsigned>(m.status()); })
      .def("velocity", &ts::Motor::velocity)
      .def("integral", &ts::Motor::integral)
      .def("set_state", &ts::Motor::set_state, "q"_a, "v"_a, "z"_a = 0.0);
}

void bind_sensor(nb::module_& m) {
  using SeP = ts::SensorParams;
  bind_copy(bind_params<SeP>(m, "SensorParams"));
  bind_copy(nb::class_<ts::Sensor>(m, "Sensor"))
      .def(nb::init<const SeP&>(), "params"_a)
      .def_ro_static("MAX_HISTORY", &ts::Sensor::kMaxHistory)
      .def_prop_ro("params", &ts::Sensor::params)
      .def("status", [](const ts::Sensor& s) { return static_cast<unsigned>(s.status()); })
      .def("reset", &ts::Sensor::reset)
      .def("measure", &ts::Sensor::measure, "x"_a, "dt"_a = 0.0)
      .def(
          "measure_many",
          [](ts::Sensor& s, InArray x, std::optional<InArray> t, double dt) {
            const std::size_t n = x.shape(0);
            if (t && t->shape(0) != n)
              throw std::invalid_argument("Sensor.measure: t and x differ in length");
            auto [arr, p] = new_array(n);
            const double* tp = t ? t->data() : nullptr;
            for (std::size_t i = 0; i < n; ++i) {
              const double step = i == 0 ? dt : (tp ? tp[i] - tp[i - 1] : 0.0);
              p[i] = s.measure(x.data()[i], step);
            }
            return arr;
          },
          "x"_a, "t"_a = nb::none(), "dt"_a = 0.0);
}

// The single-tendon, pull-pull and continuum plants.
void bind_plants(nb::module_& m) {
  using SP = ts::SingleTendonParams;
  using PP = ts::PullPullParams;
  using CP = ts::ContinuumParams;
  nb::class_<ts::SingleTendonPlant> single(m, "SingleTendonPlant");
  bind_copy(single);  // copy.copy/deepcopy of a plant: an exact snapshot
  single.def(nb::init<const SP&, const ts::Route&>(), "params"_a, "route"_a)
      .def_prop_ro("params", &ts::SingleTendonPlant::params)
      .def_prop_ro("length", &ts::SingleTendonPlant::length)
      .def_prop_ro("curve_angle", &ts::SingleTendonPlant::curve_angle)
      .def("set_route", &ts::SingleTendonPlant::set_route, "route"_a)
      .def(
          "node_angles",
          [](ts::SingleTendonPlant& p, const ts::Route& r) {
            auto [arr, d] = new_array(p.n_node_angles());
            p.node_angles(r, d);
            return arr;
          },
          "route"_a);
  bind_common<ts::SingleTendonPlant>(single, 1, "SingleTendonPlant.simulate");

  nb::class_<ts::PullPullPlant> pp(m, "PullPullPlant");
  bind_copy(pp);  // a snapshot (PlantModel's python-control systems deep-copy it)
  pp.def(nb::init<const PP&, const ts::Route&, const ts::Route&>(), "params"_a, "route1"_a,
         "route2"_a)
      .def_prop_ro("params", &ts::PullPullPlant::params)
      .def_prop_ro("length1", &ts::PullPullPlant::length1)
      .def_prop_ro("length2", &ts::PullPullPlant::length2)
      .def_prop_ro("curve_angle1", &ts::PullPullPlant::curve_angle1)
      .def_prop_ro("curve_angle2", &ts::PullPullPlant::curve_angle2)
      .def("set_route",
           nb::overload_cast<const ts::Route&, const ts::Route&>(&ts::PullPullPlant::set_route),
           "route1"_a, "route2"_a)
      .def(
          "node_angles",
          [](const ts::PullPullPlant& p, const ts::Route& r1, const ts::Route& r2) {
            auto [arr, d] = new_array(p.n_node_angles());
            p.node_angles(r1, r2, d);
            return arr;
          },
          "route1"_a, "route2"_a);
  bind_common<ts::PullPullPlant>(pp, 2, "PullPullPlant.simulate");

  nb::class_<ts::ContinuumPlant, ts::PullPullPlant> cont(m, "ContinuumPlant");
  bind_copy(cont);  // its own copy, not the base's (no slicing)
  cont.def(nb::init<const CP&, const ts::Route&, const ts::Route&>(), "params"_a, "route1"_a,
           "route2"_a)
      .def_prop_ro("continuum_params", &ts::ContinuumPlant::continuum_params)
      .def("bending_angle", &ts::ContinuumPlant::bending_angle)
      .def("tendon_force", &ts::ContinuumPlant::tendon_force);
  bind_common<ts::ContinuumPlant>(cont, 2, "ContinuumPlant.simulate");
}

}  // namespace

void bind_plant(nb::module_& m) {
  bind_route(m);
  bind_plant_params(m);
  bind_motor(m);
  bind_sensor(m);
  bind_plants(m);
}

}  // namespace tsbind
