// A tip-feedback loop around any feedforward: a PI(D) loop on the measured tip angle (an EM
// tracker, a distal encoder) around the motor's position servo, its gains scheduled over the
// route's curve angle.
//
// A feedforward computes the motor command x_ff its model says gives the desired output y_d.
// Whatever the model misses (friction drift, a changed route, wear) shows at the tip. TipLoop
// adds a correction from the tip reading y:
//   e_k = y_d[k-1] - y_k             (y_k: the tip now, the result of the last command)
//   I_k = I_{k-1} + s ki e_k dt       (clamped to +-max_correction; held while the command is cut
//                                      in the direction e_k pushes: anti-windup)
//   D_k = low-pass(de/dt, derivative_cutoff_hz)
//   u_k = shape(x_ff[k] + clamp(s kp e_k + I_k + s kd D_k, +-max_correction))
// s is the gain schedule: the piecewise-linear interpolation of schedule_gains at the curve angle
// last set (set_curve_angle, set_shape), clamped at the ends; 1 with an empty schedule. The sign
// convention: a larger motor command gives a larger tip angle.
// A non-finite tip reading (a dropout) falls back toward the feedforward: the P and D terms are
// zeroed, the integral is held, status fallback.
// A new route shape (set_shape, set_curve_angle) is bumpless: a feedforward that follows the route
// moves its command at once by what the new shape changes, and the integral has already taken up
// most of that change from the tip error (shape sensing comes late); the step of the feedforward's
// command beyond its last cycle's trend is taken out of the integral on the next cycle, so the
// change is not corrected twice.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "../physics/pull_pull_statics.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "encoder_loop.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of TipLoop (validated by its constructor); angles in rad.
struct TipLoopParams {
  /// The most points a gain schedule holds.
  static constexpr std::size_t kMaxSchedule = 8;
  double kp = 0.0;  ///< proportional gain on the tip error, rad of command per rad of tip, >= 0
  double ki = 0.0;  ///< integral gain, 1/s, >= 0
  double kd = 0.0;  ///< derivative gain, s, >= 0
  double derivative_cutoff_hz = 50.0;  ///< corner of the derivative's first-order low-pass, Hz, > 0
  double max_correction = std::numeric_limits<double>::infinity();  ///< largest |correction|, rad, > 0
  std::size_t schedule_size = 0;  ///< points in the gain schedule, 0 (s = 1) to kMaxSchedule
  std::array<double, kMaxSchedule> schedule_angles{};  ///< curve angles, rad, finite, strictly increasing
  std::array<double, kMaxSchedule> schedule_gains{};  ///< gain factors s at those angles, finite, > 0
  CommandLimits limits{};  ///< the servo command's limits (after the correction)
};

/// The parameter table of TipLoopParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<TipLoopParams> {
  static constexpr const char* owner = "TipLoop";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("kp", &TipLoopParams::kp, "rad/rad", non_negative(),
            "proportional gain on the tip error"),
      param("ki", &TipLoopParams::ki, "1/s", non_negative(),
            "integral gain"),
      param("kd", &TipLoopParams::kd, "s", non_negative(),
            "derivative gain"),
      param("derivative_cutoff_hz", &TipLoopParams::derivative_cutoff_hz, "Hz", positive(),
            "corner of the derivative's first-order low-pass"),
      param("max_correction", &TipLoopParams::max_correction, "rad", documented(0.0, false, kInf, true),
            "largest |correction|"),
      param("limits", &TipLoopParams::limits, "", any(),
            "CommandLimits: the command's min, max and max_rate"));
};

