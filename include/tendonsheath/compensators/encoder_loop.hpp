// A motor-encoder loop around any feedforward: no tip sensor, only the motor's own encoder.
//
// A feedforward computes the motor angle x_ff that its model says gives the desired output.
// A position servo that yields to the tendons' torque (no integral action) does not put the
// shaft there: the shaft lags and gives way differently in each direction. EncoderLoop closes
// a PI(D) loop on the encoder around the servo:
//   e_k = x_ff[k-1] - q_k            (q_k: the encoder now, where the last command took the shaft)
//   I_k = I_{k-1} + ki e_k dt         (clamped to +-max_correction; held while the command is cut
//                                      in the direction e_k pushes: anti-windup)
//   D_k = low-pass(de/dt, derivative_cutoff_hz)
//   u_k = shape(x_ff[k] + clamp(kp e_k + I_k + kd D_k, +-max_correction))
// A non-finite encoder reading (a dropout) holds the correction and reports fallback.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "../physics/pull_pull_statics.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of EncoderLoop (validated by its constructor); angles in rad.
struct EncoderLoopParams {
  double kp = 0.0;  ///< proportional gain on the encoder error, rad per rad, >= 0
  double ki = 20.0;  ///< integral gain, 1/s, >= 0
  double kd = 0.0;  ///< derivative gain, s, >= 0
  double derivative_cutoff_hz = 50.0;  ///< corner of the derivative's first-order low-pass, Hz, > 0
  double max_correction = std::numeric_limits<double>::infinity();  ///< largest |correction|, rad, > 0
  CommandLimits limits{};  ///< the servo command's limits (after the correction)
};

/// The parameter table of EncoderLoopParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<EncoderLoopParams> {
  static constexpr const char* owner = "EncoderLoop";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("kp", &EncoderLoopParams::kp, "rad/rad", non_negative(),
            "proportional gain on the encoder error"),
      param("ki", &EncoderLoopParams::ki, "1/s", non_negative(),
            "integral gain"),
      param("kd", &EncoderLoopParams::kd, "s", non_negative(),
            "derivative gain"),
      param("derivative_cutoff_hz", &EncoderLoopParams::derivative_cutoff_hz, "Hz", positive(),
            "corner of the derivative's first-order low-pass"),
      param("max_correction", &EncoderLoopParams::max_correction, "rad", documented(0.0, false, kInf, true),
            "largest |correction|"),
      param("limits", &EncoderLoopParams::limits, "", any(),
            "CommandLimits: the command's min, max and max_rate"));
};

