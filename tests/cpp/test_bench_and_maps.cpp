// The closed-loop bench runner, the polynomial map and the generalized PI inverse.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

static_assert(noexcept(std::declval<ts::GeneralizedPrandtlIshlinskii&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::GeneralizedPrandtlIshlinskiiInverse&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::Polynomial&>().step(0.0, 0.0)));

TEST(ClosedLoop, FeedforwardLoopEqualsOpenLoopSimulation) {
  ts::PullPullParams pp;
  pp.elements = 20;
  pp.stiffness = 5e3;
  pp.pretension = 20.0;
  const auto route = ts::Route::uniform(1.2, 3.0);
  ts::MotorParams mp;
  mp.bandwidth_hz = 30.0;
  const std::size_t n = 4000;
  std::vector<double> t(n), y_d(n), u(n), open(n), closed(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = 1e-3 * k;
    y_d[k] = 0.6 * std::sin(2 * 3.141592653589793 * 0.5 * t[k]);
  }
  ts::BacklashInverseParams ip;
  ip.B_r = ip.B_l = 0.02;
  ts::BacklashInverseFeedforward ff(ip);
  for (std::size_t k = 0; k < n; ++k) u[k] = ff.step(y_d[k], k ? t[k] - t[k - 1] : 0.0);

  ts::PullPullPlant plant(pp, route, route);
  ts::Motor motor(mp);
  ts::PlantTrace open_trace;
  open_trace.q_out = open.data();
  ts::simulate_plant(plant, &motor, nullptr, t.data(), u.data(), n, {}, open_trace, "open");

  ts::PullPullPlant plant2(pp, route, route);
  ts::Motor motor2(mp);
  ts::FeedforwardLoop<ts::BacklashInverseFeedforward> loop{ts::BacklashInverseFeedforward(ip)};
  ts::ClosedLoopTrace trace;
  trace.output = closed.data();
  ts::run_closed_loop(plant2, &motor2, nullptr, loop, t.data(), y_d.data(), n, {}, {}, nullptr,
                      trace, "closed");
  for (std::size_t k = 0; k < n; ++k) ASSERT_EQ(open[k], closed[k]) << k;
}

TEST(ClosedLoop, RejectsBadInput) {
  ts::PullPullParams pp;
  pp.elements = 10;
  const auto route = ts::Route::uniform(1.0, 1.0);
  ts::PullPullPlant plant(pp, route, route);
  ts::OpenLoop loop;
  std::vector<double> t{0.0, 1e-3, 1e-3}, y{0.0, 0.1, 0.2}, out(3);
  ts::ClosedLoopTrace trace;
  trace.output = out.data();
  EXPECT_THROW(ts::run_closed_loop(plant, nullptr, nullptr, loop, t.data(), y.data(), 3, {}, {},
                                   nullptr, trace, "bench"),
               std::invalid_argument);
}

TEST(Polynomial, OddAndFullForms) {
  ts::PolynomialParams p;
  p.coefficients = {0.5, -0.2, 0.1};
  ts::Polynomial full(p);
  p.odd = true;
  ts::Polynomial odd(p);
  for (double u = -2.0; u <= 2.0; u += 0.25) {
    EXPECT_NEAR(full.step(u), 0.5 - 0.2 * u + 0.1 * u * u, 1e-14);
    EXPECT_NEAR(odd.step(u), 0.5 * u - 0.2 * u * u * u + 0.1 * std::pow(u, 5), 1e-12);
  }
  EXPECT_EQ(odd.degree(), 5u);
}

TEST(GeneralizedPrandtlIshlinskii, InverseIsExactOverRandomOperators) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 0.05);
  for (int trial = 0; trial < 20; ++trial) {
    ts::GeneralizedPrandtlIshlinskiiParams p;
    p.rising = {0.8 + u(rng), 0.5 + 2.0 * u(rng), 0.4 * u(rng) - 0.2, 0.4 * u(rng) - 0.2};
    p.falling = {0.8 + u(rng), 0.5 + 2.0 * u(rng), 0.4 * u(rng) - 0.2, 0.4 * u(rng) - 0.2};
    p.thresholds = {0.0, 0.05 + 0.1 * u(rng), 0.2 + 0.1 * u(rng)};
    p.weights = {0.3 + u(rng), 0.4 * u(rng), 0.4 * u(rng)};
    ts::GeneralizedPrandtlIshlinskii fwd(p);
    ts::GeneralizedPrandtlIshlinskiiInverse inv(p);
    double x = 0.0;
    for (int k = 0; k < 2000; ++k) {
      x = std::fmin(0.8, std::fmax(-0.8, x + g(rng)));
      ASSERT_NEAR(inv.step(fwd.step(x)), x, 1e-9) << "trial " << trial << " step " << k;
    }
  }
}
