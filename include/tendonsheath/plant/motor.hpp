// Motor models that turn a command into the proximal pulley angle (rad) or,
// for a SingleTendonPlant, the proximal displacement (m).
//
// Position: a position-controlled drive seen as a second-order lag,
//   q'' = w^2 (q_cmd - q) - 2 zeta w q',   w = 2 pi f_n,
// with |q''| <= max_accel and |q'| <= max_speed; integrated with backward
// Euler on sub-steps of w h <= 0.1 (at most max_substeps). The first step
// after reset() starts at rest at the command.
// Torque: J q'' + b q' = sat(tau_cmd, max_torque) + tau_ext, where tau_ext
// is the torque the tendons exert on the pulley (supplied by the caller);
// semi-implicit Euler on the same sub-steps (h <= J/b/10 when b > 0). It
// starts at rest at q = 0.
#pragma once

#include <cmath>
#include <limits>

#include "../validate.hpp"

namespace tendonsheath {

enum class MotorKind : int { Position = 0, Torque = 1 };

struct MotorParams {
  MotorKind kind = MotorKind::Position;
  double bandwidth_hz = 1.5;  // natural frequency f_n (position)
  double damping = 0.7;       // zeta (position)
  double max_speed = std::numeric_limits<double>::infinity();  // rad/s (both)
  double max_accel = std::numeric_limits<double>::infinity();  // rad/s^2 (position)
  double inertia = 1e-2;      // J (torque)
  double viscous = 0.2;       // b (torque)
  double max_torque = std::numeric_limits<double>::infinity();  // (torque)
  int max_substeps = 256;
};

class Motor {
  static constexpr double kPi = 3.14159265358979323846;

 public:
  using Params = MotorParams;

  explicit Motor(const Params& p) : p_(p) {
    const char* w = "Motor";
    require(p.kind == MotorKind::Position || p.kind == MotorKind::Torque, w, "unknown kind");
    require(p.max_speed > 0.0 && !std::isnan(p.max_speed), w,
            "max_speed must be > 0 (got " + detail::format_value(p.max_speed) + ")");
    require(p.max_substeps >= 1, w, "max_substeps must be >= 1");
    if (p.kind == MotorKind::Position) {
      require_positive(p.bandwidth_hz, w, "bandwidth_hz");
      require_positive(p.damping, w, "damping");
      require(p.max_accel > 0.0 && !std::isnan(p.max_accel), w,
              "max_accel must be > 0 (got " + detail::format_value(p.max_accel) + ")");
    } else {
      require_positive(p.inertia, w, "inertia");
      require_non_negative(p.viscous, w, "viscous");
      require(p.max_torque > 0.0 && !std::isnan(p.max_torque), w,
              "max_torque must be > 0 (got " + detail::format_value(p.max_torque) + ")");
    }
  }

  const Params& params() const noexcept { return p_; }
  void reset() noexcept {
    q_ = 0.0;
    v_ = 0.0;
    initialised_ = false;
  }

  // Advance by dt under command u (angle or torque); returns the position.
  // A non-finite command holds the last position.
  double step(double u, double dt, double tau_ext = 0.0) noexcept {
    if (!std::isfinite(u)) return q_;
    if (!std::isfinite(tau_ext)) tau_ext = 0.0;
    if (!initialised_) {
      initialised_ = true;
      if (p_.kind == MotorKind::Position) q_ = u;
      v_ = 0.0;
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) return q_;
    const double rate = p_.kind == MotorKind::Position
                            ? 2.0 * kPi * p_.bandwidth_hz
                            : (p_.viscous > 0.0 ? p_.viscous / p_.inertia : 0.0);
    double m = std::ceil(dt * rate / 0.1);
    const int n = m >= p_.max_substeps ? p_.max_substeps : (m >= 1.0 ? static_cast<int>(m) : 1);
    const double h = dt / n;
    for (int i = 0; i < n; ++i) {
      double v_new;
      if (p_.kind == MotorKind::Position) {
        const double w = 2.0 * kPi * p_.bandwidth_hz;
        v_new = (v_ + h * w * w * (u - q_)) / (1.0 + 2.0 * p_.damping * w * h + w * w * h * h);
        const double amax = p_.max_accel * h;
        if (v_new - v_ > amax) v_new = v_ + amax;
        if (v_new - v_ < -amax) v_new = v_ - amax;
      } else {
        double tau = u;
        if (tau > p_.max_torque) tau = p_.max_torque;
        if (tau < -p_.max_torque) tau = -p_.max_torque;
        v_new = (v_ + h * (tau + tau_ext) / p_.inertia) / (1.0 + h * p_.viscous / p_.inertia);
      }
      if (v_new > p_.max_speed) v_new = p_.max_speed;
      if (v_new < -p_.max_speed) v_new = -p_.max_speed;
      v_ = v_new;
      q_ += h * v_;
    }
    return q_;
  }

  double position() const noexcept { return q_; }
  double velocity() const noexcept { return v_; }
  void set_state(double q, double v) noexcept {
    q_ = q;
    v_ = v;
    initialised_ = true;
  }

 private:
  Params p_;
  double q_ = 0.0, v_ = 0.0;
  bool initialised_ = false;
};

}  // namespace tendonsheath
