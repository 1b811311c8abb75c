// Fuzz drivers, one per real-time class family, shared by the libFuzzer targets (make fuzz:
// tests/fuzz/fuzz_<family>.cpp) and the seeded GoogleTest harness in make test
// (tests/fuzz/test_fuzz_seeded.cpp). A driver reads its bytes as a stream of operations
// (steps with random, extreme and non-finite inputs and dt, resets, route or curve-angle
// changes) on one or more instances and checks the real-time contract after each:
//   - a finite input gives a finite output, whatever came before (so a non-finite or extreme
//     input never poisons the state: the next finite input recovers);
//   - a plant step never makes more than max_solves() tridiagonal solves, and a non-finite
//     input is reported held in its status.
// A driver returns the first broken rule (nullptr when none).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "../cpp/listed_steppers.hpp"
#include "../cpp/model_inverse_cases.hpp"

namespace tendonsheath::fuzz {

struct Failure {
  const char* rule = nullptr;  // nullptr: none
  long op = -1;                // index of the operation that broke it
};

// The fuzzer's bytes as numbers (0 once they run out).
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : p_(data), n_(size) {}
  bool done() const noexcept { return i_ >= n_; }
  std::uint8_t byte() noexcept { return i_ < n_ ? p_[i_++] : 0; }
  double unit() noexcept {  // in [0, 1]
    const unsigned v = (static_cast<unsigned>(byte()) << 8) | byte();
    return v / 65535.0;
  }
  // A value: one in 8 an extreme or non-finite one, else uniform in [-scale, scale]
  // (one in 8 of those scaled up 1000x: a shock).
  double value(double scale) noexcept {
    const std::uint8_t k = byte();
    if (k < 32) return special(k);
    const double v = (2.0 * unit() - 1.0) * scale;
    return k >= 224 ? 1000.0 * v : v;
  }
  // A time step: usually 1 ms-ish, else one of the extremes (0, negative, huge, non-finite).
  double dt() noexcept {
    const std::uint8_t k = byte();
    static constexpr double kDt[] = {0.0, -1e-3, 1e300, 1e-300, -1e300, 10.0, 4.0,
                                     std::numeric_limits<double>::quiet_NaN(),
                                     std::numeric_limits<double>::infinity(),
                                     std::numeric_limits<double>::denorm_min()};
    if (k < 20) return kDt[k % 10];
    return 1e-3 * (0.25 + k / 64.0);
  }

 private:
  static double special(std::uint8_t k) noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    static constexpr double kSpecial[] = {
        std::numeric_limits<double>::quiet_NaN(), inf, -inf, 1e300, -1e300, 1e308, -1e308,
        std::numeric_limits<double>::max(), std::numeric_limits<double>::denorm_min(),
        -std::numeric_limits<double>::denorm_min(), 0.0, -0.0, 1e6, -1e6, 1e12, 1e-300};
    return kSpecial[k % 16];
  }
  const std::uint8_t* p_;
  std::size_t n_;
  std::size_t i_ = 0;
};

namespace detail_fuzz {
constexpr double kPi = 3.14159265358979323846;
constexpr int kMaxOps = 256;  // operations per case at most

inline bool bad(double in, double out) noexcept { return std::isfinite(in) && !std::isfinite(out); }

// Lumped node angles of a random route change: uniform, random per node, or extreme.
inline void route_angles(Bytes& b, std::vector<double>& a) {
  const std::uint8_t kind = b.byte() % 4;
  const double total = kind == 3 ? 400.0 * b.unit() * static_cast<double>(a.size())
                                 : 8.0 * b.unit();
  for (double& x : a) {
    const double share = kind == 1 ? 2.0 * b.unit() : 1.0;
    x = total * share / static_cast<double>(a.size());
  }
  if (kind == 2 && !a.empty()) a[b.byte() % a.size()] = b.value(10.0);  // maybe NaN or < 0
}

template <class Plant>
Failure drive_plant(Plant& plant, Bytes& b, double scale) {
  std::vector<double> angles(plant.n_node_angles());
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    const std::uint8_t what = b.byte() % 16;
    if (what == 0) {
      plant.reset();
    } else if (what == 1) {
      route_angles(b, angles);
      plant.set_node_angles(angles.data());
    } else {
      const double x = b.value(scale);
      const double y = plant.step(x, b.dt());
      if (bad(x, y)) return {"plant: non-finite output for a finite input", op};
      if (plant.chain().last_solves() > plant.chain().max_solves())
        return {"plant: more solves in one step than max_solves()", op};
      if (!std::isfinite(x) && !has(plant.status(), Status::held_nonfinite_input))
        return {"plant: a non-finite input not reported held", op};
    }
  }
  return {};
}
}  // namespace detail_fuzz