/// @brief A PI(D) loop on the motor encoder that makes the shaft follow a feedforward's target.
///
/// correct(target, encoder, dt) compares the encoder with the target of the previous cycle
/// (where the last command took the shaft), integrates that error with anti-windup and returns the
/// servo command target + correction, shaped to the limits. No tip sensor is involved.
class EncoderLoop {
 public:
  /// The parameter struct its constructor takes.
  using Params = EncoderLoopParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit EncoderLoop(const Params& p) : p_(p), shaper_(p.limits) {
    const char* w = "EncoderLoop";
    // kp, ki, kd, derivative_cutoff_hz from ParamTable<EncoderLoopParams> (the two finiteness
    // checks below cannot fail first: >= 0 and > 0 already require finite values)
    validate_fields(p, w);
    require(std::isfinite(p.kp) && std::isfinite(p.ki) && std::isfinite(p.kd), w,
            "kp, ki and kd must be finite");
    require(std::isfinite(p.derivative_cutoff_hz), w, "derivative_cutoff_hz must be finite");
    require(p.max_correction > 0.0, w, "max_correction must be > 0 (got ", p.max_correction, ")");
    p.limits.validate(w);
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters are kept.
  void reset() noexcept {
    primed_ = false;
    integral_ = derivative_ = error_ = correction_ = cut_ = 0.0;
    shaper_.reset();
    held_ = fallback_ = limited_ = false;
  }

  /// @brief One cycle: the servo command for a feedforward target, from the encoder reading.
  /// @param target the feedforward's motor angle this cycle, rad; a non-finite one holds the last command
  /// @param encoder the motor encoder now, rad; a non-finite one (dropout) holds the correction
  /// @param dt the time since the previous cycle, s (not finite or <= 0: nothing is integrated)
  /// @return the servo command target + correction, within the limits
  double correct(double target, double encoder, double dt) noexcept {
    held_ = !std::isfinite(target);
    fallback_ = !std::isfinite(encoder);
    if (held_) return shaper_.apply(NAN, dt);
    const bool timed = dt > 0.0 && std::isfinite(dt);
    if (primed_ && !fallback_ && timed) update(last_target_ - encoder, dt);
    last_target_ = target;
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
  /// The last encoder error (previous target minus encoder), rad.
  double error() const noexcept { return error_; }

  /// The last cycle's status: held_nonfinite_input (the target was not finite), fallback (no
  /// encoder reading: the correction was held), saturated (the command was cut to its limits, or
  /// the correction to max_correction).
  Status status() const noexcept {
    Status s = shaper_.status();
    if (held_) s |= Status::held_nonfinite_input;
    if (fallback_) s |= Status::fallback;
    if (limited_) s |= Status::saturated;
    return s;
  }

 private:
  void update(double e, double dt) noexcept {
    const double tau = 1.0 / (2.0 * 3.14159265358979323846 * p_.derivative_cutoff_hz);
    const double rate = (e - error_) / dt;
    const double a = dt / (tau + dt);  // backward Euler of the first-order low-pass
    derivative_ = std::isfinite(rate) ? derivative_ + a * (rate - derivative_) : derivative_;
    error_ = e;
    // anti-windup: no integration in the direction the shaper is already cutting
    const bool blocked = (cut_ < 0.0 && e > 0.0) || (cut_ > 0.0 && e < 0.0);
    if (!blocked) integral_ = clamp(integral_ + p_.ki * e * dt);
    const double raw = p_.kp * e + integral_ + p_.kd * derivative_;
    correction_ = clamp(raw);
    limited_ = correction_ != raw;
    if (!std::isfinite(correction_)) correction_ = integral_ = derivative_ = 0.0;
  }
  double clamp(double c) const noexcept {
    const double m = p_.max_correction;
    return c > m ? m : (c < -m ? -m : c);
  }

  Params p_;
  CommandShaper shaper_{};
  double last_target_ = 0.0, integral_ = 0.0, derivative_ = 0.0, error_ = 0.0;
  double correction_ = 0.0, cut_ = 0.0;
  bool primed_ = false, held_ = false, fallback_ = false, limited_ = false;
};

namespace detail {
template <class T, class = void>
struct FollowsShape : std::false_type {};
template <class T>
struct FollowsShape<T, std::void_t<decltype(std::declval<T&>().set_shape(ShapeIntegrals{}))>>
    : std::true_type {};
}  // namespace detail

/// @brief Any feedforward (step(y_d, dt)) with an EncoderLoop around it: step(y_d, q, dt).
/// @tparam Feedforward BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
/// CurveAngleFeedforward, ContinuumFeedforward, or any class with step(y_d, dt), reset() and status()
template <class Feedforward>
class EncoderLooped {
 public:
  /// @param ff the feedforward (its command is the encoder's target)
  /// @param loop the encoder loop around the servo
  EncoderLooped(Feedforward ff, EncoderLoop loop) : ff_(std::move(ff)), loop_(std::move(loop)) {}

  /// Start afresh: both the feedforward and the loop.
  void reset() noexcept {
    ff_.reset();
    loop_.reset();
  }
  /// @param y_d the desired output
  /// @param q the motor encoder, rad (NaN: no reading this cycle)
  /// @param dt the time since the previous cycle, s
  /// @return the servo command
  double step(double y_d, double q, double dt) noexcept {
    return loop_.correct(ff_.step(y_d, dt), q, dt);
  }
  /// Passes a route shape to a feedforward that follows the route (ignored otherwise).
  void set_shape(const ShapeIntegrals& s) noexcept {
    if constexpr (detail::FollowsShape<Feedforward>::value) ff_.set_shape(s);
  }
  /// The feedforward's and the loop's flags of the last step.
  Status status() const noexcept { return ff_.status() | loop_.status(); }
  /// The feedforward inside.
  Feedforward& feedforward() noexcept { return ff_; }
  /// The encoder loop.
  const EncoderLoop& loop() const noexcept { return loop_; }

 private:
  Feedforward ff_;
  EncoderLoop loop_;
};

}  // namespace tendonsheath
