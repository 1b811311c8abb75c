// Prandtl-Ishlinskii hysteresis: a weighted sum of play operators
//
//   y = sum_i p_i F_{r_i}[x],   F_r: z <- max(x - r, min(x + r, z))
//
// with thresholds 0 <= r_0 < r_1 < ... and weights p_i whose partial sums
// P_j = p_0 + ... + p_j are all > 0. With r_0 = 0 as well the loading curve
// is strictly increasing and the operator is invertible. The plays start on the virgin
// curve from 0: z_i = clamp(0, x_0 - r_i, x_0 + r_i).
//
// PrandtlIshlinskiiInverse solves, every step, the piecewise-linear equation
// y(x) = y_desired exactly along the breakpoints of the plays, and updates the
// same play states, so model(inverse(y)) == y and inverse(model(x)) == x up to
// rounding.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../compensators/input_range.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of PrandtlIshlinskii and PrandtlIshlinskiiInverse (validated by their constructors).
struct PrandtlIshlinskiiParams {
  std::vector<double> thresholds{0.0, 0.05, 0.1, 0.15, 0.2};  ///< play thresholds r_i >= 0, strictly increasing, input units (r_0 = 0 for the inverse)
  std::vector<double> weights{0.5, 0.2, 0.15, 0.1, 0.05};  ///< play weights p_i; every partial sum p_0 + ... + p_j must be > 0
};

/// The parameter table of PrandtlIshlinskiiParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<PrandtlIshlinskiiParams> {
  static constexpr const char* owner = "PrandtlIshlinskii";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = false;  ///< its constructor checks every bound by hand (an order of checks or a message of its own)
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("thresholds", &PrandtlIshlinskiiParams::thresholds, "input", any(),
            "play thresholds r_i >= 0, strictly increasing (r_0 = 0 for the inverse)"),
      param("weights", &PrandtlIshlinskiiParams::weights, "", any(),
            "play weights p_i; every partial sum p_0 + ... + p_j must be > 0"));
};

namespace detail {

inline void validate_pi(const PrandtlIshlinskiiParams& p, const char* w, bool invertible) {
  require(!p.thresholds.empty(), w, "thresholds must not be empty");
  require(p.thresholds.size() == p.weights.size(), w,
          "thresholds and weights must have the same length (got ", p.thresholds.size(), " and ",
          p.weights.size(), ")");
  if (detail::failed()) return;  // without exceptions, in make(): the vectors are not indexed
  if (invertible)
    require(p.thresholds.front() == 0.0, w,
            "thresholds[0] must be 0 for an invertible operator (a play with threshold 0 makes the "
            "loading curve strictly increasing; got ",
            p.thresholds.front(), ")");
  double partial = 0.0;
  for (std::size_t i = 0; i < p.thresholds.size(); ++i) {
    const std::string ri = "thresholds[" + std::to_string(i) + "]";
    const std::string pi = "weights[" + std::to_string(i) + "]";
    require_non_negative(p.thresholds[i], w, ri.c_str());
    require_finite(p.weights[i], w, pi.c_str());
    if (i > 0)
      require(p.thresholds[i] > p.thresholds[i - 1], w, "thresholds must be strictly increasing");
    partial += p.weights[i];
    require(partial > 0.0, w,
            "partial sums of weights must be > 0 for an invertible operator (weights[0...", i,
            "] sum to ", partial, ")");
  }
}

// The largest input magnitude the operator accepts, 1e9 (1 + the largest threshold):
// inputs are clamped to it. Far beyond any use, it keeps the plays' sums finite and the
// round-off left after a return from it below 1e-6 (1 + r_max).
inline double pi_input_limit(const PrandtlIshlinskiiParams& p) noexcept {
  return 1e9 * (1.0 + p.thresholds.back());
}

inline double clamp_play(double z, double x, double r) noexcept {
  const double lo = x - r, hi = x + r;
  return z < lo ? lo : (z > hi ? hi : z);
}

}  // namespace detail

/// @brief Prandtl-Ishlinskii hysteresis: y = sum_i p_i F_{r_i}[x], a weighted sum of play
/// operators F_r: z <- max(x - r, min(x + r, z)).
///
/// The plays start on the virgin curve from 0. The play states are allocated once, in the
/// constructor; step() does O(number of plays) work. Rate-independent.
class PrandtlIshlinskii {
 public:
  /// The parameter struct its constructor takes.
  using Params = PrandtlIshlinskiiParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the thresholds and weights; throws std::invalid_argument naming the first bad entry.
  explicit PrandtlIshlinskii(const Params& p) : p_(p), z_(p.thresholds.size(), 0.0) {
    detail::validate_pi(p, "PrandtlIshlinskii", false);
    if (detail::failed()) return;  // without exceptions, in make(): thresholds may be empty
    x_limit_ = detail::pi_input_limit(p_);
  }
  /// The last step's input was beyond +-input_limit() and was clamped to it.
  bool input_clamped() const noexcept { return clamped_; }
  /// The largest input magnitude accepted, 1e9 (1 + the largest threshold); beyond it inputs are
  /// clamped.
  double input_limit() const noexcept { return x_limit_; }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { initialised_ = false; }