// SingleTendonPlant, PullPullPlant (optionally with a damped load, distal dynamics and every
// rate effect) and ContinuumPlant, with few elements (the bound is a formula in N: small N
// keeps a case fast and reaches the bound as easily).
inline Failure plants(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  const int n = 2 + b.byte() % 23;
  const double mu = 0.5 * b.unit();
  const Route route = Route::uniform(0.2 + b.unit(), 6.0 * b.unit());
  switch (b.byte() % 4) {
    case 0: {
      SingleTendonParams p;
      p.elements = n;
      p.friction = mu;
      p.load_stiffness = 100.0 * b.unit();
      SingleTendonPlant plant(p, route);
      return drive_plant(plant, b, 0.01);
    }
    case 1: {
      PullPullParams p;
      p.elements = n;
      p.friction = mu;
      p.load_stiffness = 0.1 * b.unit();
      p.load_damping = 0.02 * b.unit();  // the damped load (SpringDamper)
      PullPullPlant plant(p, route);
      return drive_plant(plant, b, 2.0);
    }
    case 2: {
      PullPullParams p;
      p.elements = n;
      p.friction = mu;
      p.distal_inertia = 1e-4 * b.unit();
      p.distal_damping = 5e-3 * b.unit();
      p.sheath_viscosity = 10.0 * b.unit();
      p.relaxation_fraction = 0.3 * b.unit();
      PullPullPlant plant(p, route);
      return drive_plant(plant, b, 2.0);
    }
    default: {
      ContinuumParams p;
      p.elements = n;
      p.friction = mu;
      ContinuumPlant plant(p, route);
      return drive_plant(plant, b, 2.0);
    }
  }
}

// The drive: a position motor (ideal, or with reflected inertia, friction and gear backlash;
// PD or, one in two, PID with speed and acceleration limits some of the time) or a torque
// motor; torques from outside are random too.
inline Failure motor(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  MotorParams p;
  const std::uint8_t kind = b.byte() % 3;
  if (kind == 2) {
    p.kind = MotorKind::Torque;
    p.inertia = 1e-2;  // the rotor's
    p.coulomb_friction = 0.01 * b.unit();
  } else {
    p.bandwidth_hz = 1.0 + 100.0 * b.unit();
    p.damping = 0.2 + b.unit();
    if (kind == 1) {
      p.inertia = 1e-4 * (0.1 + b.unit());
      p.coulomb_friction = 0.01 * b.unit();
      p.viscous_friction = 1e-3 * b.unit();
    }
    const std::uint8_t servo = b.byte();
    if (servo % 2 == 1) {  // integral time from just above the stability bound to 100x it
      const double bound = 1.0 / (2.0 * p.damping * 2.0 * kPi * p.bandwidth_hz);
      p.integral_time = bound * (1.0 + 1e-6 + 100.0 * b.unit());
    }
    if (servo % 4 == 3) {
      p.max_speed = 0.1 + 10.0 * b.unit();
      p.max_accel = 1.0 + 1000.0 * b.unit();
    }
  }
  p.gear_backlash = 0.02 * b.unit();
  Motor m(p);
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    if (b.byte() % 16 == 0) {
      m.reset();
      continue;
    }
    const double u = b.value(2.0), tau = b.value(0.05);
    const double q = m.step(u, b.dt(), tau);
    if (std::isfinite(u) && std::isfinite(tau) && !std::isfinite(q))
      return {"motor: non-finite output for finite inputs", op};
  }
  return {};
}