/// @brief A PI(D) loop on the tip angle around a feedforward's motor command, its gains scheduled
/// over the route's curve angle.
///
/// correct(target, y_d, measured, dt) compares the tip reading with the desired output of the
/// previous cycle (the tip now is the result of the last command), integrates that error with
/// anti-windup and returns the servo command target + correction, shaped to the limits.
class TipLoop {
 public:
  /// The parameter struct its constructor takes.
  using Params = TipLoopParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit TipLoop(const Params& p) : p_(p), shaper_(p.limits) {
    const char* w = "TipLoop";
    validate_fields(p, w);  // kp, ki, kd, derivative_cutoff_hz, from ParamTable<TipLoopParams>
    require(p.max_correction > 0.0, w, "max_correction must be > 0 (got ", p.max_correction, ")");
    require(p.schedule_size <= Params::kMaxSchedule, w, "schedule_size must be <= ",
            Params::kMaxSchedule, " (got ", p.schedule_size, ")");
    if (detail::failed()) return;  // without exceptions, in make(): no entry read past the arrays
    for (std::size_t i = 0; i < p.schedule_size; ++i) {
      require(std::isfinite(p.schedule_angles[i]), w, "schedule_angles[", i, "] must be finite (got ",
              p.schedule_angles[i], ")");
      require(i == 0 || p.schedule_angles[i] > p.schedule_angles[i - 1], w,
              "schedule_angles must be strictly increasing (schedule_angles[", i, "] = ",
              p.schedule_angles[i], " after ", i == 0 ? 0.0 : p.schedule_angles[i - 1], ")");
      require(std::isfinite(p.schedule_gains[i]) && p.schedule_gains[i] > 0.0, w, "schedule_gains[",
              i, "] must be > 0 and finite (got ", p.schedule_gains[i], ")");
    }
    p.limits.validate(w);
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    scale_ = scale_at(0.0);
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters and the curve
  /// angle set since are kept.
  void reset() noexcept {
    primed_ = have_error_ = shape_changed_ = false;
    targets_ = 0;
    integral_ = derivative_ = error_ = correction_ = cut_ = 0.0;
    last_target_ = trend_ = 0.0;
    shaper_.reset();
    held_ = fallback_ = limited_ = angle_flag_ = angle_rejected_ = false;
  }

  /// @brief The route's curve angle for the gain schedule (from shape sensing).
  /// @param angle the total curve angle, rad; a non-finite or negative one is ignored (the last
  /// angle is kept) and reported as input_clamped by status() until the end of the next cycle
  /// @return whether the angle was taken
  bool set_curve_angle(double angle) noexcept {
    angle_rejected_ = !(std::isfinite(angle) && angle >= 0.0);
    if (angle_rejected_) return false;
    shape_changed_ = shape_changed_ || angle != curve_angle_ || targets_ == 0;
    curve_angle_ = angle;
    scale_ = scale_at(angle);
    return true;
  }
  /// The route's shape: its curve_angle is the curve angle (set_curve_angle).
  bool set_shape(const ShapeIntegrals& s) noexcept { return set_curve_angle(s.curve_angle); }

  /// @brief One cycle: the servo command for a feedforward target, from the tip reading.
  /// @param target the feedforward's motor command this cycle, rad; a non-finite one holds the last command
  /// @param y_d the desired output this cycle, rad; a non-finite one holds the last command
  /// @param measured the tip angle now, rad; a non-finite one (dropout) zeroes the P and D terms
  /// and holds the integral (fallback)
  /// @param dt the time since the previous cycle, s (not finite or <= 0: nothing is integrated)
  /// @return the servo command target + correction, within the limits
  double correct(double target, double y_d, double measured, double dt) noexcept {
    angle_flag_ = angle_rejected_;
    angle_rejected_ = false;
    held_ = !std::isfinite(target) || !std::isfinite(y_d);
    fallback_ = !std::isfinite(measured);
    if (held_) {
      cut_ = 0.0;
      return shaper_.apply(NAN, dt);
    }
    transfer_shape_change(target);
    if (fallback_) {
      // toward the feedforward: no P, no D, the integral held
      derivative_ = 0.0;
      have_error_ = false;  // no derivative kick when the reading returns
      correction_ = integral_;
      limited_ = false;
    } else if (primed_ && dt > 0.0 && std::isfinite(dt)) {
      update(last_y_d_ - measured, dt);
    }
    last_y_d_ = y_d;
    primed_ = true;
    const double raw = target + correction_;
    const double u = shaper_.apply(raw, dt);
    cut_ = u - raw;  // < 0: the command was cut from above, > 0: from below
    return u;
  }

  /// The correction added to the last target, rad.
  double correction() const noexcept { return correction_; }
  /// The integral term, rad.
  double integral() const noexcept { return integral_; }
  /// The last tip error (previous desired output minus the tip reading), rad.
  double error() const noexcept { return error_; }
  /// The gain schedule's factor s at the curve angle now (1 with no schedule).
  double gain_scale() const noexcept { return scale_; }
  /// The curve angle the schedule is at, rad (0 until one is set).
  double curve_angle() const noexcept { return curve_angle_; }
  /// Whether the last cycle had no tip reading (the P and D terms were zeroed).
  bool in_fallback() const noexcept { return fallback_; }

  /// The last cycle's status: held_nonfinite_input (the target or y_d was not finite), fallback
  /// (no tip reading), saturated (the command was cut to its limits, or the correction to
  /// max_correction), input_clamped (a curve angle was ignored: not finite or negative).
  Status status() const noexcept {
    Status s = shaper_.status();
    if (held_) s |= Status::held_nonfinite_input;
    if (fallback_) s |= Status::fallback;
    if (limited_) s |= Status::saturated;
    if (angle_flag_ || angle_rejected_) s |= Status::input_clamped;
    return s;
  }

 private:
  // bumpless shape change: the feedforward's step beyond its trend leaves the integral
  void transfer_shape_change(double target) noexcept {
    if (shape_changed_ && targets_ >= 2) {
      const double jump = (target - last_target_) - trend_;
      if (std::isfinite(jump)) integral_ = clamp(integral_ - jump);
      correction_ = integral_;  // recomputed by update() when there is a reading
    }
    shape_changed_ = false;
    if (targets_ >= 1) trend_ = target - last_target_;
    last_target_ = target;
    if (targets_ < 2) ++targets_;
  }
  // the schedule's piecewise-linear factor at curve angle a, clamped at the ends
  double scale_at(double a) const noexcept {
    const std::size_t n = p_.schedule_size;
    if (n == 0) return 1.0;
    const auto& x = p_.schedule_angles;
    const auto& g = p_.schedule_gains;
    if (a <= x[0]) return g[0];
    for (std::size_t i = 1; i < n; ++i)
      if (a < x[i]) return g[i - 1] + (a - x[i - 1]) / (x[i] - x[i - 1]) * (g[i] - g[i - 1]);
    return g[n - 1];
  }
  void update(double e, double dt) noexcept {
    const double s = scale_;
    const double tau = 1.0 / (2.0 * 3.14159265358979323846 * p_.derivative_cutoff_hz);
    if (have_error_) {
      const double rate = (e - error_) / dt;
      const double a = dt / (tau + dt);  // backward Euler of the first-order low-pass
      if (std::isfinite(rate)) derivative_ += a * (rate - derivative_);
    }
    error_ = e;
    have_error_ = true;
    // anti-windup: no integration in the direction the shaper is already cutting
    const bool blocked = (cut_ < 0.0 && e > 0.0) || (cut_ > 0.0 && e < 0.0);
    if (!blocked) integral_ = clamp(integral_ + s * p_.ki * e * dt);
    const double raw = s * p_.kp * e + integral_ + s * p_.kd * derivative_;
    correction_ = clamp(raw);
    limited_ = correction_ != raw;
    if (!std::isfinite(correction_) || !std::isfinite(integral_) || !std::isfinite(derivative_)) {
      correction_ = integral_ = derivative_ = 0.0;
      have_error_ = false;
    }
  }
  double clamp(double c) const noexcept {
    const double m = p_.max_correction;
    return c > m ? m : (c < -m ? -m : c);
  }

  Params p_;
  CommandShaper shaper_{};
  double last_y_d_ = 0.0, integral_ = 0.0, derivative_ = 0.0, error_ = 0.0;
  double correction_ = 0.0, cut_ = 0.0, curve_angle_ = 0.0, scale_ = 1.0;
  bool primed_ = false, have_error_ = false, held_ = false, fallback_ = false, limited_ = false;
  bool angle_flag_ = false, angle_rejected_ = false;
  double last_target_ = 0.0, trend_ = 0.0;  // the feedforward's last command and its last step
  int targets_ = 0;  // targets seen since reset, up to 2
  bool shape_changed_ = false;  // a new shape since the last cycle
};

namespace detail {
template <class T, class = void>
struct FollowsCurveAngle : std::false_type {};
template <class T>
struct FollowsCurveAngle<T, std::void_t<decltype(std::declval<T&>().set_curve_angle(0.0))>>
    : std::true_type {};
}  // namespace detail

/// @brief Any feedforward (step(y_d, dt)) with a TipLoop around it: step(y_d, y, dt).
/// @tparam Feedforward BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
/// CurveAngleFeedforward, ContinuumFeedforward, ModelInverse, or any class with step(y_d, dt),
/// reset() and status()
template <class Feedforward>
class TipLooped {
 public:
  /// @param ff the feedforward (its command is the loop's target)
  /// @param loop the tip loop around the servo
  TipLooped(Feedforward ff, TipLoop loop) : ff_(std::move(ff)), loop_(std::move(loop)) {}

