// Backlash-like hysteresis of Do et al. (spec D.1): a normalised Bouc-Wen
// state w in [-1, 1] blends the two backlash branches.
//
//   dw = rho [dx - sigma |dx| |w|^(n-1) w + (sigma - 1) dx |w|^n]
//   phi = (1 + w) / 2
//   y = phi c_r (x - B_r) + (1 - phi) c_l (x + B_l)
//
// dw depends on dx only (rate-independent). Between samples x moves
// linearly, so w is integrated in x with RK4 sub-steps of at most
// rho |dx| <= max_step, capped at max_substeps to bound the work.
#pragma once

#include <cmath>
#include <cstddef>

#include "../validate.hpp"
#include "power.hpp"

namespace tendonsheath {

struct BoucWenBacklashParams {
  double c_r = 1.0;
  double c_l = 1.0;
  double B_r = 0.1;
  double B_l = 0.1;
  double rho = 10.0;   // transition rate, 1/input unit (spec default 2/(B_r+B_l))
  double sigma = 1.0;  // shape, >= 0.5
  double n = 4.0;      // sharpness, >= 1
  double max_step = 0.05;  // largest rho*|dx| per RK4 sub-step
  int max_substeps = 256;

  // The identifiable parameters as a flat vector, in the order of the Python
  // param_names (numerical options are left as they are).
  static constexpr std::size_t vector_size = 7;
  void assign(const double* v) noexcept {
    c_r = v[0]; c_l = v[1]; B_r = v[2]; B_l = v[3]; rho = v[4]; sigma = v[5]; n = v[6];
  }
};

namespace detail {
// dw/d|x| of the normalised Bouc-Wen state, s = direction of motion.
struct NormalisedBoucWen {
  double rho, sigma;
  AbsPower pow_nm1;
  double operator()(double w, double s) const noexcept {
    const double a = std::fabs(w);
    const double p = pow_nm1(a);  // |w|^(n-1)
    return rho * (s - sigma * p * w + (sigma - 1.0) * s * p * a);
  }
};

template <class F>
double rk4_in_x(const F& f, double w, double s, double h, int m) noexcept {
  for (int i = 0; i < m; ++i) {
    const double k1 = f(w, s);
    const double k2 = f(clamp_unit(w + 0.5 * h * k1), s);
    const double k3 = f(clamp_unit(w + 0.5 * h * k2), s);
    const double k4 = f(clamp_unit(w + h * k3), s);
    w = clamp_unit(w + h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
  }
  return w;
}

inline int substeps_for(double scaled_travel, double max_step, int max_substeps) noexcept {
  const double m = std::ceil(scaled_travel / max_step);
  if (!(m >= 1.0)) return 1;
  return m > max_substeps ? max_substeps : static_cast<int>(m);
}
}  // namespace detail

class BoucWenBacklash {
 public:
  using Params = BoucWenBacklashParams;
  static constexpr bool rate_independent = true;

  explicit BoucWenBacklash(const Params& p) : p_(p) {
    const char* w = "BoucWenBacklash";
    require_positive(p.c_r, w, "c_r");
    require_positive(p.c_l, w, "c_l");
    require_non_negative(p.B_r, w, "B_r");
    require_non_negative(p.B_l, w, "B_l");
    require_positive(p.rho, w, "rho");
    require_at_least(p.sigma, 0.5, w, "sigma");
    require_at_least(p.n, 1.0, w, "n");
    require_positive(p.max_step, w, "max_step");
    require(p.max_substeps >= 1, w, "max_substeps must be >= 1");
    f_ = detail::NormalisedBoucWen{p.rho, p.sigma, detail::AbsPower(p.n - 1.0)};
  }

  const Params& params() const noexcept { return p_; }

  void reset() noexcept {
    initialised_ = false;
    w_ = 0.0;
  }

  double step(double x, double /*dt*/ = 0.0) noexcept {
    if (!std::isfinite(x)) return initialised_ ? y_ : 0.0;
    if (!initialised_) {
      x_ = x;
      initialised_ = true;
    } else {
      const double dx = x - x_;
      // w = +-1 moving the same way is a fixed point (dw = 0 exactly): skip the work.
      const bool saturated = (dx > 0.0 && w_ >= 1.0) || (dx < 0.0 && w_ <= -1.0);
      if (dx != 0.0 && !saturated) {
        const double travel = std::fabs(dx);
        const double sgn = dx > 0.0 ? 1.0 : -1.0;
        double w;
        if (p_.rho * travel <= p_.max_step) {  // the usual case: one RK4 step
          w = detail::rk4_in_x(f_, w_, sgn, travel, 1);
        } else {
          const int m = detail::substeps_for(p_.rho * travel, p_.max_step, p_.max_substeps);
          w = detail::rk4_in_x(f_, w_, sgn, travel / m, m);
        }
        if (std::isfinite(w)) w_ = w;  // an overflowing jump keeps the old state
      }
      x_ = x;
    }
    y_ = output_at(x_, w_);
    return y_;
  }

  double output_at(double x, double w) const noexcept {
    const double phi = 0.5 * (1.0 + w);
    return phi * p_.c_r * (x - p_.B_r) + (1.0 - phi) * p_.c_l * (x + p_.B_l);
  }

  double output() const noexcept { return y_; }
  double state() const noexcept { return w_; }
  void set_state(double x, double w) noexcept {
    x_ = x;
    w_ = detail::clamp_unit(w);
    y_ = output_at(x_, w_);
    initialised_ = true;
  }

 private:
  Params p_;
  detail::NormalisedBoucWen f_{};
  double x_ = 0.0, w_ = 0.0, y_ = 0.0;
  bool initialised_ = false;
};

}  // namespace tendonsheath