  /// @param x the input; a non-finite x holds the last output, one beyond +-input_limit() is clamped
  /// @return the output y = sum_i p_i z_i
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    if (held_) {
      clamped_ = false;
      return initialised_ ? y_ : 0.0;
    }
    clamped_ = std::fabs(x) > x_limit_;
    if (clamped_) x = std::copysign(x_limit_, x);
    const std::size_t n = z_.size();
    double y = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double prev = initialised_ ? z_[i] : 0.0;
      z_[i] = detail::clamp_play(prev, x, p_.thresholds[i]);
      y += p_.weights[i] * z_[i];
    }
    initialised_ = true;
    x_ = x;
    y_ = y;
    return y;
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input (input not finite), input_clamped (see
  /// input_clamped()).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return clamped_ ? s | Status::input_clamped : s;
  }
  /// The input of the last step(), after clamping.
  double last_input() const noexcept { return x_; }
  /// The play states z_i, one per threshold.
  const std::vector<double>& play_states() const noexcept { return z_; }

 private:
  Params p_;
  std::vector<double> z_;
  double x_ = 0.0, y_ = 0.0;
  double x_limit_ = 1e300;
  bool clamped_ = false;
  bool held_ = false;
  bool initialised_ = false;
};

/// @brief The exact inverse of PrandtlIshlinskii (thresholds[0] must be 0): every step solves the
/// piecewise-linear equation y(x) = y_desired along the breakpoints of the plays.
///
/// It updates the same play states, so model(inverse(y)) == y and inverse(model(x)) == x up to
/// rounding. step() does O(number of plays) work and allocates nothing.
class PrandtlIshlinskiiInverse {
 public:
  /// The parameter struct its constructor takes.
  using Params = PrandtlIshlinskiiParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the thresholds (thresholds[0] == 0) and weights; throws std::invalid_argument naming the
  /// first bad entry.
  explicit PrandtlIshlinskiiInverse(const Params& p) : p_(p), z_(p.thresholds.size(), 0.0) {
    detail::validate_pi(p, "PrandtlIshlinskiiInverse", true);
    if (detail::failed()) return;  // without exceptions, in make(): thresholds may be empty
    x_limit_ = detail::pi_input_limit(p_);
  }
  /// The last command was beyond +-input_limit() (or its target unreachable) and was clamped.
  bool input_clamped() const noexcept { return clamped_; }
  /// The largest command magnitude it returns, 1e9 (1 + the largest threshold).
  double input_limit() const noexcept { return x_limit_; }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { initialised_ = false; }

  /// Returns the input x that drives the forward operator to y_desired.
  /// @param y_desired the desired output; a non-finite one holds the last command
  /// @return the command x, within +-input_limit()
  double step(double y_desired, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(y_desired);
    if (held_) {
      clamped_ = false;
      return initialised_ ? x_ : 0.0;
    }
    if (!initialised_) {
      // Virgin curve from the demagnetised state at x = 0.
      for (double& z : z_) z = 0.0;
      x_ = 0.0;
      initialised_ = true;
    }
    double y_now = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) y_now += p_.weights[i] * z_[i];
    // targets are kept within +-1e300 so that y_desired - y_now cannot overflow
    if (std::fabs(y_desired) > 1e300) y_desired = std::copysign(1e300, y_desired);
    double x = (y_desired >= y_now) ? solve_up(y_desired, y_now)
                                    : solve_down(y_desired, y_now);
    clamped_ = !(std::fabs(x) <= x_limit_);
    if (clamped_) x = std::isnan(x) ? x_ : std::copysign(x_limit_, x);
    x = range_.apply(x);  // the plays follow the command actually sent
    for (std::size_t i = 0; i < z_.size(); ++i) z_[i] = detail::clamp_play(z_[i], x, p_.thresholds[i]);
    x_ = x;
    return x;
  }

  /// The command x of the last step().
  double output() const noexcept { return x_; }
  /// The last step's status: held_nonfinite_input (input not finite), input_clamped (see
  /// input_clamped()), out_of_range (the command was held at the edge of set_range()'s range).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    if (!held_) s = s | range_.status();
    return clamped_ ? s | Status::input_clamped : s;
  }
  /// Keep the commands inside `range` (validated here; unbounded by default): a command beyond it
  /// is held at its edge, the plays follow it and status() reports out_of_range.
  void set_range(const InputRange& range) {
    range.validate("PrandtlIshlinskiiInverse");
    range_ = RangeGuard(range);
  }

 private:
  // Rising input: play i follows max(z_i, x - r_i); it engages at b_i = z_i + r_i,
  // which is non-decreasing in i for play states reached by any input history.
  double solve_up(double y_target, double y_now) const noexcept {
    double x = x_, y = y_now, slope = 0.0;
    const std::size_t n = z_.size();
    std::size_t i = 0;
    for (; i < n; ++i) {
      const double b = z_[i] + p_.thresholds[i];
      if (b > x) {
        if (slope > 0.0) {
          const double y_b = y + slope * (b - x);
          if (y_target <= y_b) return x + (y_target - y) / slope;
          y = y_b;
        }
        x = b;
      }
      slope += p_.weights[i];
    }
    return slope > 0.0 ? x + (y_target - y) / slope : x;
  }

  double solve_down(double y_target, double y_now) const noexcept {
    double x = x_, y = y_now, slope = 0.0;
    const std::size_t n = z_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const double b = z_[i] - p_.thresholds[i];
      if (b < x) {
        if (slope > 0.0) {
          const double y_b = y - slope * (x - b);
          if (y_target >= y_b) return x - (y - y_target) / slope;
          y = y_b;
        }
        x = b;
      }
      slope += p_.weights[i];
    }
    return slope > 0.0 ? x - (y - y_target) / slope : x;
  }

  Params p_;
  std::vector<double> z_;
  RangeGuard range_{};
  double x_ = 0.0;
  double x_limit_ = 1e300;
  bool clamped_ = false;
  bool held_ = false;
  bool initialised_ = false;
};

}  // namespace tendonsheath
