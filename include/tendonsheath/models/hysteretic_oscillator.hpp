// Single-degree-of-freedom oscillator with a Bouc-Wen restoring force:
//
//   m y'' + c y' + k y + z = u
//   z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu)
//
// force u in, displacement y out. Integrated by RK4 with a fixed number of
// sub-steps per sample (at least `substeps`, raised automatically so that
// h * omega <= 0.5 for stability, never above `max_substeps`). Between samples
// the input is interpolated linearly (default) or held.
#pragma once

#include <cmath>
#include <cstddef>

#include "../validate.hpp"
#include "power.hpp"

namespace tendonsheath {

struct HystereticOscillatorParams {
  double m = 1.0;
  double c = 0.1;
  double k = 1.0;
  double alpha = 1.0;
  double beta = 1.0;
  double gamma = 0.5;
  double delta = 0.5;
  double nu = 1.0;
  int substeps = 4;
  int max_substeps = 4096;
  bool hold_input = false;  // false: linear interpolation between samples

  // The identifiable parameters as a flat vector, in the order of the Python
  // param_names (numerical options are left as they are).
  static constexpr std::size_t vector_size = 8;
  void assign(const double* v) noexcept {
    m = v[0]; c = v[1]; k = v[2]; alpha = v[3]; beta = v[4]; gamma = v[5]; delta = v[6]; nu = v[7];
  }
};

class HystereticOscillator {
 public:
  using Params = HystereticOscillatorParams;
  static constexpr bool rate_independent = false;

  explicit HystereticOscillator(const Params& p) : p_(p) {
    const char* w = "HystereticOscillator";
    require_positive(p.m, w, "m");
    require_non_negative(p.c, w, "c");
    require_non_negative(p.k, w, "k");
    require_non_negative(p.alpha, w, "alpha");
    require_non_negative(p.beta, w, "beta");
    require_finite(p.gamma, w, "gamma");
    require_finite(p.delta, w, "delta");
    require_at_least(p.nu, 1.0, w, "nu");
    require(p.k + p.alpha > 0.0, w, "k + alpha must be > 0 (no restoring force otherwise)");
    require(p.beta == 0.0 || p.gamma + p.delta > 0.0, w,
            "gamma + delta must be > 0 when beta > 0 (the hysteretic force is unbounded otherwise)");
    require(p.substeps >= 1, w, "substeps must be >= 1");
    require(p.max_substeps >= p.substeps, w, "max_substeps must be >= substeps");
    pow_num1_ = detail::AbsPower(p.nu - 1.0);
    omega_ = std::sqrt((p.k + p.alpha) / p.m) + p.c / p.m;
  }

  const Params& params() const noexcept { return p_; }

  void reset() noexcept {
    initialised_ = false;
    y_ = v_ = z_ = 0.0;
  }

  // Starts at rest (y = y' = z = 0) at the first sample.
  double step(double u, double dt) noexcept {
    if (!std::isfinite(u)) return y_;
    if (!initialised_ || !(dt > 0.0) || !std::isfinite(dt)) {
      if (!initialised_) {
        initialised_ = true;
        u_ = u;
      }
      return y_;
    }
    const int m = substeps(dt);
    const double h = dt / m;
    const double du = p_.hold_input ? 0.0 : (u - u_) / dt;
    double st[3] = {y_, v_, z_};
    for (int i = 0; i < m; ++i) {
      const double t0 = i * h;
      double k1[3], k2[3], k3[3], k4[3], tmp[3];
      rhs(st, u_ + du * t0, k1);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + 0.5 * h * k1[j];
      rhs(tmp, u_ + du * (t0 + 0.5 * h), k2);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + 0.5 * h * k2[j];
      rhs(tmp, u_ + du * (t0 + 0.5 * h), k3);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + h * k3[j];
      rhs(tmp, u_ + du * (t0 + h), k4);
      for (int j = 0; j < 3; ++j) st[j] += h * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]) / 6.0;
    }
    if (std::isfinite(st[0]) && std::isfinite(st[1]) && std::isfinite(st[2])) {
      y_ = st[0];
      v_ = st[1];
      z_ = st[2];
    }
    u_ = u;
    return y_;
  }

  int substeps(double dt) const noexcept {
    const double need = std::ceil(dt * omega_ / 0.5);
    double m = need > p_.substeps ? need : p_.substeps;
    if (!(m <= p_.max_substeps)) m = p_.max_substeps;
    return static_cast<int>(m);
  }

  double output() const noexcept { return y_; }
  double velocity() const noexcept { return v_; }
  double hysteretic_force() const noexcept { return z_; }

 private:
  void rhs(const double* s, double u, double* d) const noexcept {
    const double y = s[0], v = s[1], z = s[2];
    const double az = std::fabs(z);
    const double q = pow_num1_(az);  // |z|^(nu-1)
    d[0] = v;
    d[1] = (u - p_.c * v - p_.k * y - z) / p_.m;
    d[2] = p_.alpha * v - p_.beta * (p_.gamma * std::fabs(v) * q * z + p_.delta * v * q * az);
  }

  Params p_;
  detail::AbsPower pow_num1_{};
  double omega_ = 1.0;
  double y_ = 0.0, v_ = 0.0, z_ = 0.0, u_ = 0.0;
  bool initialised_ = false;
};

}  // namespace tendonsheath