  /// Start afresh: both the feedforward and the loop (the curve angle is kept).
  void reset() noexcept {
    ff_.reset();
    loop_.reset();
  }
  /// @param y_d the desired output
  /// @param y the tip reading, rad (NaN: no reading this cycle)
  /// @param dt the time since the previous cycle, s
  /// @return the servo command
  double step(double y_d, double y, double dt) noexcept {
    return loop_.correct(ff_.step(y_d, dt), y_d, y, dt);
  }
  /// Passes a route shape to a feedforward that follows the route, and its curve angle to the loop.
  void set_shape(const ShapeIntegrals& s) noexcept {
    if constexpr (detail::FollowsShape<Feedforward>::value) ff_.set_shape(s);
    loop_.set_shape(s);
  }
  /// Passes a uniform curve angle to a feedforward that follows the route, and to the loop.
  void set_curve_angle(double angle) noexcept {
    if constexpr (detail::FollowsCurveAngle<Feedforward>::value) ff_.set_curve_angle(angle);
    loop_.set_curve_angle(angle);
  }
  /// The feedforward's and the loop's flags of the last step.
  Status status() const noexcept { return ff_.status() | loop_.status(); }
  /// The feedforward inside.
  Feedforward& feedforward() noexcept { return ff_; }
  /// The tip loop.
  const TipLoop& loop() const noexcept { return loop_; }

 private:
  Feedforward ff_;
  TipLoop loop_;
};

}  // namespace tendonsheath
