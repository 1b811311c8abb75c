// A plant behind a function table (tendonsheath/bench/erased_plant.hpp): the table calls the
// members the class has and the contract's defaults for the others, and the closed loop through
// the table equals the loop on the class itself, route changes, slack and status included.
#include <gtest/gtest.h>

#include <cmath>
#include <tendonsheath/bench/erased_plant.hpp>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {

struct Minimal {  // only the required members: the table supplies the defaults
  double y = 0.0;
  int resets = 0;
  void reset() noexcept {
    y = 0.0;
    ++resets;
  }
  double step(double input, double dt) noexcept { return y = 0.5 * input + dt; }
  double output() const noexcept { return y; }
};

template <class P>
ts::ErasedPlantLoop erase(P& p) {
  return ts::ErasedPlantLoop{ts::ErasedPlant{&ts::plant_table<P>(), &p}};
}

}  // namespace

TEST(ErasedPlant, CallsTheMembersTheClassHasAndDefaultsTheOthers) {
  Minimal m;
  auto e = erase(m);
  EXPECT_EQ(e.step(2.0, 0.25), 1.25);
  EXPECT_EQ(e.output(), 1.25);
  EXPECT_EQ(e.input(), 0.0);
  EXPECT_EQ(e.drive_reaction(), 0.0);
  EXPECT_FALSE(e.slack());
  EXPECT_EQ(e.status(), ts::Status::ok);
  EXPECT_EQ(e.n_node_angles(), 0u);
  e.reset();
  EXPECT_EQ(m.resets, 1);
  EXPECT_EQ(e.output(), 0.0);
  EXPECT_EQ(ts::plant_table<Minimal>().version, ts::kPlantTableVersion);

  ts::PullPullParams pp;
  pp.elements = 12;
  const auto route = ts::Route::uniform(1.0, 2.0);
  ts::PullPullPlant pair(pp, route, route);
  auto ep = erase(pair);
  EXPECT_EQ(ep.n_node_angles(), pair.n_node_angles());
  ep.step(0.0, 0.0);  // the first step sets the rest state
  ep.step(0.3, 1e-3);
  EXPECT_EQ(ep.input(), pair.input());
  EXPECT_EQ(ep.drive_reaction(), pair.drive_reaction());
  EXPECT_NE(ep.drive_reaction(), 0.0);
}

TEST(ErasedPlant, ClosedLoopEqualsTheTypedLoop) {
  ts::SingleTendonParams sp;
  sp.elements = 30;
  sp.load_force = 10.0;
  const auto r1 = ts::Route::uniform(1.0, 1.0), r2 = ts::Route::uniform(1.0, 4.0);
  const std::size_t n = 2000;
  std::vector<double> t(n), y_d(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = 1e-3 * k;
    y_d[k] = 2e-3 * std::sin(2 * 3.141592653589793 * 1.3 * t[k]);
  }
  ts::SingleTendonPlant probe(sp, r1);
  std::vector<double> angles(2 * probe.n_node_angles());
  probe.node_angles(r1, angles.data());
  probe.node_angles(r2, angles.data() + probe.n_node_angles());
  const std::size_t idx[2] = {0, n / 2};
  ts::RouteSchedule sched;
  sched.index = idx;
  sched.angles = angles.data();
  sched.count = 2;
  sched.width = probe.n_node_angles();
  struct Run {
    std::vector<double> out, cmd;
    std::vector<unsigned char> status, slack;
  };
  auto run = [&](auto& plant) {
    Run r{std::vector<double>(n), std::vector<double>(n), std::vector<unsigned char>(n),
          std::vector<unsigned char>(n)};
    ts::MotorParams mp;
    ts::Motor motor(mp);
    ts::OpenLoop loop{1.0};
    ts::ClosedLoopTrace trace;
    trace.output = r.out.data();
    trace.command = r.cmd.data();
    trace.status = r.status.data();
    trace.slack = r.slack.data();
    ts::run_closed_loop(plant, &motor, nullptr, loop, t.data(), y_d.data(), n, sched, {}, nullptr,
                        trace, "bench");
    return r;
  };
  ts::SingleTendonPlant typed_plant(sp, r1), erased_plant(sp, r1);
  const Run typed = run(typed_plant);
  auto view = erase(erased_plant);
  const Run erased = run(view);
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_EQ(erased.out[k], typed.out[k]) << k;
    ASSERT_EQ(erased.cmd[k], typed.cmd[k]) << k;
    ASSERT_EQ(erased.status[k], typed.status[k]) << k;
    ASSERT_EQ(erased.slack[k], typed.slack[k]) << k;
  }
  EXPECT_NE(typed.out[n / 2 - 1], typed.out[n - 1]);  // a real run
}
