// Pieces every compensator shares: a smooth direction switch, a finite-
// difference rate of the desired trajectory, and the motor's limits.
#pragma once

#include <cmath>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// phi = (1 + tanh(v / v_eps)) / 2: 1 moving forward, 0 moving backward, 1/2 at
/// rest (spec D.2, B2). v_eps is the smoothing speed (2-5 % of the peak speed).
inline double smooth_direction(double velocity, double v_eps) noexcept {
  return 0.5 * (1.0 + std::tanh(velocity / v_eps));
}

/// Backward-difference rate of a sampled signal; 0 on the first sample.
class RateEstimator {
 public:
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { primed_ = false; }
  /// True once update() has seen a sample since construction or reset().
  bool primed() const noexcept { return primed_; }
  /// @param value the new sample
  /// @param dt the time since the last sample, s (a dt that is not finite and > 0 gives rate 0)
  /// @return (value - last) / dt, or 0 on the first sample
  double update(double value, double dt) noexcept {
    double rate = 0.0;
    if (primed_ && dt > 0.0 && std::isfinite(dt)) rate = (value - last_) / dt;
    last_ = value;
    primed_ = true;
    return rate;
  }

 private:
  double last_ = 0.0;
  bool primed_ = false;
};

/// The motor command's limits, in command units (rad for a motor angle); unbounded by default.
struct CommandLimits {
  double min = -std::numeric_limits<double>::infinity();  ///< smallest command
  double max = std::numeric_limits<double>::infinity();   ///< largest command
  double max_rate = std::numeric_limits<double>::infinity();  ///< |d command / dt| limit, per s

  /// Throws std::invalid_argument (message starting with `where`) unless min < max and max_rate > 0.
  void validate(const char* where) const {
    require(!std::isnan(min) && !std::isnan(max) && min < max, where,
            "command limits need min < max (got min=", min, ", max=", max, ")");
    require(max_rate > 0.0, where, "max_rate must be > 0 (got ", max_rate, ")");
  }
};

/// Saturates a command to the limits and its rate of change; holds the last
/// command on non-finite input, so the output is never NaN.
class CommandShaper {
 public:
  CommandShaper() = default;
  /// @param limits the limits; not validated here (the compensators that own a shaper validate them).
  explicit CommandShaper(const CommandLimits& limits) : lim_(limits) {}
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { primed_ = false; }
  /// @brief Shape one command.
  /// @param command the raw command; a non-finite one holds the last command (the clamped 0 at first)
  /// @param dt the time since the last command, s (the rate limit allows max_rate dt of change)
  /// @return the command clamped to [min, max] and to the rate limit
  double apply(double command, double dt) noexcept {
    held_ = !std::isfinite(command);
    if (held_) {
      saturated_ = false;
      return primed_ ? last_ : clamp(0.0);
    }
    double c = clamp(command);
    if (primed_ && std::isfinite(lim_.max_rate)) {
      const double step = lim_.max_rate * ((dt > 0.0 && std::isfinite(dt)) ? dt : 0.0);
      if (c > last_ + step) c = last_ + step;
      if (c < last_ - step) c = last_ - step;
    }
    saturated_ = c != command;
    last_ = c;
    primed_ = true;
    return c;
  }
  /// The last shaped command.
  double last() const noexcept { return last_; }
  /// The last apply(): held_nonfinite_input (command not finite: the last one held),
  /// saturated (the command was cut to the limits or the rate limit).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return saturated_ ? s | Status::saturated : s;
  }
  /// The limits.
  const CommandLimits& limits() const noexcept { return lim_; }

 private:
  double clamp(double c) const noexcept { return c < lim_.min ? lim_.min : (c > lim_.max ? lim_.max : c); }
  CommandLimits lim_{};
  double last_ = 0.0;
  bool primed_ = false;
  bool held_ = false, saturated_ = false;
};

}  // namespace tendonsheath
