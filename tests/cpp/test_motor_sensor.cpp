// The position servo's integral action (issue 23, item 3) and the sensor's latency (item 6),
// against closed forms and against the code they extend, kept here as reference copies: with
// integral_time = 0 and delay = 0 both must be the old classes bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

std::string thrown_message(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// The position kind of Motor::step() before integral action existed (commit fc11d43),
// transcribed: the reference the PD servo must equal bit for bit.
struct OldPositionMotor {
  ts::MotorParams p;
  double q = 0.0, v = 0.0, pulley = 0.0;
  bool initialised = false;

  double step(double u, double dt, double tau_ext) {
    if (!std::isfinite(u)) return pulley;
    if (!std::isfinite(tau_ext)) tau_ext = 0.0;
    if (!initialised) {
      initialised = true;
      q = u;
      v = 0.0;
      pulley = q;
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) return pulley;
    const double w = 2.0 * kPi * p.bandwidth_hz;
    const double J = p.inertia;
    const double inv_J = J > 0.0 ? 1.0 / J : 0.0;
    const double b = p.viscous_friction;
    const double m = std::ceil(dt * w / 0.1);
    const int n = m >= p.max_substeps ? p.max_substeps : (m >= 1.0 ? static_cast<int>(m) : 1);
    double h = dt / n;
    if (h > 10.0 / w) h = 10.0 / w;
    const double stick = h * p.coulomb_friction * inv_J;
    for (int i = 0; i < n; ++i) {
      const double num = v + h * (w * w * (u - q) + tau_ext * inv_J);
      const double den = 1.0 + 2.0 * p.damping * w * h + w * w * h * h + h * b * inv_J;
      double v_new = std::fabs(num) <= stick ? 0.0 : (num - std::copysign(stick, num)) / den;
      const double amax = p.max_accel * h;
      if (v_new - v > amax) v_new = v + amax;
      if (v_new - v < -amax) v_new = v - amax;
      if (std::fabs(v_new) > p.max_speed) v_new = std::copysign(p.max_speed, v_new);
      const double q_new = q + h * v_new;
      if (!std::isfinite(v_new) || !std::isfinite(q_new)) {
        v = 0.0;
        break;
      }
      v = v_new;
      q = q_new;
    }
    const double half = 0.5 * p.gear_backlash;
    if (pulley < q - half) pulley = q - half;
    if (pulley > q + half) pulley = q + half;
    return pulley;
  }
};

// Random position-motor parameters: bandwidth 2-80 Hz, damping 0.3-1.5, reflected inertia
// 1e-5-1e-3 kg m^2, viscous friction b_m up to J_r w (so 2 zeta w + b_m / J_r <= 4 w).
ts::MotorParams random_servo(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ts::MotorParams p;
  p.bandwidth_hz = 2.0 + 78.0 * u(rng);
  p.damping = 0.3 + 1.2 * u(rng);
  p.inertia = std::pow(10.0, -5.0 + 2.0 * u(rng));
  p.viscous_friction = p.inertia * 2.0 * kPi * p.bandwidth_hz * u(rng);
  return p;
}

double omega(const ts::MotorParams& p) { return 2.0 * kPi * p.bandwidth_hz; }

// Hold the command at u under a constant torque tau for `duration` seconds at 1 kHz.
void hold(ts::Motor& m, double u, double tau, double duration) {
  m.step(u, 0.0, tau);
  const int n = static_cast<int>(duration / 1e-3);
  for (int k = 0; k < n; ++k) m.step(u, 1e-3, tau);
}
}  // namespace

