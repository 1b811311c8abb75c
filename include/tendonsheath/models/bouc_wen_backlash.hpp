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

#include "../status.hpp"
#include "../validate.hpp"
#include "power.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of BoucWenBacklash (validated by its constructor).
struct BoucWenBacklashParams {
  double c_r = 1.0;  ///< slope of the right (rising) branch, > 0
  double c_l = 1.0;  ///< slope of the left (falling) branch, > 0
  double B_r = 0.1;  ///< dead-band offset of the right branch, input units, >= 0
  double B_l = 0.1;  ///< dead-band offset of the left branch, input units, >= 0
  double rho = 10.0;   ///< transition rate, 1/input unit (spec default 2/(B_r+B_l))
  double sigma = 1.0;  ///< shape, >= 0.5
  double n = 4.0;      ///< sharpness, >= 1
  double max_step = 0.05;  ///< largest rho*|dx| per RK4 sub-step
  int max_substeps = 256;  ///< most RK4 sub-steps in one step(), >= 1 (bounds its work)

  /// How many identifiable parameters assign() reads: the table's Role::parameter rows
  /// (checked against it below the table).
  static constexpr std::size_t vector_size = 7;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the order of the table's
  /// parameter rows (the Python param_names); the options are kept.
  void assign(const double* v) noexcept;
};

/// The parameter table of BoucWenBacklashParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<BoucWenBacklashParams> {
  static constexpr const char* owner = "BoucWenBacklash";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("c_r", &BoucWenBacklashParams::c_r, "output/input", positive(),
            "slope of the right (rising) branch"),
      param("c_l", &BoucWenBacklashParams::c_l, "output/input", positive(),
            "slope of the left (falling) branch"),
      param("B_r", &BoucWenBacklashParams::B_r, "input", non_negative(),
            "dead-band offset of the right branch"),
      param("B_l", &BoucWenBacklashParams::B_l, "input", non_negative(),
            "dead-band offset of the left branch"),
      param("rho", &BoucWenBacklashParams::rho, "1/input", positive(),
            "transition rate (spec default 2/(B_r+B_l))"),
      param("sigma", &BoucWenBacklashParams::sigma, "", at_least(0.5),
            "shape of the transition"),
      param("n", &BoucWenBacklashParams::n, "", at_least(1.0),
            "sharpness of the transition"),
      option("max_step", &BoucWenBacklashParams::max_step, "", positive(),
            "largest rho*|dx| per RK4 sub-step"),
      option("max_substeps", &BoucWenBacklashParams::max_substeps, "", documented(1, true, kInf, false),
            "most RK4 sub-steps in one step() (bounds its work)"));
};

static_assert(BoucWenBacklashParams::vector_size == parameter_count<BoucWenBacklashParams>(),
              "vector_size is the number of the table's parameter rows");
inline void BoucWenBacklashParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

namespace detail {
// |w|^P for a compile-time integer P (the usual sharpness exponents).
template <int P>
struct FixedPower {
  double operator()(double a) const noexcept {
    if constexpr (P == 0) return 1.0;
    else if constexpr (P == 1) return a;
    else {
      const double h = FixedPower<P / 2>{}(a);
      return (P % 2) ? h * h * a : h * h;
    }
  }
};

// dw/d|x| of the normalised Bouc-Wen state, s = direction of motion:
//   rho [s - |w|^(n-1) (sigma w - (sigma - 1) s |w|)]
template <class Power>
struct NormalisedBoucWen {
  double rho, sigma;
  Power pow_nm1;
  double operator()(double w, double s) const noexcept {
    const double a = std::fabs(w);
    return rho * (s - pow_nm1(a) * (sigma * w - (sigma - 1.0) * s * a));
  }
};

// Intermediate RK4 stages are kept inside [-1, 1] without branches.
inline double clamp_stage(double w) noexcept { return std::fmin(1.0, std::fmax(-1.0, w)); }

template <class F>
double rk4_in_x(const F& f, double w, double s, double h, int m) noexcept {
  for (int i = 0; i < m; ++i) {
    const double k1 = f(w, s);
    const double k2 = f(clamp_stage(w + 0.5 * h * k1), s);
    const double k3 = f(clamp_stage(w + 0.5 * h * k2), s);
    const double k4 = f(clamp_stage(w + h * k3), s);
    w = clamp_unit(w + h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
    // within 1e-12 of the attracting fixed point w = s the remaining sub-steps cannot leave
    // it (the caller snaps it to s): the work is bounded by the transition, not the travel
    if (w * s >= 1.0 - 1e-12) return s;
  }
  return w;
}

inline int substeps_for(double scaled_travel, double max_step, int max_substeps) noexcept {
  const double m = std::ceil(scaled_travel / max_step);
  if (!(m >= 1.0)) return 1;
  return m > max_substeps ? max_substeps : static_cast<int>(m);
}
}  // namespace detail

/// @brief Backlash-like hysteresis of Do et al.\ (spec D.1): a normalised Bouc-Wen state w in
/// [-1, 1] blends the two backlash branches.
///
/// dw = rho [dx - sigma |dx| |w|^(n-1) w + (sigma - 1) dx |w|^n], phi = (1 + w) / 2 and
/// y = phi c_r (x - B_r) + (1 - phi) c_l (x + B_l); w is integrated in x by RK4 (at most
/// max_substeps sub-steps a step). Rate-independent.
class BoucWenBacklash {
 public:
  /// The parameter struct its constructor takes.
  using Params = BoucWenBacklashParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit BoucWenBacklash(const Params& p) : p_(p) {
    const char* w = "BoucWenBacklash";
    validate_fields(p, w);  // c_r .. max_step, from ParamTable<BoucWenBacklashParams>
    require(p.max_substeps >= 1, w, "max_substeps must be >= 1");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    f_ = detail::NormalisedBoucWen<detail::AbsPower>{p.rho, p.sigma, detail::AbsPower(p.n - 1.0)};
    const double e = p.n - 1.0;
    int_exponent_ = (e == std::round(e) && e >= 0.0 && e <= 11.0) ? static_cast<int>(e) : -1;
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    initialised_ = false;
    w_ = 0.0;
  }

