// The inverse of HystereticOscillator (force in, displacement out) by inverting its dynamics:
// a deadbeat root of the sampled oscillator would ring (relative degree 2: a sampling zero
// near -1), so the force is computed from the desired displacement filtered by
// 1/(s/w_f + 1)^2:
//
//   y_f'' = w_f^2 (y_d - y_f) - 2 w_f y_f'                 (trapezoidal, at each step's dt)
//   z     integrated along y_f: dz/dy = alpha - beta |z|^(nu-1) (gamma s z + delta |z|),
//         s = sign(dy) (rate-independent, RK4 sub-steps in y)
//   u     = m y_f'' + c y_f' + k y_f + z
//
// so the oscillator's displacement follows y_f, y_d through the critically damped filter.
// w_f = 2 pi min(filter_hz, 0.2 / dt); filter_hz defaults to 5 x the natural frequency
// sqrt((k + alpha) / m) / (2 pi). The filter starts at the oscillator's rest, y_f = y_f' = 0.
#pragma once

#include <cmath>

#include "../models/hysteretic_oscillator.hpp"
#include "../models/power.hpp"
#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// @brief The force that makes a HystereticOscillator's displacement follow the desired one through
/// a critically damped filter (see the file's comment). step() is noexcept, allocation-free and
/// does at most 256 RK4 sub-steps.
class OscillatorInverse {
 public:
  /// @param p the oscillator (validated as HystereticOscillator does)
  /// @param filter_hz the filter corner, Hz, > 0; 0: 5 x the natural frequency
  /// Throws std::invalid_argument naming a bad parameter.
  OscillatorInverse(const HystereticOscillatorParams& p, double filter_hz) : p_(p) {
    (void)HystereticOscillator(p);  // the oscillator's own validation
    require(std::isfinite(filter_hz) && filter_hz >= 0.0, "OscillatorInverse",
            "filter_hz must be > 0, or 0 for the default (got ", filter_hz, ")");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    filter_hz_ = filter_hz > 0.0 ? filter_hz : 5.0 * natural_hz(p);
    derive();
  }

  /// The natural frequency of the oscillator's tangent at rest, Hz: sqrt((k + alpha) / m) / 2 pi.
  static double natural_hz(const HystereticOscillatorParams& p) noexcept {
    return std::sqrt((p.k + p.alpha) / p.m) / (2.0 * 3.14159265358979323846);
  }
  /// True when p's model parameters pass HystereticOscillator's checks (no exception).
  static bool valid(const HystereticOscillatorParams& p) noexcept {
    return std::isfinite(p.m) && p.m > 0.0 && std::isfinite(p.c) && p.c >= 0.0 &&
           std::isfinite(p.k) && p.k >= 0.0 && std::isfinite(p.alpha) && p.alpha >= 0.0 &&
           std::isfinite(p.beta) && p.beta >= 0.0 && std::isfinite(p.gamma) &&
           std::isfinite(p.delta) && std::isfinite(p.nu) && p.nu >= 1.0 && p.k + p.alpha > 0.0;
  }
  /// New model parameters (a route that changed them), the filter and z kept; the filter corner
  /// stays. False (nothing changed) when they are not valid().
  bool set_params(const HystereticOscillatorParams& p) noexcept {
    if (!valid(p)) return false;
    p_ = p;
    derive();
    return true;
  }
  /// New model parameters by HystereticOscillatorParams::assign order (m, c, k, alpha, beta,
  /// gamma, delta, nu).
  bool set_base_params(const double* values) noexcept {
    HystereticOscillatorParams p = p_;
    p.assign(values);
    return set_params(p);
  }

  /// The model parameters.
  const HystereticOscillatorParams& params() const noexcept { return p_; }
  /// The filter corner asked for, Hz (before the 0.2 / dt cap).
  double filter_hz() const noexcept { return filter_hz_; }
  /// Start afresh: the filter and z at the oscillator's rest.
  void reset() noexcept {
    primed_ = false;
    y_ = v_ = z_ = 0.0;
  }

  /// @param y_d the desired displacement; a non-finite one holds the last force
  /// @param dt the time since the previous step, s (a dt that is not finite and > 0 holds)
  /// @return the force
  double step(double y_d, double dt) noexcept {
    held_ = !std::isfinite(y_d);
    if (held_) return u_;
    if (!primed_) {
      primed_ = true;
      r_ = y_d;
      return force(y_d, 2.0 * 3.14159265358979323846 * filter_hz_);
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) return u_;
    const double hz = filter_hz_ < 0.2 / dt ? filter_hz_ : 0.2 / dt;
    const double w = 2.0 * 3.14159265358979323846 * hz;
    const double y0 = y_;
    filter(y_d, w, dt);
    integrate_z(y_ - y0);
    r_ = y_d;
    return force(y_d, w);
  }
  /// The last step's status: held_nonfinite_input when y_d was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }
  /// The filtered displacement y_f the oscillator is driven to follow.
  double filtered() const noexcept { return y_; }

 private:
  void derive() noexcept { pow_ = detail::AbsPower(p_.nu - 1.0); }

  double force(double y_d, double w) noexcept {
    const double a = w * w * (y_d - y_) - 2.0 * w * v_;
    u_ = p_.m * a + p_.c * v_ + p_.k * y_ + z_;
    return u_;
  }

  // trapezoidal step of [y, v]' = [v, w^2 (r - y) - 2 w v], r linear from r_ to r1
  void filter(double r1, double w, double h) noexcept {
    const double w2 = w * w, hh = 0.5 * h;
    const double f1 = y_ + hh * v_;
    const double f2 = v_ + hh * (w2 * (r_ + r1 - y_) - 2.0 * w * v_);
    // (I - hh A) x1 = [f1, f2] with A = [[0, 1], [-w2, -2w]]
    const double m11 = 1.0, m12 = -hh, m21 = hh * w2, m22 = 1.0 + h * w;
    const double det = m11 * m22 - m12 * m21;
    y_ = (f1 * m22 - m12 * f2) / det;
    v_ = (m11 * f2 - m21 * f1) / det;
  }

  double dz_dy(double z, double s) const noexcept {
    const double az = std::fabs(z);
    return p_.alpha - p_.beta * pow_(az) * (p_.gamma * s * z + p_.delta * az);
  }

  void integrate_z(double dy) noexcept {
    if (dy == 0.0) return;
    const double s = dy > 0.0 ? 1.0 : -1.0;
    // RK4 stable and accurate where z relaxes fast: h |d(dz/dy)/dz| <= 1/20
    const double stiff = p_.beta * p_.nu * (std::fabs(p_.gamma) + std::fabs(p_.delta)) *
                         pow_(std::fabs(z_) + p_.alpha * std::fabs(dy));
    const double need = std::ceil(20.0 * std::fabs(dy) * stiff);
    const int m = need < 1.0 ? 1 : (need > 256.0 ? 256 : static_cast<int>(need));
    const double h = dy / m;
    double z = z_;
    for (int i = 0; i < m; ++i) {
      const double k1 = dz_dy(z, s);
      const double k2 = dz_dy(z + 0.5 * h * k1, s);
      const double k3 = dz_dy(z + 0.5 * h * k2, s);
      const double k4 = dz_dy(z + h * k3, s);
      z += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    }
    if (std::isfinite(z)) z_ = z;
  }

  HystereticOscillatorParams p_;
  detail::AbsPower pow_{};
  double filter_hz_ = 1.0;
  double y_ = 0.0, v_ = 0.0, z_ = 0.0, r_ = 0.0, u_ = 0.0;
  bool primed_ = false, held_ = false;
};

}  // namespace tendonsheath
