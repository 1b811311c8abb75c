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
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept { primed_ = false; }
  bool primed() const noexcept { return primed_; }
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

struct CommandLimits {
  double min = -std::numeric_limits<double>::infinity();  // smallest command
  double max = std::numeric_limits<double>::infinity();   // largest command
  double max_rate = std::numeric_limits<double>::infinity();  // |d command / dt| limit, per s

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
  explicit CommandShaper(const CommandLimits& limits) : lim_(limits) {}
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept { primed_ = false; }
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
  double last() const noexcept { return last_; }
  /// The last apply(): held_nonfinite_input (command not finite: the last one held),
  /// saturated (the command was cut to the limits or the rate limit).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return saturated_ ? s | Status::saturated : s;
  }
  const CommandLimits& limits() const noexcept { return lim_; }

 private:
  double clamp(double c) const noexcept { return c < lim_.min ? lim_.min : (c > lim_.max ? lim_.max : c); }
  CommandLimits lim_{};
  double last_ = 0.0;
  bool primed_ = false;
  bool held_ = false, saturated_ = false;
};

}  // namespace tendonsheath
