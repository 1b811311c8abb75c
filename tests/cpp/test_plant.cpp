// Physics plant: closed forms of spec A (capstan, A7 offsets), routes,
// validation, and the real-time properties of step().
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

double drive(ts::PullPullPlant& p, double from, double to, double step) {
  const int n = static_cast<int>(std::ceil(std::fabs(to - from) / step));
  double y = 0.0;
  for (int i = 1; i <= n; ++i) y = p.step(from + (to - from) * i / n);
  return y;
}

std::string thrown_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(Route, ElementAnglesSumToTotal) {
  const auto r = ts::Route::arcs({{0.6, 0.0}, {0.4, kPi / 2}, {0.2, -1.0}});
  EXPECT_DOUBLE_EQ(r.length(), 1.2);
  EXPECT_DOUBLE_EQ(r.curve_angle(), kPi / 2 + 1.0);
  for (std::size_t n : {2u, 3u, 7u, 100u}) {
    std::vector<double> el(n), nodes(n - 1), work(n);
    r.element_angles(n, el.data());
    r.node_angles(n, nodes.data(), work.data());
    double se = 0, sn = 0;
    for (double a : el) se += a;
    for (double a : nodes) sn += a;
    EXPECT_NEAR(se, r.curve_angle(), 1e-12);
    EXPECT_NEAR(sn, r.curve_angle(), 1e-12);
  }
  EXPECT_NEAR(r.angle_at(0.3), 0.0, 1e-15);
  EXPECT_NEAR(r.angle_at(0.8), kPi / 4, 1e-12);
}

TEST(Route, PolylineTurningAngles) {
  // a square corner, then a 45 degree turn out of plane
  const double xyz[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 2, 1};
  const auto r = ts::Route::from_points(xyz, 4);
  EXPECT_NEAR(r.length(), 2.0 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(r.curve_angle(), kPi / 2 + kPi / 4, 1e-12);
  EXPECT_NEAR(r.angle_at(0.5), 0.0, 1e-15);
  EXPECT_NEAR(r.angle_at(1.5), kPi / 2, 1e-12);
}

TEST(Route, RejectsBadInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double xyz[] = {0, 0, 0, nan, 0, 0};
  EXPECT_NE(thrown_message([&] { ts::Route::from_points(xyz, 2); }).find("not finite"),
            std::string::npos);
  EXPECT_NE(thrown_message([] { ts::Route::uniform(-1.0, 1.0); }).find("length must be > 0"),
            std::string::npos);
}

TEST(SingleTendon, CapstanRatioInFullSlip) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int draw = 0; draw < 20; ++draw) {
    ts::SingleTendonParams p;
    p.friction = 0.05 + 0.15 * U(rng);
    p.stiffness = 5e3 + 4.5e4 * U(rng);
    p.load_force = 2.0 + 20.0 * U(rng);
    p.elements = 50;
    const double L = 0.5 + 1.5 * U(rng);
    const double theta = 4 * kPi * U(rng);
    const auto route = draw % 2 ? ts::Route::uniform(L, theta)
                                : ts::Route::arcs({{0.9 * L, theta / 3}, {0.1 * L, 2 * theta / 3}});
    ts::SingleTendonPlant plant(p, route);
    const double travel = 4 * p.load_force * L / p.stiffness * (1 + p.friction * theta);
    for (int k = 1; k <= 400; ++k) plant.step(travel * k / 400.0);
    std::vector<double> T(p.elements);
    plant.tensions(T.data());
    // measured over the 20 draws: worst 1.1e-13 (ratio) and 6.5e-14 relative (distal
    // tension), round-off; 1e-12 is 9x and 15x above
    EXPECT_NEAR(T.back() / T.front(), std::exp(-p.friction * theta), 1e-12) << "draw " << draw;
    EXPECT_NEAR(T.back(), p.load_force, 1e-12 * p.load_force);
  }
}

TEST(PullPull, SteadyOffsetsMatchA7) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int draw = 0; draw < 20; ++draw) {
    ts::PullPullParams p;
    p.friction = 0.05 + 0.15 * U(rng);
    p.stiffness = 5e3 + 4.5e4 * U(rng);
    p.pretension = 2.0 + 38.0 * U(rng);
    p.elements = 200;
    const double FL = (U(rng) - 0.5) * 0.8 * p.pretension;
    p.load_torque = FL * p.distal_radius;
    const double L = 0.5 + 1.5 * U(rng);
    const double theta = 0.1 + 4 * kPi * U(rng);
    ts::PullPullPlant plant(p, ts::Route::uniform(L, theta));
    const double a = p.friction * theta;
    const double c = L / p.stiffness * std::tanh(a / 2);
    const double eb = p.pretension * c, eL = FL * c / a;
    const double span = 6 * (eb + std::fabs(eL)) / p.proximal_radius;
    const double stepq = eb / 40 / p.proximal_radius;
    // measured over the 20 draws (200 elements): worst 5.6e-6 (forward) and 7.6e-6
    // (backward) relative, the discretisation error; 3e-5 is 5x and 4x above
    double q = drive(plant, 0.0, span, stepq) * p.distal_radius;
    EXPECT_NEAR((span * p.proximal_radius - q) / (eb + eL), 1.0, 3e-5) << "forward, draw " << draw;
    q = drive(plant, span, -span, stepq) * p.distal_radius;
    EXPECT_NEAR((-span * p.proximal_radius - q) / (-eb + eL), 1.0, 3e-5) << "backward, draw " << draw;
    EXPECT_FALSE(plant.slack());
    EXPECT_EQ(plant.nonconverged(), 0);
  }
}

