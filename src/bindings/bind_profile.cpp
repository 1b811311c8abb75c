// Per-step cost of a plant for benchmarks/plant.py: each step timed alone (thread CPU time
// and wall time) with its solve count and status, the loop in C++ on a copy of the plant.
#include <nanobind/stl/optional.h>
#include <nanobind/stl/tuple.h>

#include <chrono>
#include <ctime>
#include <optional>
#include <tendonsheath/tendonsheath.hpp>

#include "bindings.hpp"

namespace tsbind {
namespace ts = tendonsheath;
using namespace nb::literals;

namespace {

using IntArray = nb::ndarray<nb::numpy, std::int64_t, nb::ndim<1>>;

std::pair<IntArray, std::int64_t*> new_int_array(std::size_t n) {
  auto* data = new std::int64_t[n > 0 ? n : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<std::int64_t*>(p); });
  return {IntArray(data, {n}, owner), data};
}

std::int64_t thread_cpu_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<std::int64_t>(t.tv_sec) * 1000000000 + t.tv_nsec;
}

// -> (cpu_ns, wall_ns, solves, status) per step
template <class Plant>
nb::tuple profile_steps(const Plant& self, InArray u, double dt, std::optional<InIndex> sidx,
                        std::optional<InMatrix> sang) {
  const std::size_t n = u.shape(0);
  std::vector<std::size_t> idx;
  const ts::RouteSchedule sched = to_schedule(sidx, sang, idx, "profile_steps");
  ts::check_schedule(self, sched, n, "profile_steps");
  Plant plant = self;
  auto [cpu, pc] = new_int_array(n);
  auto [wall, pw] = new_int_array(n);
  auto [solves, ps] = new_int_array(n);
  auto [status, pst] = new_int_array(n);
  {
    nb::gil_scoped_release release;
    std::size_t next = 0;
    for (std::size_t k = 0; k < n; ++k) {
      while (next < sched.count && sched.index[next] == k) {
        plant.set_node_angles(sched.angles + next * sched.width);
        ++next;
      }
      const auto w0 = std::chrono::steady_clock::now();
      const std::int64_t c0 = thread_cpu_ns();
      plant.step(u.data()[k], dt);
      const std::int64_t c1 = thread_cpu_ns();
      const auto w1 = std::chrono::steady_clock::now();
      pc[k] = c1 - c0;
      pw[k] = std::chrono::duration_cast<std::chrono::nanoseconds>(w1 - w0).count();
      ps[k] = plant.chain().last_solves();
      pst[k] = static_cast<std::int64_t>(plant.status());
    }
  }
  return nb::make_tuple(cpu, wall, solves, status);
}

template <class Plant, class Cls>
void bind_work(Cls& cls) {
  cls.def("last_solves", [](const Plant& p) { return p.chain().last_solves(); })
      .def("max_solves", [](const Plant& p) { return p.chain().max_solves(); })
      .def("profile_steps", &profile_steps<Plant>, "u"_a, "dt"_a,
           "schedule_index"_a.none() = nb::none(), "schedule_angles"_a.none() = nb::none());
}

}  // namespace

// Adds to the plant classes bind_plant() registered: last_solves(), max_solves() (the hard
// work bound of a step) and profile_steps().
void bind_profile(nb::module_& m) {
  auto single = nb::borrow<nb::class_<ts::SingleTendonPlant>>(m.attr("SingleTendonPlant"));
  auto pair = nb::borrow<nb::class_<ts::PullPullPlant>>(m.attr("PullPullPlant"));
  auto continuum = nb::borrow<nb::class_<ts::ContinuumPlant>>(m.attr("ContinuumPlant"));
  bind_work<ts::SingleTendonPlant>(single);
  bind_work<ts::PullPullPlant>(pair);
  bind_work<ts::ContinuumPlant>(continuum);
}

}  // namespace tsbind
