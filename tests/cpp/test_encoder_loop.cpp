// EncoderLoop: a PI(D) loop on the motor encoder around a feedforward's target. Checked against
// the closed form of its difference equations, on a yielding servo (the integral removes the
// steady yield a PD servo leaves, tau / (J_r w^2)), and for its dropout and anti-windup rules.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

ts::EncoderLoop make_loop(double kp, double ki, double kd = 0.0, double cutoff = 50.0) {
  ts::EncoderLoopParams p;
  p.kp = kp, p.ki = ki, p.kd = kd, p.derivative_cutoff_hz = cutoff;
  return ts::EncoderLoop(p);
}
}  // namespace

// The loop's difference equations written out independently: e_k = x_{k-1} - q_k,
// I_k = I_{k-1} + ki e_k dt, D_k = D_{k-1} + a ((e_k - e_{k-1})/dt - D_{k-1}), u = x + kp e + I + kd D.
TEST(EncoderLoop, CommandsFollowItsDifferenceEquationsOverRandomGains) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> g(0.0, 3.0), gi(0.0, 500.0), gd(0.0, 0.01), v(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const double kp = g(rng), ki = gi(rng), kd = gd(rng), cutoff = 20.0 + 200.0 * g(rng);
    ts::EncoderLoop loop = make_loop(kp, ki, kd, cutoff);
    const double dt = 1e-3, a = dt / (dt + 1.0 / (2 * kPi * cutoff));
    double x_prev = 0.0, I = 0.0, D = 0.0, e_prev = 0.0;
    for (int k = 0; k < 300; ++k) {
      const double x = std::sin(0.01 * k) + 0.1 * v(rng), q = 0.9 * x + 0.05 * v(rng);
      const double u = loop.correct(x, q, k == 0 ? 0.0 : dt);
      double expected = x;
      if (k > 0) {
        const double e = x_prev - q;
        I += ki * e * dt;
        D += a * ((e - e_prev) / dt - D);
        e_prev = e;
        expected = x + kp * e + I + kd * D;
      }
      ASSERT_NEAR(u, expected, 1e-12 * (1.0 + std::fabs(expected))) << "trial " << trial << " k " << k;
      x_prev = x;
    }
  }
}

// A PD position servo with reflected inertia J_r yields tau / (J_r w^2) under a constant load
// torque (its static stiffness); the integral of the encoder loop removes it.
TEST(EncoderLoop, RemovesTheSteadyYieldOfAPdServoUnderRandomLoads) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> f(20.0, 80.0), tq(-0.3, 0.3), jr(5e-5, 2e-4);
  for (int trial = 0; trial < 20; ++trial) {
    ts::MotorParams mp;
    mp.bandwidth_hz = f(rng), mp.damping = 0.8, mp.inertia = jr(rng);
    const double tau = tq(rng), w = 2 * kPi * mp.bandwidth_hz;
    const double yield = tau / (mp.inertia * w * w);
    ts::Motor bare(mp), looped(mp);
    ts::EncoderLoop loop = make_loop(0.5, 0.2 * w);
    const double target = 0.3;
    double q = 0.0;
    for (int k = 0; k < 4000; ++k) {
      bare.step(target, 1e-3, tau);
      q = looped.step(loop.correct(target, q, k == 0 ? 0.0 : 1e-3), 1e-3, tau);
    }
    EXPECT_NEAR(bare.position() - target, yield, 1e-3 * std::fabs(yield) + 1e-9) << trial;
    EXPECT_LT(std::fabs(looped.position() - target), 1e-6 * (1.0 + std::fabs(yield))) << trial;
  }
}

TEST(EncoderLoop, ADropoutHoldsTheCorrectionAndSaysFallback) {
  ts::EncoderLoop loop = make_loop(1.0, 100.0);
  loop.correct(0.0, 0.0, 0.0);
  for (int k = 0; k < 50; ++k) loop.correct(0.5, 0.4, 1e-3);  // a steady error builds a correction
  const double held = loop.correction();
  EXPECT_GT(held, 0.1);
  const double u = loop.correct(0.5, NAN, 1e-3);
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::fallback));
  EXPECT_DOUBLE_EQ(u, 0.5 + held);
  EXPECT_DOUBLE_EQ(loop.correction(), held);
  loop.correct(0.5, 0.4, 1e-3);
  EXPECT_FALSE(ts::has(loop.status(), ts::Status::fallback));
}

// Anti-windup: while the command is cut at its limit the integral stops growing in the direction
// of the error, so it lets go of the limit as soon as the error turns.
TEST(EncoderLoop, TheIntegralDoesNotWindUpAgainstTheLimits) {
  ts::EncoderLoopParams p;
  p.ki = 200.0;
  p.limits.max = 1.0;
  ts::EncoderLoop loop(p);
  loop.correct(1.0, 0.0, 0.0);
  for (int k = 0; k < 2000; ++k) loop.correct(1.0, 0.5, 1e-3);  // the shaft never gets there
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::saturated));
  EXPECT_LT(loop.integral(), 0.2);  // without anti-windup: 200 * 0.5 * 2 s = 200
  const double u = loop.correct(0.2, 1.0, 1e-3);
  EXPECT_LT(u, 1.0);  // released at once when the error turns
}

TEST(EncoderLoop, MaxCorrectionBoundsTheCorrection) {
  ts::EncoderLoopParams p;
  p.ki = 1000.0, p.kp = 5.0, p.max_correction = 0.05;
  ts::EncoderLoop loop(p);
  loop.correct(0.0, 0.0, 0.0);
  for (int k = 0; k < 100; ++k) {
    const double u = loop.correct(1.0, 0.0, 1e-3);
    EXPECT_LE(u, 1.05 + 1e-15);
  }
  EXPECT_TRUE(ts::has(loop.status(), ts::Status::saturated));
}

TEST(EncoderLoop, InvalidParametersNameThemselves) {
  const auto message = [](ts::EncoderLoopParams p) {
    try {
      ts::EncoderLoop loop(p);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  ts::EncoderLoopParams p;
  p.ki = -1.0;
  EXPECT_NE(message(p).find("ki"), std::string::npos);
  p = {};
  p.derivative_cutoff_hz = 0.0;
  EXPECT_NE(message(p).find("derivative_cutoff_hz"), std::string::npos);
  p = {};
  p.max_correction = 0.0;
  EXPECT_NE(message(p).find("max_correction"), std::string::npos);
  p = {};
  p.kp = NAN;
  EXPECT_NE(message(p).find("kp"), std::string::npos);
}

// EncoderLooped: the feedforward's command is the loop's target; the shape reaches a feedforward
// that follows the route.
TEST(EncoderLoop, LoopedFeedforwardComposesTheTwo) {
  ts::CurveAngleFeedforward ff(ts::CurveAngleFeedforwardParams{});
  ts::EncoderLooped<ts::CurveAngleFeedforward> looped(ff, make_loop(0.5, 50.0));
  ts::CurveAngleFeedforward alone(ts::CurveAngleFeedforwardParams{});
  ts::EncoderLoop loop = make_loop(0.5, 50.0);
  const ts::ShapeIntegrals shape = ts::uniform_shape(0.1, 4.0);
  looped.set_shape(shape);
  alone.set_shape(shape);
  for (int k = 0; k < 200; ++k) {
    const double y = 0.5 * std::sin(0.03 * k), q = 0.4 * std::sin(0.03 * k - 0.1);
    const double dt = k == 0 ? 0.0 : 1e-3;
    EXPECT_DOUBLE_EQ(looped.step(y, q, dt), loop.correct(alone.step(y, dt), q, dt));
  }
}