TEST(PidServo, PdYieldsTauOverJw2AndPidNotAtAll) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    ts::MotorParams p = random_servo(rng);
    const double w = omega(p);
    const double tau = 0.5 * u(rng), q_cmd = u(rng);
    const double yield = tau / (p.inertia * w * w);  // the PD servo's deflection
    ts::Motor pd(p);
    // s^2 + c s + w^2 with c <= 4 w decays at >= 0.26 w: 120 / w leaves < e^-30 of the step
    hold(pd, q_cmd, tau, 120.0 / w + 0.2);
    // the backward-Euler rest state is the continuous one: rounding only (the Python twin of
    // this test measured <= 3.2e-13 of the yield, 8.4e-13 on the integral)
    EXPECT_NEAR(pd.position() - q_cmd, yield, 1e-11 * std::fabs(yield) + 1e-14) << trial;
    p.integral_time = 5.0 / w;  // the preset's integral corner, a fifth of w
    ts::Motor pid(p);
    // s^3 + c s^2 + w^2 s + w^3 / 5 with c <= 4 w decays at >= 0.12 w: 250 / w leaves < e^-30
    hold(pid, q_cmd, tau, 250.0 / w + 0.2);
    EXPECT_NEAR(pid.position(), q_cmd, 1e-11 * std::fabs(yield) + 1e-14) << trial;
    // at rest the integral carries the load: w^2 z / T_i = -tau / J_r
    const double z = -yield * p.integral_time;
    EXPECT_NEAR(pid.integral(), z, 1e-11 * std::fabs(z)) << trial;
  }
}

TEST(PidServo, ZeroIntegralTimeIsTheOldMotorBitForBit) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    ts::MotorParams p = random_servo(rng);
    p.coulomb_friction = trial % 2 ? 0.02 * u(rng) : 0.0;
    p.gear_backlash = 0.02 * u(rng);
    p.max_speed = trial % 3 ? 1.0 + 20.0 * u(rng) : std::numeric_limits<double>::infinity();
    p.max_accel = trial % 4 ? 50.0 + 2000.0 * u(rng) : std::numeric_limits<double>::infinity();
    p.max_substeps = 1 + static_cast<int>(300.0 * u(rng));
    if (trial % 5 == 0) {  // the ideal lag
      p.inertia = 0.0;
      p.coulomb_friction = 0.0;
      p.viscous_friction = 0.0;
    }
    ts::Motor now(p);
    OldPositionMotor old{p};
    for (int k = 0; k < 3000; ++k) {
      double cmd = std::sin(0.003 * k * (1 + trial)) + (k % 700 == 0 ? 2.0 : 0.0);
      if (k == 1500) cmd = NAN;
      const double dt = k % 97 == 0 ? 0.05 : 1e-3 * (0.5 + u(rng));
      const double tau = 0.05 * std::sin(0.01 * k);
      ASSERT_EQ(now.step(cmd, dt, tau), old.step(cmd, dt, tau)) << trial << " " << k;
      ASSERT_EQ(now.position(), old.q);
      ASSERT_EQ(now.velocity(), old.v);
      ASSERT_EQ(now.integral(), 0.0);
    }
  }
}

