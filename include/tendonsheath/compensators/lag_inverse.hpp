// The proper inverse of Python's linear blocks (unit static gain), for Hammerstein and Wiener
// chains: a deadbeat inverse of their sampled form would ring (the first-order hold puts a
// sampling zero near -1), so the inverse is a filter with its own corner.
//
//   FirstOrderLag 1/(tau s + 1)          -> (tau s + 1) / (tau_f s + 1)
//   SecondOrderLag w^2/(s^2+2 z w s+w^2) -> (s^2/w^2 + 2 z s/w + 1) / (s/w_f + 1)^2
//
// tau_f = 1 / w_f, w_f = 2 pi min(filter_hz, 0.2 / dt), discretised by Tustin at each step's dt
// (the coefficients are recomputed, in bounded work, when dt changes by more than 1e-9 of
// itself: sample times' rounding does not redesign the filter). The block's output then
// follows the desired one through 1/(tau_f s + 1) (first order) or 1/(s/w_f + 1)^2 (second).
// It starts at rest at its first input (output = input), as the blocks do.
#pragma once

#include <cmath>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of LagInverse (validated by its constructor).
struct LagInverseParams {
  int order = 1;                ///< 1: FirstOrderLag, 2: SecondOrderLag
  double time_constant = 0.05;  ///< the first-order lag's tau, s, > 0
  double frequency = 5.0;       ///< the second-order lag's natural frequency, Hz, > 0
  double damping = 0.7;         ///< the second-order lag's damping ratio, > 0
  double filter_hz = 0.0;       ///< the inverse's corner, Hz, > 0; 0: 5 x the block's corner

  /// The block's corner frequency, Hz: 1 / (2 pi tau), or frequency.
  double corner_hz() const noexcept {
    return order == 1 ? 1.0 / (2.0 * 3.14159265358979323846 * time_constant) : frequency;
  }
};

namespace detail {
/// The rows of a first-order lag only (time_constant).
constexpr bool is_first_order(const LagInverseParams& p) { return p.order == 1; }
/// The rows of a second-order lag only (frequency, damping).
constexpr bool is_second_order(const LagInverseParams& p) { return p.order == 2; }
}  // namespace detail

/// The parameter table of LagInverseParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<LagInverseParams> {
  static constexpr const char* owner = "LagInverse";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("order", &LagInverseParams::order, "", documented(1, true, 2, true),
            "1: FirstOrderLag, 2: SecondOrderLag"),
      only_if(param("time_constant", &LagInverseParams::time_constant, "s", positive(),
                    "the first-order lag's tau"),
              &detail::is_first_order, "order 1"),
      only_if(param("frequency", &LagInverseParams::frequency, "Hz", positive(),
                    "the second-order lag's natural frequency"),
              &detail::is_second_order, "order 2"),
      only_if(param("damping", &LagInverseParams::damping, "", positive(),
                    "the second-order lag's damping ratio"),
              &detail::is_second_order, "order 2"),
      param("filter_hz", &LagInverseParams::filter_hz, "Hz", documented(0.0, true, kInf, false),
            "the inverse's corner; 0: 5 x the block's corner"));
};

/// @brief The inverse of a unit-gain first- or second-order lag: a Tustin filter with its own
/// corner (see the file's comment); step() is noexcept, allocation-free and O(1).
class LagInverse {
 public:
  /// The parameter struct its constructor takes.
  using Params = LagInverseParams;

  /// @param p the block and the filter corner; throws std::invalid_argument naming a bad one.
  explicit LagInverse(const Params& p) : p_(p) {
    const char* w = "LagInverse";
    require(p.order == 1 || p.order == 2, w, "order must be 1 or 2 (got ", p.order, ")");
    validate_fields(p, w);  // each field's own bound, from ParamTable<LagInverseParams>
    require(std::isfinite(p.filter_hz) && p.filter_hz >= 0.0, w,
            "filter_hz must be > 0, or 0 for the default (got ", p.filter_hz, ")");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    if (p_.filter_hz == 0.0) p_.filter_hz = 5.0 * p_.corner_hz();
  }