  /// @brief One sample: move the input to x and return the output y.
  /// @param x the input; a non-finite x is ignored and the last output held (0 before the first step)
  /// @return the output y; the first call after reset() starts with w = 0 at x
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    kept_ = false;
    if (held_) return initialised_ ? y_ : 0.0;
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
        const int m = p_.rho * travel <= p_.max_step  // the usual case: one RK4 step
                          ? 1
                          : detail::substeps_for(p_.rho * travel, p_.max_step, p_.max_substeps);
        double w = integrate(sgn, travel / m, m);
        // w approaches +-1 geometrically and would stall one ulp short of it; within 1e-12
        // of the fixed point it is the fixed point (the output moves by < 1e-12 B).
        if (1.0 - std::fabs(w) < 1e-12) w = w > 0.0 ? 1.0 : -1.0;
        kept_ = !std::isfinite(w);
        if (!kept_) w_ = w;  // an overflowing jump keeps the old state
      }
      x_ = x;
    }
    y_ = output_at(x_, w_);
    return y_;
  }

  /// The output y for input x and state w (no change of state).
  double output_at(double x, double w) const noexcept {
    const double phi = 0.5 * (1.0 + w);
    return phi * p_.c_r * (x - p_.B_r) + (1.0 - phi) * p_.c_l * (x + p_.B_l);
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input (input not finite), not_converged (the
  /// integration overflowed and the state was kept).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return kept_ ? s | Status::not_converged : s;
  }
  /// The blending state w, in [-1, 1].
  double state() const noexcept { return w_; }
  /// Put the model at input x with state w (clamped to [-1, 1]), for inverses and identification.
  void set_state(double x, double w) noexcept {
    x_ = x;
    w_ = detail::clamp_unit(w);
    y_ = output_at(x_, w_);
    initialised_ = true;
  }

 private:
  // The exponent n - 1 is dispatched once per sample, not once per evaluation.
  double integrate(double sgn, double h, int m) const noexcept {
    const double r = p_.rho, sg = p_.sigma;
    switch (int_exponent_) {
      case 0: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<0>>{r, sg, {}}, w_, sgn, h, m);
      case 1: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<1>>{r, sg, {}}, w_, sgn, h, m);
      case 2: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<2>>{r, sg, {}}, w_, sgn, h, m);
      case 3: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<3>>{r, sg, {}}, w_, sgn, h, m);
      case 4: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<4>>{r, sg, {}}, w_, sgn, h, m);
      case 5: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<5>>{r, sg, {}}, w_, sgn, h, m);
      case 6: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<6>>{r, sg, {}}, w_, sgn, h, m);
      case 7: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<7>>{r, sg, {}}, w_, sgn, h, m);
      case 8: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<8>>{r, sg, {}}, w_, sgn, h, m);
      case 9: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<9>>{r, sg, {}}, w_, sgn, h, m);
      case 10: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<10>>{r, sg, {}}, w_, sgn, h, m);
      case 11: return detail::rk4_in_x(detail::NormalisedBoucWen<detail::FixedPower<11>>{r, sg, {}}, w_, sgn, h, m);
      default: return detail::rk4_in_x(f_, w_, sgn, h, m);
    }
  }

  Params p_;
  detail::NormalisedBoucWen<detail::AbsPower> f_{};
  int int_exponent_ = -1;  // n - 1 when it is an integer in 0..11, else -1
  double x_ = 0.0, w_ = 0.0, y_ = 0.0;
  bool initialised_ = false;
  bool held_ = false, kept_ = false;
};

}  // namespace tendonsheath
