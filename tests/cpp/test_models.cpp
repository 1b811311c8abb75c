// Hysteresis models of the real-time core: closed-form behaviour and the
// real-time contract (noexcept, no NaN for finite input).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <tendonsheath/tendonsheath.hpp>
#include <type_traits>
#include <vector>

namespace ts = tendonsheath;

static_assert(noexcept(std::declval<ts::Backlash&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::BoucWenBacklash&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::BoucWen&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::HystereticOscillator&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::PrandtlIshlinskii&>().step(0.0, 0.0)));
static_assert(noexcept(std::declval<ts::PrandtlIshlinskiiInverse&>().step(0.0, 0.0)));

TEST(Backlash, BranchesAndDeadZoneAreExact) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> slope(0.5, 1.5), width(0.0, 0.5);
  for (int trial = 0; trial < 50; ++trial) {
    ts::BacklashParams p{slope(rng), slope(rng), width(rng), width(rng)};
    ts::Backlash b(p);
    b.step(0.0);
    // Peak below the point where unequal branches would cross.
    double peak = 3.0;
    if (p.c_r > p.c_l) peak = std::fmin(peak, 0.5 * (p.c_l * p.B_l + p.c_r * p.B_r) / (p.c_r - p.c_l));
    // Rising far past the band: on the right branch.
    for (double x = 0.0; x < peak; x += 0.01) b.step(x);
    b.step(peak);
    EXPECT_NEAR(b.output(), p.c_r * (peak - p.B_r), 1e-12);
    const double held = b.output();
    // Falling inside the band: output holds.
    const double x_switch = held / p.c_l - p.B_l;  // where the left branch is met
    for (double x = peak; x > x_switch + 1e-9; x -= 0.001) ASSERT_EQ(b.step(x), held);
    // Past the band: on the left branch.
    b.step(x_switch - 0.5);
    EXPECT_NEAR(b.output(), p.c_l * (x_switch - 0.5 + p.B_l), 1e-12);
  }
}

TEST(BoucWenBacklash, StateStaysInUnitIntervalForAnyInput) {
  std::mt19937 rng(2);
  std::normal_distribution<double> jump(0.0, 1.0);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    ts::BoucWenBacklashParams p;
    p.B_r = 0.01 + 0.3 * u(rng);
    p.B_l = 0.01 + 0.3 * u(rng);
    p.rho = 1.0 + 200.0 * u(rng);
    p.sigma = 0.5 + 3.0 * u(rng);
    p.n = 1.0 + 9.0 * u(rng);
    p.max_substeps = 4;  // coarse on purpose
    ts::BoucWenBacklash m(p);
    double x = 0.0;
    for (int k = 0; k < 2000; ++k) {
      x += jump(rng) * (k % 50 == 0 ? 100.0 : 0.05);
      const double y = m.step(x);
      ASSERT_TRUE(std::isfinite(y));
      ASSERT_LE(std::fabs(m.state()), 1.0);
    }
  }
}

TEST(Models, NoNanForFiniteInputAndHoldOnNan) {
  ts::Backlash b({});
  ts::BoucWenBacklash bwb({});
  ts::BoucWen bw({});
  ts::HystereticOscillator ho({});
  ts::PrandtlIshlinskii pi({});
  ts::PrandtlIshlinskiiInverse inv({});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1e6, 1e6);
  for (int k = 0; k < 10000; ++k) {
    const double x = (k % 7 == 0) ? u(rng) : u(rng) * 1e-6;
    ASSERT_FALSE(std::isnan(b.step(x, 1e-3)));
    ASSERT_FALSE(std::isnan(bwb.step(x, 1e-3)));
    ASSERT_FALSE(std::isnan(bw.step(x, 1e-3)));
    ASSERT_FALSE(std::isnan(ho.step(x * 1e-6, 1e-3)));
    ASSERT_FALSE(std::isnan(pi.step(x, 1e-3)));
    ASSERT_FALSE(std::isnan(inv.step(x, 1e-3)));
  }
  const double held = bwb.output();
  EXPECT_EQ(bwb.step(std::nan(""), 1e-3), held);
}

TEST(PrandtlIshlinskii, InverseIsExact) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g(0.0, 0.3);
  for (int trial = 0; trial < 40; ++trial) {
    ts::PrandtlIshlinskiiParams p;
    const int n = 1 + trial % 12;
    p.thresholds.clear();
    p.weights.clear();
    double r = 0.0;
    double partial = 0.0;
    for (int i = 0; i < n; ++i) {
      p.thresholds.push_back(r);
      r += 0.01 + 0.2 * u(rng);
      double w = (i == 0) ? 0.2 + u(rng) : g(rng);
      if (partial + w <= 0.05) w = 0.05 - partial + 0.1 * u(rng);
      partial += w;
      p.weights.push_back(w);
    }
    ts::PrandtlIshlinskii fwd(p);
    ts::PrandtlIshlinskiiInverse inv(p);
    double x = 0.0;
    for (int k = 0; k < 3000; ++k) {
      x += g(rng);
      const double back = inv.step(fwd.step(x));
      ASSERT_NEAR(back, x, 1e-9) << "trial " << trial << " step " << k;
    }
  }
}