// The sensor: noise and quantisation, and half the time a latency (up to 20 ms, sometimes
// beyond what a short history covers) read at random (and extreme) time steps.
inline Failure sensor(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  SensorParams p{1e-3 * b.unit(), 1e-3 * b.unit(), b.byte()};
  if (b.byte() % 2 == 1) {
    p.delay = 0.02 * b.unit();
    p.history = 1 + b.byte() % 64;
  }
  Sensor s(p);
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    if (b.byte() % 16 == 0) {
      s.reset();
      continue;
    }
    const double x = b.value(2.0);
    if (bad(x, s.measure(x, b.dt()))) return {"sensor: non-finite reading of a finite input", op};
    if (!std::isfinite(x) && !has(s.status(), Status::held_nonfinite_input))
      return {"sensor: a non-finite input not reported held", op};
  }
  return {};
}

// Every hysteresis model, stepped with the same inputs.
inline Failure models(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  BacklashParams bp;
  bp.c_r = 0.5 + b.unit();
  bp.c_l = 0.5 + b.unit();  // crossing branch lines included
  Backlash backlash(bp);
  BoucWenBacklash bwb(BoucWenBacklashParams{});
  BoucWen bw(BoucWenParams{});
  HystereticOscillator osc(HystereticOscillatorParams{});
  PrandtlIshlinskii pi(PrandtlIshlinskiiParams{{0.0, 0.1, 0.2}, {0.5, 0.3, 0.2}});
  GeneralizedPrandtlIshlinskii gpi(GeneralizedPrandtlIshlinskiiParams{});
  CurveAngleModel curve(CurveAngleParams{});
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    const std::uint8_t what = b.byte() % 32;
    if (what == 0) {
      backlash.reset(), bwb.reset(), bw.reset(), osc.reset(), pi.reset(), gpi.reset();
      curve.reset();
      continue;
    }
    const double x = b.value(2.0), dt = b.dt();
    if (what == 1) curve.set_curve_angle(b.value(10.0));
    if (what == 2) curve.set_shape(ShapeIntegrals{b.value(2.0), b.value(2.0), b.value(10.0)});
    if (bad(x, backlash.step(x))) return {"Backlash: non-finite output", op};
    if (bad(x, bwb.step(x, dt))) return {"BoucWenBacklash: non-finite output", op};
    if (bad(x, bw.step(x, dt))) return {"BoucWen: non-finite output", op};
    if (bad(x, osc.step(x, dt))) return {"HystereticOscillator: non-finite output", op};
    if (bad(x, pi.step(x))) return {"PrandtlIshlinskii: non-finite output", op};
    if (bad(x, gpi.step(x))) return {"GeneralizedPrandtlIshlinskii: non-finite output", op};
    if (bad(x, curve.step(x, dt))) return {"CurveAngleModel: non-finite output", op};
  }
  return {};
}

// A route change for a model inverse: a curve angle or a shape (maybe extreme or non-finite).
inline void route_change(ModelInverse& inv, Bytes& b) {
  using namespace detail_fuzz;
  if (b.byte() % 2) {
    inv.set_curve_angle(b.value(10.0));
    return;
  }
  const double mu = 0.5 * b.unit(), theta = b.value(8.0);
  ShapeIntegrals s = uniform_shape(mu, std::fabs(theta) < 1e3 ? std::fabs(theta) : 1.0);
  if (b.byte() % 4 == 0) s.g = b.value(2.0);  // maybe NaN, 0 or negative: ignored
  inv.set_shape(s);
}

