// An encoder-like sensor: y = quantise(x + noise), with Gaussian noise of
// standard deviation noise_std and quantisation to multiples of resolution
// (0: none). The noise comes from a seeded splitmix64 generator and a
// Box-Muller transform, so a seed gives the same sequence on every platform.
// With a latency (delay > 0) the reading is of the true value delay seconds
// ago, linearly interpolated between the samples kept in a ring buffer of
// `history` samples (allocated at construction); noise and quantisation apply
// to that delayed value.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of Sensor (validated by its constructor).
struct SensorParams {
  double resolution = 0.0;  ///< quantisation step (same unit as x), 0 = none
  double noise_std = 0.0;   ///< Gaussian noise standard deviation
  std::uint64_t seed = 0;  ///< seed of the noise generator: a seed gives the same sequence on every platform
  double delay = 0.0;  ///< latency, s, >= 0: a reading is of x delay seconds ago (0 = none)
  int history = 1024;  ///< samples kept for the delay, in [1, 2^24] (allocated at construction)
};

/// The parameter table of SensorParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<SensorParams> {
  static constexpr const char* owner = "Sensor";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("resolution", &SensorParams::resolution, "input", non_negative(),
            "quantisation step (same unit as x), 0 = none"),
      param("noise_std", &SensorParams::noise_std, "input", non_negative(),
            "Gaussian noise standard deviation"),
      param("seed", &SensorParams::seed, "", any(),
            "seed of the noise generator: a seed gives the same sequence on every platform"),
      param("delay", &SensorParams::delay, "s", non_negative(),
            "latency: a reading is of x delay seconds ago (0 = none)"),
      param("history", &SensorParams::history, "samples", documented(1, true, 16777216, true),
            "samples kept for the delay (allocated at construction)"));
};

/// @brief An encoder-like sensor: y = quantise(x(t - delay) + noise), Gaussian noise of standard
/// deviation noise_std and quantisation to multiples of resolution (0: none).
///
/// The noise comes from a seeded splitmix64 generator and a Box-Muller transform. With delay > 0
/// measure(x, dt) stores x in a ring buffer of `history` samples and reads the true value delay
/// seconds ago, linearly interpolated between stored samples (the first stored sample until
/// there is enough history; the oldest kept one, flagged input_clamped, when the history is too
/// short for the delay). measure() is noexcept, allocates nothing and does O(log history) work;
/// reset() restarts the noise sequence from the seed and empties the history.
class Sensor {
  static constexpr double kPi = 3.14159265358979323846;

 public:
  /// The parameter struct its constructor takes.
  using Params = SensorParams;

  /// The most samples a history may keep.
  static constexpr int kMaxHistory = 1 << 24;

