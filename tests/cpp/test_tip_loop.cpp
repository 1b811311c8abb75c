// TipLoop: a PI(D) loop on the tip angle around a feedforward's command, its gains scheduled over
// the curve angle. Checked on a toy first-order plant (the integral removes an offset the
// feedforward does not know), for its anti-windup, dropout and schedule rules, its parameter
// checks, and for finite commands over random sequences.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

namespace {

ts::TipLoopParams gains(double kp, double ki, double kd = 0.0, double cutoff = 50.0) {
  ts::TipLoopParams p;
  p.kp = kp, p.ki = ki, p.kd = kd, p.derivative_cutoff_hz = cutoff;
  return p;
}

// y' = (u + offset - y) / T: a first-order plant whose static map the feedforward (u = y_d) misses
// by `offset`.
struct ToyPlant {
  double T, offset, y = 0.0;
  double step(double u, double dt) {
    y += dt / (T + dt) * (u + offset - y);
    return y;
  }
};

std::string message(const ts::TipLoopParams& p) {
  try {
    ts::TipLoop loop(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(TipLoop, IntegralActionRemovesAConstantOffsetInClosedLoop) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> off(-0.3, 0.3), tc(0.005, 0.05);
  for (int trial = 0; trial < 20; ++trial) {
    const double offset = off(rng), T = tc(rng), dt = 1e-3, y_d = 0.4;
    ToyPlant bare{T, offset}, looped{T, offset};
    ts::TipLoop loop(gains(0.2, 0.5 / T));
    double y = 0.0;
    for (int k = 0; k < 3000; ++k) {
      bare.step(y_d, dt);  // the feedforward alone: u = y_d
      y = looped.step(loop.correct(y_d, y_d, y, k == 0 ? 0.0 : dt), dt);
    }
    EXPECT_NEAR(bare.y - y_d, offset, 1e-6) << trial;  // the offset stays without the loop
    EXPECT_LT(std::fabs(looped.y - y_d), 1e-6 * (1.0 + std::fabs(offset))) << trial;
    EXPECT_NEAR(loop.integral(), -offset, 1e-5) << trial;
  }
}

// While the command is cut at its limit the integral does not grow in the error's direction, so
// the command lets go of the limit as soon as the error turns.
TEST(TipLoop, AntiWindupHoldsTheIntegralWhileTheLimitsCut) {
  ts::TipLoopParams p = gains(0.0, 200.0);
  p.limits.max = 1.0;
  ts::TipLoop loop(p);
  double y = 0.0;
  loop.correct(1.0, 1.0, y, 0.0);
  double u = 0.0;
  for (int k = 0; k < 2000; ++k) {
    u = loop.correct(1.0, 2.0, y, 1e-3);  // y_d = 2 is out of reach: the plant gives y = u
    y = u;
  }
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::saturated));
  EXPECT_DOUBLE_EQ(u, 1.0);
  // it integrated only until the limit cut (one cycle: 200 * 1 * 1e-3), not 2 s of error (~400)
  EXPECT_LT(loop.integral(), 0.5);
  const double held = loop.integral();
  loop.correct(1.0, 2.0, 1.0, 1e-3);
  EXPECT_DOUBLE_EQ(loop.integral(), held);
  u = loop.correct(0.2, 0.2, 1.0, 1e-3);  // the error turns negative: released at once
  EXPECT_LT(u, 1.0);
}

TEST(TipLoop, ADropoutFallsBackTowardTheFeedforward) {
  ts::TipLoop loop(gains(2.0, 100.0, 0.01));
  loop.correct(0.0, 0.0, 0.0, 0.0);
  for (int k = 0; k < 50; ++k) loop.correct(0.5, 0.5, 0.4, 1e-3);  // a steady error
  const double integral = loop.integral();
  EXPECT_GT(integral, 0.01);
  EXPECT_GT(loop.correction(), integral + 0.1);  // the P term is in the correction
  const double u = loop.correct(0.5, 0.5, NAN, 1e-3);
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::fallback));
  EXPECT_TRUE(loop.in_fallback());
  EXPECT_DOUBLE_EQ(loop.integral(), integral);  // held
  EXPECT_DOUBLE_EQ(loop.correction(), integral);  // P and D zeroed
  EXPECT_DOUBLE_EQ(u, 0.5 + integral);
  for (int k = 0; k < 20; ++k) loop.correct(0.5, 0.5, NAN, 1e-3);
  EXPECT_DOUBLE_EQ(loop.integral(), integral);
  loop.correct(0.5, 0.5, 0.45, 1e-3);
  EXPECT_FALSE(ts::has(loop.status(), ts::Status::fallback));
  // back: P and I act on the new error, no derivative kick from the gap
  EXPECT_NEAR(loop.correction(), 2.0 * 0.05 + integral + 100.0 * 0.05 * 1e-3, 1e-12);
}