// One ModelInverse (a kind of core chosen by the bytes), maybe with a bounded input range:
// a finite y_d gives a finite command, inside the range.
inline Failure model_inverse(Bytes& b) {
  using namespace detail_fuzz;
  const int kind = b.byte() % cases::kInverseCases;
  const bool ranged = b.byte() % 2;
  const InputRange range = ranged ? InputRange{-1.0, 1.0} : InputRange{};
  ModelInverse inv = cases::inverse_case(kind, range);
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    const std::uint8_t what = b.byte() % 32;
    if (what == 0) {
      inv.reset();
      continue;
    }
    if (what == 1) route_change(inv, b);
    const double y = b.value(1.0), dt = b.dt();
    const double x = inv.step(y, dt);
    if (bad(y, x)) return {"ModelInverse: non-finite command", op};
    if (std::isfinite(x) && !range.contains(x)) return {"ModelInverse: command outside its range", op};
  }
  return {};
}

// The models' inverses (desired output in, input out).
inline Failure inverses(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  if (b.byte() % 2) return model_inverse(b);
  PrandtlIshlinskiiInverse pi(PrandtlIshlinskiiParams{{0.0, 0.1, 0.2}, {0.5, 0.3, 0.2}});
  GeneralizedPrandtlIshlinskiiInverse gpi(GeneralizedPrandtlIshlinskiiParams{});
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    if (b.byte() % 32 == 0) {
      pi.reset(), gpi.reset();
      continue;
    }
    const double y = b.value(2.0);
    if (bad(y, pi.step(y))) return {"PrandtlIshlinskiiInverse: non-finite output", op};
    if (bad(y, gpi.step(y))) return {"GeneralizedPrandtlIshlinskiiInverse: non-finite output", op};
  }
  return {};
}

// An encoder loop with gains from the bytes (from 0 to extreme), maybe limited.
inline EncoderLoop encoder_loop(Bytes& b) {
  EncoderLoopParams p;
  p.kp = 10.0 * b.unit() * (b.byte() % 8 == 0 ? 1e6 : 1.0);
  p.ki = 1e3 * b.unit() * (b.byte() % 8 == 0 ? 1e6 : 1.0);
  p.kd = 0.01 * b.unit();
  p.derivative_cutoff_hz = 1.0 + 500.0 * b.unit();
  if (b.byte() % 2 == 0) p.max_correction = 0.01 + b.unit();
  if (b.byte() % 2 == 0) p.limits.max = 0.5 + b.unit(), p.limits.min = -p.limits.max;
  return EncoderLoop(p);
}

// A learned correction table from the bytes (1 to 64 samples of up to +-1e3, maybe limited).
inline LearnedCorrection learned_correction(Bytes& b) {
  LearnedFeedforwardParams p;
  p.table_dt = 1e-4 + 0.1 * b.unit();
  p.hold_last = b.byte() % 2 == 0;
  if (b.byte() % 2 == 0) p.limits.max = 0.5 + b.unit(), p.limits.min = -p.limits.max;
  std::vector<double> table(1 + b.byte() % 64);
  for (double& c : table) c = (2.0 * b.unit() - 1.0) * (b.byte() % 8 == 0 ? 1e3 : 0.1);
  return LearnedCorrection(std::move(table), p);
}

// A tip loop with gains from the bytes (from 0 to extreme), maybe limited, maybe scheduled.
inline TipLoop tip_loop(Bytes& b) {
  TipLoopParams p;
  p.kp = 10.0 * b.unit() * (b.byte() % 8 == 0 ? 1e6 : 1.0);
  p.ki = 1e3 * b.unit() * (b.byte() % 8 == 0 ? 1e6 : 1.0);
  p.kd = 0.01 * b.unit();
  p.derivative_cutoff_hz = 1.0 + 500.0 * b.unit();
  if (b.byte() % 2 == 0) p.max_correction = 0.01 + b.unit();
  if (b.byte() % 2 == 0) p.limits.max = 0.5 + b.unit(), p.limits.min = -p.limits.max;
  p.schedule_size = b.byte() % (TipLoopParams::kMaxSchedule + 1);
  double angle = b.unit();
  for (std::size_t i = 0; i < p.schedule_size; ++i) {
    p.schedule_angles[i] = angle;
    p.schedule_gains[i] = 0.01 + 10.0 * b.unit();
    angle += 0.01 + b.unit();
  }
  return TipLoop(p);
}

