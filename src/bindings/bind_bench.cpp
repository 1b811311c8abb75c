// The closed-loop virtual bench: one call runs the whole loop in C++.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/tuple.h>

#include <optional>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

using InMask = nb::ndarray<const std::uint8_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

template <class Controller>
nb::tuple run(const ts::PullPullPlant& plant_in, std::optional<ts::Motor> motor,
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
  ts::PullPullPlant plant = plant_in;
  auto [output, po] = new_array(n);
  auto [measured, pm] = new_array(n);
  auto [command, pc] = new_array(n);
  auto [motor_pos, pq] = new_array(n);
  auto [status, pst] = new_bytes(n);
  std::vector<unsigned char> slack(n), fallback(n);
  ts::ClosedLoopTrace trace{po, pm, pc, pq, slack.data(), fallback.data(), pst};
  {
    nb::gil_scoped_release release;
    ts::run_closed_loop(plant, motor ? &*motor : nullptr, sensor ? &*sensor : nullptr, controller,
                        t.data(), y_d.data(), n, sched, shape_sched,
                        dropout ? dropout->data() : nullptr, trace, where);
  }
  auto [slack_arr, ps] = new_array(n);
  auto [fallback_arr, pf] = new_array(n);
  for (std::size_t k = 0; k < n; ++k) {
    ps[k] = slack[k];
    pf[k] = fallback[k];
  }
  return nb::make_tuple(output, measured, command, motor_pos, slack_arr, fallback_arr, status);
}

template <class Make>
void def_run(nb::module_& m, const char* name, Make make) {
  m.def(
      name,
      [make](const ts::PullPullPlant& plant, std::optional<ts::Motor> motor,
             std::optional<ts::Sensor> sensor, const typename Make::argument_type& c, InArray t,
             InArray y_d, std::optional<InIndex> sidx, std::optional<InMatrix> sang,
             std::optional<InMatrix> shapes, std::optional<InMask> dropout) {
        return run(plant, motor, sensor, make(c), t, y_d, sidx, sang, shapes, dropout);
      },
      "plant"_a, "motor"_a.none(), "sensor"_a.none(), "controller"_a, "t"_a, "y_d"_a,
      "schedule_index"_a.none(), "schedule_angles"_a.none(), "shapes"_a.none(),
      "dropout"_a.none());
}

template <class Arg, class Loop>
struct Maker {
  using argument_type = Arg;
  Loop operator()(const Arg& a) const { return Loop{a}; }
};

}  // namespace

void bind_bench(nb::module_& m) {
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
  def_run(m, "bench_continuum", Maker<ts::ContinuumFeedforward,
                                            ts::FeedforwardLoop<ts::ContinuumFeedforward>>{});
  def_run(m, "bench_adaptive", Maker<ts::AdaptiveController, ts::AdaptiveLoop>{});
}

}  // namespace tsbind