TEST(Validation, MessagesNameTheParameter) {
  ts::BoucWenBacklashParams p;
  p.sigma = 0.2;
  try {
    ts::BoucWenBacklash m(p);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("sigma"), std::string::npos);
  }
  ts::PrandtlIshlinskiiParams q;
  q.weights = {-1.0, 0.5, 0.1, 0.1, 0.1};
  EXPECT_THROW(ts::PrandtlIshlinskii{q}, std::invalid_argument);
  ts::PrandtlIshlinskiiParams flat_start;
  flat_start.thresholds = {0.1, 0.2};
  flat_start.weights = {1.0, 0.5};
  EXPECT_NO_THROW(ts::PrandtlIshlinskii{flat_start});
  EXPECT_THROW(ts::PrandtlIshlinskiiInverse{flat_start}, std::invalid_argument);
  ts::HystereticOscillatorParams h;
  h.m = 0.0;
  EXPECT_THROW(ts::HystereticOscillator{h}, std::invalid_argument);
}

TEST(Simulate, RejectsNonIncreasingTime) {
  ts::Backlash b({});
  std::vector<double> t{0.0, 1.0, 1.0}, x{0.0, 1.0, 2.0}, y(3);
  EXPECT_THROW(ts::simulate(b, t.data(), x.data(), y.data(), 3, "Backlash"), std::invalid_argument);
}

TEST(HystereticOscillator, SofteningAcceptedDivergenceFlaggedNeverNan) {
  static_assert(noexcept(std::declval<ts::HystereticOscillator&>().step_dense(nullptr, 2, 0.0)));
  ts::HystereticOscillatorParams p;
  p.m = 2.0; p.c = 10.0; p.k = 5e4; p.alpha = 5e4; p.beta = 1e3; p.gamma = 0.8; p.delta = -1.1;
  EXPECT_NO_THROW(ts::HystereticOscillator{p});  // softening: gamma + delta < 0
  // nu = 2, gamma = 0, delta < 0: z escapes in finite displacement under a large force
  ts::HystereticOscillatorParams q;
  q.gamma = 0.0; q.delta = -0.5; q.nu = 2.0;
  for (int mode = 0; mode <= 2; ++mode) {
    q.input_interpolation = mode;
    ts::HystereticOscillator osc(q);
    EXPECT_EQ(osc.delay(), mode == 2 ? q.lookahead - 1 : 0);
    for (int k = 0; k < 5000; ++k) {
      const double y = osc.step(20.0 * std::sin(0.01 * k), 0.01);
      ASSERT_TRUE(std::isfinite(y));
    }
    EXPECT_TRUE(osc.diverged());
    EXPECT_GT(osc.diverged_at(), 0);
    osc.reset();
    EXPECT_FALSE(osc.diverged());
  }
}

// CurveAngleModel::set_shape: a uniform shape gives the uniform closed form (A7), any shape
// the full-slip elongations of PullPullStatics (A5, A6).
TEST(CurveAngleModel, SetShapeIsUniformClosedFormAndA5A6) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    ts::CurveAngleParams p;
    p.friction = 0.05 + 0.15 * unit(rng);
    p.stiffness = 5e3 + 4.5e4 * unit(rng);
    p.pretension = 2.0 + 38.0 * unit(rng);
    p.load_force = -3.0 + 6.0 * unit(rng);
    const double theta = 4.0 * std::acos(-1.0) * unit(rng);
    ts::CurveAngleModel by_angle(p), by_shape(p);
    by_angle.set_curve_angle(theta);
    by_shape.set_shape(ts::uniform_shape(p.friction, theta));
    EXPECT_FALSE(by_shape.uniform());
    const double scale = p.pretension * p.length / p.stiffness / p.proximal_radius;
    for (int k = 0; k < 200; ++k) {
      const double q = 20.0 * scale * std::sin(0.05 * k);
      EXPECT_NEAR(by_shape.step(q), by_angle.step(q), 1e-12 * scale);
    }
    // two arcs: the dead zone and the branches are those of spec A5/A6 with the load
    const double s[] = {0.0, 0.3 * p.length, p.length};
    const double th[] = {0.0, 0.2 * theta, theta};
    const ts::ShapeIntegrals sh = ts::shape_integrals(s, th, 3, p.friction);
    ts::PullPullStatics statics;
    statics.friction = p.friction;
    statics.compliance = p.length / p.stiffness;
    statics.pretension = p.pretension;
    const double fwd = statics.forward_elongation(sh, p.load_force);
    const double bwd = statics.backward_elongation(sh, p.load_force);
    ts::CurveAngleModel model(p);
    model.set_shape(sh);
    const double top = 10.0 * (std::fabs(fwd) + std::fabs(bwd)) / p.proximal_radius;
    for (int k = 0; k <= 100; ++k) model.step(top * k / 100.0);
    EXPECT_NEAR(model.output() * p.distal_radius, top * p.proximal_radius - fwd,
                1e-12 * (fwd - bwd));
    for (int k = 100; k >= -100; --k) model.step(top * k / 100.0);
    EXPECT_NEAR(model.output() * p.distal_radius, -top * p.proximal_radius - bwd,
                1e-12 * (fwd - bwd));
  }
}