TEST(PullPull, FastPathEqualsPlainActiveSet) {
  ts::PullPullParams p;
  p.elements = 40;
  p.load_stiffness = 2e-3;
  ts::PullPullParams plain = p;
  plain.options.fast_path = false;
  const auto route = ts::Route::arcs({{0.8, 1.0}, {0.4, 3.0}});
  ts::PullPullPlant a(p, route), b(plain, route);
  for (int k = 0; k < 4000; ++k) {
    const double q = 0.4 * std::sin(2 * kPi * k / 1000.0) + 0.1 * std::sin(2 * kPi * k / 310.0);
    if (k == 2500) {
      a.set_route(ts::Route::uniform(1.2, 1.0));
      b.set_route(ts::Route::uniform(1.2, 1.0));
    }
    ASSERT_NEAR(a.step(q), b.step(q), 1e-10) << "sample " << k;
  }
}

TEST(PullPull, StepIsNoexceptAndNeverNaN) {
  ts::PullPullParams p;
  p.elements = 20;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 2 * kPi));
  static_assert(noexcept(plant.step(0.0, 0.0)), "step must be noexcept");
  std::mt19937 rng(3);
  std::normal_distribution<double> G(0.0, 1.0);
  double last = plant.step(0.0);
  for (int k = 0; k < 2000; ++k) {
    const double q = k % 97 == 0 ? std::numeric_limits<double>::quiet_NaN() : 3.0 * G(rng);
    const double y = plant.step(q, 1e-3);
    ASSERT_TRUE(std::isfinite(y));
    if (!std::isfinite(q)) {
      EXPECT_EQ(y, last);
    }
    last = y;
  }
}

TEST(PullPull, SlackIsReported) {
  ts::PullPullParams p;
  p.elements = 20;
  p.pretension = 2.0;
  p.load_torque = 10.0 * p.distal_radius;  // F_L far above the no-slack bound
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, kPi));
  for (int k = 0; k < 200; ++k) plant.step(0.01 * k);
  EXPECT_TRUE(plant.slack());
  EXPECT_LE(plant.min_tension(), 0.0);
}

TEST(PullPull, ValidationNamesTheParameter) {
  ts::PullPullParams p;
  p.friction = -0.1;
  EXPECT_NE(thrown_message([&] { ts::PullPullPlant(p, ts::Route::uniform(1, 1)); })
                .find("friction must be >= 0"),
            std::string::npos);
  p.friction = 0.1;
  p.elements = 1;
  EXPECT_NE(thrown_message([&] { ts::PullPullPlant(p, ts::Route::uniform(1, 1)); })
                .find("elements must be >= 2"),
            std::string::npos);
  p.elements = 10;
  p.stiffness = 0;
  EXPECT_NE(thrown_message([&] { ts::PullPullPlant(p, ts::Route::uniform(1, 1)); })
                .find("stiffness must be > 0"),
            std::string::npos);
}

TEST(Continuum, SpringSlopeAndForce) {
  ts::ContinuumParams c;
  c.elements = 100;
  ts::ContinuumPlant plant(c, ts::Route::uniform(1.0, kPi));
  const double a = c.friction * kPi;
  const double CL = 1.0 / c.stiffness * std::tanh(a / 2) / a;
  const double k = c.bending_stiffness / (c.tendon_offset * c.tendon_offset * c.backbone_length);
  const double slope = 1.0 / (1.0 + k * CL);
  drive(static_cast<ts::PullPullPlant&>(plant), 0.0, 0.5, 1e-3);
  const double y1 = plant.bending_angle();
  drive(static_cast<ts::PullPullPlant&>(plant), 0.5, 0.8, 1e-3);
  const double y2 = plant.bending_angle();
  const double measured = (y2 - y1) * c.tendon_offset / (0.3 * c.proximal_radius);
  EXPECT_NEAR(measured / slope, 1.0, 2e-6);  // measured 2.9e-7; 7x above
  EXPECT_NEAR(plant.tendon_force(), y2 / c.backbone_length * c.bending_stiffness / c.tendon_offset,
              1e-12);
}

TEST(MotorSensor, PositionLagSettlesAndRespectsLimits) {
  ts::MotorParams m;
  m.bandwidth_hz = 2.0;
  m.max_speed = 1.0;
  ts::Motor motor(m);
  motor.step(0.0, 0.0);
  double q = 0;
  for (int k = 0; k < 5000; ++k) {
    q = motor.step(1.0, 1e-3);
    ASSERT_LE(std::fabs(motor.velocity()), 1.0 + 1e-12);
  }
  EXPECT_NEAR(q, 1.0, 1e-6);
  ts::Sensor s1({0.01, 0.0, 1}), s2({0.0, 0.1, 5}), s3({0.0, 0.1, 5});
  EXPECT_DOUBLE_EQ(s1.measure(0.123), 0.12);
  for (int k = 0; k < 10; ++k) EXPECT_EQ(s2.measure(1.0), s3.measure(1.0));
}