  /// @param p the parameters; throws std::invalid_argument when resolution, noise_std or delay is
  /// not >= 0 (finite) or history is not in [1, kMaxHistory].
  explicit Sensor(const Params& p) : p_(p) {
    validate_fields(p, "Sensor");  // resolution, noise_std, delay: from ParamTable<SensorParams>
    require(p.history >= 1 && p.history <= kMaxHistory, "Sensor", "history must be in [1, ",
            kMaxHistory, "] samples (got ", p.history, ")");
    if (detail::failed()) return;  // without exceptions, in make(): no history of a bad size
    if (p.delay > 0.0) {
      times_.resize(static_cast<std::size_t>(p.history));
      values_.resize(static_cast<std::size_t>(p.history));
    }
    reset();
  }
  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The last reading's status: held_nonfinite_input when x was not finite, input_clamped when
  /// the history no longer held the value delay seconds ago (the oldest kept one was read).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    if (clamped_) s |= Status::input_clamped;
    return s;
  }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    state_ = p_.seed;
    have_spare_ = false;
    last_ = 0.0;
    now_ = 0.0;
    count_ = 0;
    head_ = 0;
    dropped_ = false;
    held_ = clamped_ = false;
  }

  /// One reading of the true value x, dt seconds after the previous call; a non-finite x
  /// repeats the last reading (time still passes) and is not stored.
  /// @param x the true value now
  /// @param dt the time since the previous call, s (0, or not finite and > 0: no time passes; a
  /// second value at the same time replaces the first)
  /// @return the reading: x delay seconds ago plus noise, quantised (the last reading when x is
  /// not finite)
  double measure(double x, double dt = 0.0) noexcept {
    held_ = !std::isfinite(x);
    clamped_ = false;
    if (dt > 0.0 && dt < std::numeric_limits<double>::infinity()) now_ += dt;
    if (held_) return last_;
    double y = p_.delay > 0.0 ? delayed(x) : x;
    if (p_.noise_std > 0.0) y += p_.noise_std * gaussian();
    // past 2^52 steps y / resolution is an integer already (and it may overflow): kept
    if (p_.resolution > 0.0 && std::fabs(y / p_.resolution) < 4503599627370496.0)
      y = p_.resolution * std::round(y / p_.resolution);
    last_ = y;
    return y;
  }

 private:
  // Store x at the current time (replacing the newest sample when no time has passed since it)
  // and return the stored signal at now - delay.
  double delayed(double x) noexcept {
    const std::size_t cap = times_.size();
    if (count_ > 0 && !(now_ > times_[head_])) {
      values_[head_] = x;
    } else {
      head_ = count_ == 0 ? 0 : (head_ + 1) % cap;
      if (count_ < cap) ++count_;
      else dropped_ = true;
      times_[head_] = now_;
      values_[head_] = x;
    }
    return at(now_ - p_.delay);
  }
  // The i-th stored sample from the oldest (0) to the newest (count_ - 1).
  std::size_t slot(std::size_t i) const noexcept {
    const std::size_t cap = times_.size();
    return (head_ + cap - (count_ - 1) + i) % cap;
  }
  // The stored signal at time tau: linear between the samples around it, the oldest before
  // them (flagged when older samples were dropped), the newest after them.
  double at(double tau) noexcept {
    if (times_[slot(0)] > tau) {
      clamped_ = dropped_;
      return values_[slot(0)];
    }
    std::size_t lo = 0, hi = count_ - 1;  // invariant: t(lo) <= tau, and t(hi) > tau or hi = last
    if (times_[slot(hi)] <= tau) return values_[slot(hi)];
    while (hi - lo > 1) {
      const std::size_t mid = lo + (hi - lo) / 2;
      if (times_[slot(mid)] <= tau) lo = mid;
      else hi = mid;
    }
    const double t0 = times_[slot(lo)], t1 = times_[slot(hi)];
    const double x0 = values_[slot(lo)], x1 = values_[slot(hi)];
    const double y = x0 + (x1 - x0) * ((tau - t0) / (t1 - t0));
    return std::isfinite(y) ? y : (tau - t0 < t1 - tau ? x0 : x1);  // extremes: the nearer one
  }

  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform01() noexcept {  // in (0, 1)
    return (static_cast<double>(next() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  }
  double gaussian() noexcept {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    const double u1 = uniform01(), u2 = uniform01();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    have_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

  Params p_;
  std::uint64_t state_ = 0;
  double spare_ = 0.0;
  double last_ = 0.0;
  bool have_spare_ = false;
  bool held_ = false;
  bool clamped_ = false;       // the last reading wanted a sample older than the history
  std::vector<double> times_;  // ring buffer of the stored samples' times (delay > 0)
  std::vector<double> values_;  // and of their values
  double now_ = 0.0;            // the clock: the sum of measure()'s dt since reset()
  std::size_t count_ = 0;       // samples stored
  std::size_t head_ = 0;        // slot of the newest one
  bool dropped_ = false;        // a sample was overwritten since reset()
};

}  // namespace tendonsheath