TEST(PidServo, ValidationNamesIntegralTimeAndItsBound) {
  ts::MotorParams p;
  p.bandwidth_hz = 10.0;
  p.damping = 0.5;
  const double bound = 1.0 / (2.0 * 0.5 * 2.0 * kPi * 10.0);
  p.integral_time = 0.99 * bound;
  const std::string msg = thrown_message([&] { ts::Motor m(p); });
  EXPECT_NE(msg.find("integral_time"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1 / (2 damping w) = 0.0159"), std::string::npos) << msg;
  p.integral_time = -1.0;
  EXPECT_NE(thrown_message([&] { ts::Motor m(p); }).find("integral_time must be >= 0"),
            std::string::npos);
  p.integral_time = 1.01 * bound;
  EXPECT_EQ(thrown_message([&] { ts::Motor m(p); }), "");
}

TEST(PidServo, AntiWindupHoldsTheIntegralWhileSpeedLimited) {
  ts::MotorParams p;
  p.bandwidth_hz = 20.0;
  p.damping = 0.8;
  p.max_speed = 1.0;
  p.integral_time = 5.0 / omega(p);
  ts::Motor m(p);
  m.step(0.0, 0.0);
  double peak = 0.0;
  for (int k = 0; k < 8000; ++k) {
    m.step(5.0, 1e-3);  // a 5 rad step at 1 rad/s: 5 s of slewing
    if (k > 100 && k < 4500) {
      ASSERT_EQ(m.integral(), 0.0) << k;  // cut by the limit throughout
    }
    peak = std::max(peak, m.position());
  }
  EXPECT_NEAR(m.position(), 5.0, 1e-6);
  // no wound-up integral to unwind (5 s of slewing would have wound up about 12 rad s): the
  // overshoot measured 2.4e-3 rad, that of the loop's unsaturated tail
  EXPECT_LT(peak - 5.0, 0.05);
}

TEST(PidServo, StateSnapshotContinuesIdentically) {
  ts::MotorParams p;
  p.bandwidth_hz = 15.0;
  p.inertia = 1e-4;
  p.integral_time = 0.05;
  ts::Motor a(p), b(p);
  a.step(0.0, 0.0, 0.1);
  for (int k = 0; k < 500; ++k) a.step(std::sin(0.01 * k), 1e-3, 0.1);
  b.set_state(a.position(), a.velocity(), a.integral());
  for (int k = 500; k < 900; ++k)
    ASSERT_EQ(a.step(std::sin(0.01 * k), 1e-3, 0.1), b.step(std::sin(0.01 * k), 1e-3, 0.1));
  a.reset();
  EXPECT_EQ(a.integral(), 0.0);
}

namespace {
// Sensor::measure() before the latency existed: the reference for delay = 0.
struct OldSensor {
  ts::SensorParams p;
  std::uint64_t state;
  double spare = 0.0, last = 0.0;
  bool have_spare = false;
  explicit OldSensor(const ts::SensorParams& q) : p(q), state(q.seed) {}
  std::uint64_t next() {
    std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform01() {
    return (static_cast<double>(next() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  }
  double gaussian() {
    if (have_spare) {
      have_spare = false;
      return spare;
    }
    const double u1 = uniform01(), u2 = uniform01();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare = r * std::sin(2.0 * kPi * u2);
    have_spare = true;
    return r * std::cos(2.0 * kPi * u2);
  }
  double measure(double x) {
    if (!std::isfinite(x)) return last;
    double y = x;
    if (p.noise_std > 0.0) y += p.noise_std * gaussian();
    if (p.resolution > 0.0 && std::fabs(y / p.resolution) < 4503599627370496.0)
      y = p.resolution * std::round(y / p.resolution);
    last = y;
    return y;
  }
};

ts::SensorParams delayed(double delay, int history) {
  ts::SensorParams p;
  p.delay = delay;
  p.history = history;
  return p;
}
}  // namespace

TEST(SensorDelay, ZeroDelayIsTheOldSensorBitForBit) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    ts::SensorParams p{trial % 2 ? 1e-3 * u(rng) : 0.0, 1e-2 * u(rng), rng()};
    p.history = 1 + trial;
    ts::Sensor now(p);
    OldSensor old(p);
    for (int k = 0; k < 2000; ++k) {
      const double x = k == 999 ? NAN : std::sin(0.01 * k);
      ASSERT_EQ(now.measure(x, 1e-3 * u(rng)), old.measure(x)) << trial << " " << k;
    }
  }
}

TEST(SensorDelay, ARampIsShiftedByTheDelayExactly) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    const double rate = 100.0 + 10000.0 * u(rng);  // 100 Hz to 10 kHz, jittered by +-30 %
    const double delay = 0.1 * u(rng), slope = 10.0 * (u(rng) - 0.5), offset = u(rng);
    ts::Sensor s(delayed(delay, 4096));
    double t = 0.0;
    EXPECT_EQ(s.measure(offset), offset);  // t = 0: the first sample
    for (int k = 1; k < 3000; ++k) {
      const double dt = (0.7 + 0.6 * u(rng)) / rate;
      t += dt;  // the sensor's clock sums the same dt in the same order
      const double y = s.measure(offset + slope * t, dt);
      // before `delay` has passed: the first sample (offset); linear interpolation is exact
      // on a ramp up to rounding
      const double expected = offset + slope * std::max(t - delay, 0.0);
      ASSERT_NEAR(y, expected, 1e-12 * (1.0 + std::fabs(offset) + std::fabs(slope * t)))
          << trial << " " << k;
      ASSERT_EQ(s.status(), ts::Status::ok);
    }
  }
}

TEST(SensorDelay, AnIntegerSampleDelayIsAShift) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 30; ++trial) {
    const double dt = 1e-4 * (1.0 + 99.0 * u(rng));
    const int m = 1 + static_cast<int>(40.0 * u(rng));
    // m + 1 samples span the delay; one more covers a t - delay rounded below a sample's time
    ts::Sensor s(delayed(m * dt, m + 2));
    std::vector<double> x(500);
    for (double& v : x) v = u(rng) - 0.5;
    for (int k = 0; k < 500; ++k) {
      const double y = s.measure(x[k], k == 0 ? 0.0 : dt);
      // the summed clock puts t - delay within rounding of a stored sample's time
      ASSERT_NEAR(y, x[k >= m ? k - m : 0], 1e-9) << trial << " " << k;
      ASSERT_EQ(s.status(), ts::Status::ok) << trial << " " << k;
    }
  }
}