TEST(TipLoop, ANonFiniteDesiredOutputHoldsTheLastCommand) {
  ts::TipLoop loop(gains(1.0, 10.0));
  loop.correct(0.3, 0.3, 0.0, 0.0);
  const double u = loop.correct(0.3, 0.3, 0.1, 1e-3);
  EXPECT_DOUBLE_EQ(loop.correct(0.4, NAN, 0.1, 1e-3), u);
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::held_nonfinite_input));
  EXPECT_DOUBLE_EQ(loop.correct(NAN, 0.4, 0.1, 1e-3), u);
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::held_nonfinite_input));
}

// The schedule's factor against a direct computation (std::upper_bound) over random tables, and
// its effect: with kp alone the correction is s kp e.
TEST(TipLoop, GainScheduleInterpolatesOverRandomTables) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    ts::TipLoopParams p = gains(0.7, 0.0);
    p.schedule_size = 1 + trial % ts::TipLoopParams::kMaxSchedule;
    double a = 3.0 * u01(rng);
    for (std::size_t i = 0; i < p.schedule_size; ++i) {
      p.schedule_angles[i] = a;
      p.schedule_gains[i] = 0.05 + 3.0 * u01(rng);
      a += 0.01 + u01(rng);
    }
    ts::TipLoop loop(p);
    const std::size_t n = p.schedule_size;
    const auto* x = p.schedule_angles.data();
    const auto* g = p.schedule_gains.data();
    for (int j = 0; j < 20; ++j) {
      const double theta = (j == 0) ? x[0] : (j == 1 ? x[n - 1] : 12.0 * u01(rng));
      ASSERT_TRUE(loop.set_curve_angle(theta));
      double expected;
      const auto* hi = std::upper_bound(x, x + n, theta);
      if (hi == x) {
        expected = g[0];
      } else if (hi == x + n) {
        expected = g[n - 1];
      } else {
        const std::size_t i = static_cast<std::size_t>(hi - x);
        const double w = (theta - x[i - 1]) / (x[i] - x[i - 1]);
        expected = (1.0 - w) * g[i - 1] + w * g[i];
      }
      ASSERT_NEAR(loop.gain_scale(), expected, 1e-12 * expected) << trial << " " << theta;
      loop.reset();
      loop.correct(0.0, 0.2, 0.0, 0.0);
      loop.correct(0.0, 0.2, 0.1, 1e-3);  // e = 0.1
      ASSERT_NEAR(loop.correction(), expected * 0.7 * 0.1, 1e-12);
    }
  }
}

TEST(TipLoop, AnEmptyScheduleIsOneAndABadCurveAngleIsIgnored) {
  ts::TipLoop plain(gains(1.0, 0.0));
  plain.set_curve_angle(2.0);
  EXPECT_DOUBLE_EQ(plain.gain_scale(), 1.0);
  ts::TipLoopParams p = gains(1.0, 0.0);
  p.schedule_size = 2;
  p.schedule_angles = {1.0, 3.0};
  p.schedule_gains = {2.0, 4.0};
  ts::TipLoop loop(p);
  EXPECT_DOUBLE_EQ(loop.gain_scale(), 2.0);  // angle 0, clamped at the first point
  loop.set_shape(ts::uniform_shape(0.1, 2.0));
  EXPECT_DOUBLE_EQ(loop.gain_scale(), 3.0);
  EXPECT_FALSE(loop.set_curve_angle(NAN));
  EXPECT_FALSE(loop.set_curve_angle(-0.5));
  EXPECT_DOUBLE_EQ(loop.gain_scale(), 3.0);  // kept
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::input_clamped));
  loop.correct(0.0, 0.0, 0.0, 0.0);
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::input_clamped));  // that cycle ran on the old one
  loop.correct(0.0, 0.0, 0.0, 1e-3);
  EXPECT_FALSE(ts::has(loop.status(), ts::Status::input_clamped));
  loop.reset();
  EXPECT_DOUBLE_EQ(loop.gain_scale(), 3.0);  // reset keeps the curve angle
}