  /// The parameters (filter_hz resolved).
  const Params& params() const noexcept { return p_; }
  /// Start afresh: the next step starts at rest at its input.
  void reset() noexcept {
    primed_ = false;
    dt_ = 0.0;
  }
  /// @param u the desired block output; a non-finite one holds the last output
  /// @param dt the time since the previous step, s (a dt that is not finite and > 0 holds)
  /// @return the block input that makes its output follow u through the filter
  double step(double u, double dt) noexcept {
    held_ = !std::isfinite(u);
    if (held_) return y_;
    if (!primed_) {  // at rest at u: the steady state of the filter
      s2_ = (b_[2] - a_[2]) * u;
      s1_ = (b_[1] - a_[1]) * u + s2_;
      y_ = u;
      last_u_ = u;
      primed_ = true;
      return y_;
    }
    if (!(dt > 0.0) || !std::isfinite(dt)) return y_;
    if (std::fabs(dt - dt_) > 1e-9 * dt) redesign(dt);  // not for a jitter of rounding
    y_ = b_[0] * u + s1_;
    s1_ = b_[1] * u - a_[1] * y_ + s2_;
    s2_ = b_[2] * u - a_[2] * y_;
    last_u_ = u;
    return y_;
  }
  /// The last step's status: held_nonfinite_input when its input was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }
  /// The corner in use, Hz (filter_hz capped at 0.2 / dt).
  double corner_in_use() const noexcept { return corner_; }

 private:
  // Tustin s = K (1 - z^-1) / (1 + z^-1), K = 2 / dt; the steady state carries over
  void redesign(double dt) noexcept {
    const double u = last_u_;
    const double hz = p_.filter_hz < 0.2 / dt ? p_.filter_hz : 0.2 / dt;
    const double wf = 2.0 * 3.14159265358979323846 * hz, K = 2.0 / dt;
    corner_ = hz;
    double n[3], d[3];  // s^2, s, 1 coefficients
    if (p_.order == 1) {
      n[0] = 0.0, n[1] = p_.time_constant, n[2] = 1.0;
      d[0] = 0.0, d[1] = 1.0 / wf, d[2] = 1.0;
    } else {
      const double w = 2.0 * 3.14159265358979323846 * p_.frequency;
      n[0] = 1.0 / (w * w), n[1] = 2.0 * p_.damping / w, n[2] = 1.0;
      d[0] = 1.0 / (wf * wf), d[1] = 2.0 / wf, d[2] = 1.0;
    }
    const double K2 = K * K;
    const double a0 = d[0] * K2 + d[1] * K + d[2];
    b_[0] = (n[0] * K2 + n[1] * K + n[2]) / a0;
    b_[1] = 2.0 * (n[2] - n[0] * K2) / a0;
    b_[2] = (n[0] * K2 - n[1] * K + n[2]) / a0;
    a_[1] = 2.0 * (d[2] - d[0] * K2) / a0;
    a_[2] = (d[0] * K2 - d[1] * K + d[2]) / a0;
    if (p_.order == 1) {  // first order: no common factor (1 + z^-1), no mode at Nyquist
      const double c0 = d[1] * K + d[2];
      b_[0] = (n[1] * K + n[2]) / c0;
      b_[1] = (n[2] - n[1] * K) / c0;
      b_[2] = 0.0;
      a_[1] = (d[2] - d[1] * K) / c0;
      a_[2] = 0.0;
    }
    if (dt_ == 0.0) {  // the first design: at rest at the last input
      s2_ = (b_[2] - a_[2]) * u;
      s1_ = (b_[1] - a_[1]) * u + s2_;
    }
    dt_ = dt;
  }

  Params p_;
  double b_[3] = {1.0, 0.0, 0.0}, a_[3] = {1.0, 0.0, 0.0};
  double s1_ = 0.0, s2_ = 0.0, y_ = 0.0, last_u_ = 0.0;
  double dt_ = 0.0, corner_ = 0.0;
  bool primed_ = false, held_ = false;
};

}  // namespace tendonsheath
