// A compensator behind a function table (tendonsheath/bench/erased_compensator.hpp): the table
// calls the step the class has (1, 2 or 3 signals before dt), reports its status and fallback
// when it has them, and the closed loop through the table equals the loop on the class itself.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tendonsheath/bench/erased_compensator.hpp>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {

struct Feedforward {  // remembers its inputs, so the test sees which step the table called
  double last = 0.0;
  void reset() noexcept { last = 0.0; }
  double step(double r, double dt) noexcept { return last = 2.0 * r + dt; }
};

struct Feedback {
  int resets = 0;
  void reset() noexcept { ++resets; }
  double step(double r, double y, double dt) noexcept { return r - 0.5 * y + 10.0 * dt; }
  ts::Status status() const noexcept { return ts::Status::saturated; }
};

struct WithMotor {
  bool fallback = true;
  void reset() noexcept {}
  double step(double r, double y, double q, double dt) noexcept { return r + y + 3.0 * q + dt; }
  bool in_fallback() const noexcept { return fallback; }
};

template <class C>
ts::ErasedLoop erase(C& c) {
  return ts::ErasedLoop{ts::ErasedCompensator{&ts::compensator_table<C>(), &c}};
}

}  // namespace

static_assert(ts::compensator_step_inputs<Feedforward>() == 1);
static_assert(ts::compensator_step_inputs<Feedback>() == 2);
static_assert(ts::compensator_step_inputs<WithMotor>() == 3);

TEST(ErasedCompensator, CallsTheStepTheClassHas) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  Feedforward ff;
  Feedback fb;
  WithMotor wm;
  auto a = erase(ff), b = erase(fb), c = erase(wm);
  for (int i = 0; i < 1000; ++i) {
    const double r = u(rng), y = u(rng), q = u(rng), dt = std::abs(u(rng)) * 1e-3;
    EXPECT_EQ(a.command(r, y, q, dt), 2.0 * r + dt);
    EXPECT_EQ(b.command(r, y, q, dt), r - 0.5 * y + 10.0 * dt);
    EXPECT_EQ(c.command(r, y, q, dt), r + y + 3.0 * q + dt);
  }
  b.reset();
  EXPECT_EQ(fb.resets, 1);
  EXPECT_EQ(a.status(), ts::Status::ok);
  EXPECT_EQ(b.status(), ts::Status::saturated);
  EXPECT_FALSE(a.in_fallback());
  EXPECT_TRUE(c.in_fallback());
  wm.fallback = false;
  EXPECT_FALSE(c.in_fallback());
  EXPECT_EQ(ts::compensator_table<Feedback>().version, ts::kCompensatorTableVersion);
}

TEST(ErasedCompensator, ClosedLoopEqualsTheTypedLoop) {
  ts::PullPullParams pp;
  pp.elements = 20;
  pp.stiffness = 5e3;
  pp.pretension = 20.0;
  const auto route = ts::Route::uniform(1.2, 3.0);
  ts::BacklashInverseParams ip;
  ip.B_r = 0.03;
  ip.B_l = 0.02;
  const std::size_t n = 3000;
  std::vector<double> t(n), y_d(n), typed(n), erased(n), ct(n), ce(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = 1e-3 * k;
    y_d[k] = 0.6 * std::sin(2 * 3.141592653589793 * 0.7 * t[k]);
  }
  auto run = [&](auto& loop, std::vector<double>& out, std::vector<double>& cmd) {
    ts::PullPullPlant plant(pp, route, route);
    ts::MotorParams mp;
    ts::Motor motor(mp);
    ts::ClosedLoopTrace trace;
    trace.output = out.data();
    trace.command = cmd.data();
    ts::run_closed_loop(plant, &motor, nullptr, loop, t.data(), y_d.data(), n, {}, {}, nullptr,
                        trace, "bench");
  };
  ts::FeedforwardLoop<ts::BacklashInverseFeedforward> loop{ts::BacklashInverseFeedforward(ip)};
  run(loop, typed, ct);
  ts::BacklashInverseFeedforward ff(ip);
  auto erased_loop = erase(ff);
  run(erased_loop, erased, ce);
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_EQ(ce[k], ct[k]) << k;
    ASSERT_EQ(erased[k], typed[k]) << k;
  }
}