TEST(TipLoop, InvalidParametersNameThemselves) {
  const auto names = [](const ts::TipLoopParams& p, const char* name) {
    const std::string m = message(p);
    return m.find("TipLoop") != std::string::npos && m.find(name) != std::string::npos;
  };
  ts::TipLoopParams p;
  EXPECT_EQ(message(p), "(no error)");
  p = {}, p.kp = -1.0;
  EXPECT_TRUE(names(p, "kp"));
  p = {}, p.ki = NAN;
  EXPECT_TRUE(names(p, "ki"));
  p = {}, p.kd = INFINITY;
  EXPECT_TRUE(names(p, "kd"));
  p = {}, p.derivative_cutoff_hz = 0.0;
  EXPECT_TRUE(names(p, "derivative_cutoff_hz"));
  p = {}, p.derivative_cutoff_hz = INFINITY;
  EXPECT_TRUE(names(p, "derivative_cutoff_hz"));
  p = {}, p.max_correction = 0.0;
  EXPECT_TRUE(names(p, "max_correction"));
  p = {}, p.max_correction = NAN;
  EXPECT_TRUE(names(p, "max_correction"));
  p = {}, p.schedule_size = 9;
  EXPECT_TRUE(names(p, "schedule_size"));
  p = {}, p.schedule_size = 3, p.schedule_angles = {0.0, 1.0, 1.0}, p.schedule_gains = {1, 1, 1};
  EXPECT_TRUE(names(p, "schedule_angles"));
  p = {}, p.schedule_size = 2, p.schedule_angles = {0.0, NAN}, p.schedule_gains = {1, 1};
  EXPECT_TRUE(names(p, "schedule_angles[1]"));
  p = {}, p.schedule_size = 2, p.schedule_angles = {0.0, 1.0}, p.schedule_gains = {1.0, 0.0};
  EXPECT_TRUE(names(p, "schedule_gains[1]"));
  p = {}, p.schedule_size = 1, p.schedule_gains = {-2.0};
  EXPECT_TRUE(names(p, "schedule_gains[0]"));
  p = {}, p.limits.min = 1.0, p.limits.max = -1.0;
  EXPECT_TRUE(names(p, "min"));
}

// Random finite inputs (with dropouts and extreme gains) never give a non-finite command.
TEST(TipLoop, NeverNanForFiniteInputOverRandomSequences) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u01(0.0, 1.0), v(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double big = trial % 5 == 0 ? 1e8 : 1.0;
    ts::TipLoopParams p = gains(10.0 * big * u01(rng), 1e3 * big * u01(rng), 0.1 * u01(rng),
                                0.5 + 500.0 * u01(rng));
    if (trial % 2) p.max_correction = 0.01 + u01(rng);
    if (trial % 3 == 0) p.limits.max = 0.5 + u01(rng), p.limits.min = -p.limits.max;
    if (trial % 4 == 0) p.limits.max_rate = 5.0 + 50.0 * u01(rng);
    p.schedule_size = static_cast<std::size_t>(trial % 4);
    for (std::size_t i = 0; i < p.schedule_size; ++i)
      p.schedule_angles[i] = 1.5 * i, p.schedule_gains[i] = 0.1 + 5.0 * u01(rng);
    ts::TipLoop loop(p);
    for (int k = 0; k < 500; ++k) {
      const double scale = k % 97 == 0 ? 1e6 : 1.0;
      if (k % 50 == 0) loop.set_curve_angle(6.0 * v(rng));
      const double dt = k % 41 == 0 ? (k % 2 ? 0.0 : 1e-9) : 1e-3 * (0.5 + u01(rng));
      const double y = k % 23 == 0 ? NAN : scale * v(rng);
      const double u = loop.correct(scale * v(rng), scale * v(rng), y, dt);
      ASSERT_TRUE(std::isfinite(u)) << trial << " " << k;
      ASSERT_TRUE(std::isfinite(loop.correction())) << trial << " " << k;
    }
  }
}

// TipLooped: the feedforward's command is the loop's target; the shape reaches both a feedforward
// that follows the route and the loop's schedule.
TEST(TipLoop, LoopedFeedforwardComposesTheTwo) {
  ts::TipLoopParams p = gains(0.5, 50.0, 0.001);
  p.schedule_size = 2;
  p.schedule_angles = {0.0, 6.0};
  p.schedule_gains = {0.5, 2.0};
  ts::TipLooped<ts::CurveAngleFeedforward> looped(
      ts::CurveAngleFeedforward(ts::CurveAngleFeedforwardParams{}), ts::TipLoop(p));
  ts::CurveAngleFeedforward alone(ts::CurveAngleFeedforwardParams{});
  ts::TipLoop loop(p);
  const ts::ShapeIntegrals shape = ts::uniform_shape(0.1, 4.0);
  looped.set_shape(shape);
  alone.set_shape(shape);
  loop.set_shape(shape);
  EXPECT_DOUBLE_EQ(looped.loop().gain_scale(), 1.5);
  for (int k = 0; k < 200; ++k) {
    const double y_d = 0.5 * std::sin(0.03 * k), y = 0.4 * std::sin(0.03 * k - 0.1);
    const double dt = k == 0 ? 0.0 : 1e-3;
    EXPECT_DOUBLE_EQ(looped.step(y_d, y, dt), loop.correct(alone.step(y_d, dt), y_d, y, dt));
  }
}
