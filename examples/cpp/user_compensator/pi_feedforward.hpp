// A user's own compensator: the C++ twin of examples/09_user_compensator.py's PIFeedforward.
// It includes nothing from nanobind: the same class can run in a robot's real-time loop.
//
// u = gain * y_d + kp * e + ki * integral(e), e = y_d - y measured; during a dropout (y is NaN)
// the error counts as zero and the integral holds; the integral is clamped to
// +-integral_limit (anti-windup).
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

class PIFeedforward {
 public:
  explicit PIFeedforward(double gain = 1.0, double kp = 0.5, double ki = 5.0,
                         double integral_limit = 0.2)
      : gain_(finite(gain, "gain")),
        kp_(finite(kp, "kp")),
        ki_(finite(ki, "ki")),
        limit_(finite(integral_limit, "integral_limit")) {
    if (!(limit_ >= 0.0)) throw std::invalid_argument("PIFeedforward: integral_limit must be >= 0");
  }

  void reset() noexcept { integral_ = 0.0; }

  // the contract of tendonsheath/bench/erased_compensator.hpp: reference, measured, dt
  double step(double y_d, double y, double dt) noexcept {
    const double e = std::isfinite(y) ? y_d - y : 0.0;
    integral_ = std::min(std::max(integral_ + e * dt, -limit_), limit_);
    return gain_ * y_d + kp_ * e + ki_ * integral_;
  }

  double gain() const noexcept { return gain_; }
  double kp() const noexcept { return kp_; }
  double ki() const noexcept { return ki_; }
  double integral_limit() const noexcept { return limit_; }

 private:
  static double finite(double v, const char* name) {
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string("PIFeedforward: ") + name + " must be finite");
    return v;
  }
  double gain_, kp_, ki_, limit_;
  double integral_ = 0.0;
};