// Every compensator, with measurement dropouts (NaN) for the adaptive controller and curve
// angle changes for the curve-angle feedforward; the encoder loop gets a random encoder, the tip
// loop a random tip reading (NaN for a dropout) and curve angle.
inline Failure compensators(const std::uint8_t* data, std::size_t size) {
  using namespace detail_fuzz;
  Bytes b(data, size);
  BacklashInverseFeedforward inverse(BacklashInverseParams{});
  CurveAngleFeedforward curve(CurveAngleFeedforwardParams{});
  ContinuumFeedforward continuum(ContinuumFeedforwardParams{});
  AdaptiveController adaptive(AdaptiveControllerParams{});
  EncoderLooped<BacklashInverseFeedforward> looped(inverse, encoder_loop(b));
  LearnedFeedforward<CurveAngleFeedforward> learned(curve, learned_correction(b));
  TipLooped<CurveAngleFeedforward> tipped(curve, tip_loop(b));
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    const std::uint8_t what = b.byte() % 32;
    if (what == 0) {
      inverse.reset(), curve.reset(), continuum.reset(), adaptive.reset(), looped.reset();
      learned.reset(), tipped.reset();
      continue;
    }
    if (what == 1) curve.set_curve_angle(b.value(10.0));
    if (what == 2) tipped.set_curve_angle(b.value(10.0));
    const double y = b.value(2.0), dt = b.dt();
    const double meas = b.value(2.0), motor_q = b.value(2.0);
    if (bad(y, inverse.step(y, dt))) return {"BacklashInverseFeedforward: non-finite", op};
    if (bad(y, curve.step(y, dt))) return {"CurveAngleFeedforward: non-finite", op};
    if (bad(y, continuum.step(y, dt))) return {"ContinuumFeedforward: non-finite", op};
    if (bad(y, adaptive.step(y, meas, motor_q, dt)))
      return {"AdaptiveController: non-finite torque", op};
    if (bad(y, looped.step(y, motor_q, dt))) return {"EncoderLoop: non-finite command", op};
    if (bad(y, learned.step(y, dt))) return {"LearnedFeedforward: non-finite command", op};
    const double tip = what == 3 ? NAN : meas;
    if (bad(y, tipped.step(y, tip, dt))) return {"TipLoop: non-finite command", op};
  }
  return {};
}

namespace detail_fuzz {
// One class built from its default parameters, stepped and reset as the bytes say.
template <class C>
Failure listed_one(const std::uint8_t* data, std::size_t size, const char* rule) {
  Bytes b(data, size);
  C stepped{typename C::Params{}};
  for (long op = 0; op < kMaxOps && !b.done(); ++op) {
    if (b.byte() % 32 == 0) {
      stepped.reset();
      continue;
    }
    const double x = b.value(2.0), dt = b.dt();
    if (bad(x, stepped.step(x, dt))) return {rule, op};
  }
  return {};
}
}  // namespace detail_fuzz

// Every forward model and every feedforward of the core's lists (models/model_list.hpp,
// compensators/compensator_list.hpp), each built from its default parameters and fed the same
// bytes: a class added to a list is fuzzed without a line of its own. The one rule checked is a
// finite output for a finite input, so a failure's rule names the class that broke it.
inline Failure listed(const std::uint8_t* data, std::size_t size) {
  Failure failure{};
  cases::for_each_listed_stepper([&](auto tag, const char* kind) {
    using C = typename decltype(tag)::type;
    if (!failure.rule) failure = detail_fuzz::listed_one<C>(data, size, kind);
  });
  return failure;
}

using Driver = Failure (*)(const std::uint8_t*, std::size_t);

struct Target {
  const char* name;
  Driver run;
};

inline const Target* targets() {
  static const Target kTargets[] = {{"plants", plants},         {"motor", motor},
                                    {"sensor", sensor},         {"models", models},
                                    {"inverses", inverses},     {"compensators", compensators},
                                    {"listed", listed},         {nullptr, nullptr}};
  return kTargets;
}

}  // namespace tendonsheath::fuzz