TEST(SensorDelay, AHistoryTooShortReadsTheOldestAndIsFlagged) {
  const double dt = 1e-3;
  for (int history = 1; history < 12; ++history) {
    ts::Sensor s(delayed(10.5 * dt, history));  // needs 12 samples
    for (int k = 0; k < 60; ++k) {
      const double y = s.measure(static_cast<double>(k), k == 0 ? 0.0 : dt);
      const bool dropped = k >= history;  // a sample has been overwritten since k = history
      if (k * dt < 10.5 * dt || !dropped) {  // not yet a delay of history: the first sample
        ASSERT_EQ(y, dropped ? k - history + 1 : 0.0) << history << " " << k;
      } else {
        ASSERT_EQ(y, k - history + 1) << history << " " << k;  // the oldest kept
      }
      ASSERT_EQ(has(s.status(), ts::Status::input_clamped), dropped) << history << " " << k;
    }
  }
}

TEST(SensorDelay, NoTimePassingReplacesTheSampleAndNaNIsHeld) {
  ts::Sensor s(delayed(0.01, 64));
  EXPECT_EQ(s.measure(1.0), 1.0);
  EXPECT_EQ(s.measure(2.0), 2.0);  // dt 0: the same instant, replaced
  EXPECT_EQ(s.measure(3.0, 0.02), 2.5);  // at t = 0.02 it reads t = 0.01, half way
  EXPECT_EQ(s.measure(NAN, 0.01), 2.5);  // held, time passes
  EXPECT_TRUE(has(s.status(), ts::Status::held_nonfinite_input));
  // t = 0.04 reads t = 0.03, between the samples at 0.02 (3) and 0.04 (5): the NaN left a gap
  EXPECT_NEAR(s.measure(5.0, 0.01), 4.0, 1e-12);
  EXPECT_NEAR(s.measure(5.0, 0.005), 4.5, 1e-12);  // t = 0.045 reads 0.035
  s.reset();
  EXPECT_EQ(s.measure(7.0, 1.0), 7.0);
  EXPECT_EQ(s.status(), ts::Status::ok);
}

TEST(SensorDelay, ValidationNamesDelayAndHistory) {
  EXPECT_NE(thrown_message([] { ts::Sensor s(delayed(-1.0, 8)); }).find("delay must be >= 0"),
            std::string::npos);
  EXPECT_NE(thrown_message([] { ts::Sensor s(delayed(NAN, 8)); }).find("delay"),
            std::string::npos);
  EXPECT_NE(thrown_message([] { ts::Sensor s(delayed(0.1, 0)); }).find("history must be in [1, "),
            std::string::npos);
}
