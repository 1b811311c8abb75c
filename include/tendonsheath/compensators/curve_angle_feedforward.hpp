// Curve-angle feedforward of Sun, Wang & Phee (spec B2): modify the motor
// input by the pull-pull elongation predicted for the route's current shape,
// with no distal sensor.
//
//   x_in = r_d y_d + phi Delta_fwd(shape, F_L) + (1 - phi) Delta_bwd(shape, F_L)
//          + (2 phi - 1) r_p p / 2
//   q_in = x_in / r_p,   phi = (1 + tanh(y_d' / v_eps)) / 2,   F_L = F_0 + k_e r_d y_d
// (p: a motor-side play, e.g. the gearhead's backlash, crossed on each reversal)
//
// Delta_fwd/bwd are the full-slip elongations (A5)/(A6) with the g/G shape
// integrals, so non-uniform routes are handled; the shape (or the curve angle,
// for uniform curvature) is updated every control cycle. The correction's rate
// of change is limited (spec B: limit how fast a change of Theta is followed).
#pragma once

#include <cmath>
#include <limits>

#include "../physics/pull_pull_statics.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of CurveAngleFeedforward (validated by its constructor).
struct CurveAngleFeedforwardParams {
  double friction = 0.1;           ///< mu
  double stiffness = 2e4;          ///< EA of the tendon, N
  double length = 1.0;             ///< L, the sheath's length, m (L / EA enters the statics)
  double pretension = 10.0;        ///< T0, N
  double load_force = 0.0;         ///< F_0 at the distal tendon level, N
  double load_stiffness = 0.0;     ///< k_e of a spring environment at the tendon level, N/m
  double proximal_radius = 5e-3;   ///< r_p, m
  double distal_radius = 5e-3;     ///< r_d, m
  double curve_angle = 3.141592653589793;  ///< initial Theta (uniform curvature), rad
  double play = 0.0;               ///< motor-side play (gearhead backlash), total width, rad at the motor
  double smoothing = 0.05;         ///< v_eps, the smoothing speed of the direction switch, rad/s of output
  double max_correction_rate = std::numeric_limits<double>::infinity();  ///< the correction's largest rate of change, m/s at the tendon
  CommandLimits limits{};          ///< the motor command's limits, on the motor angle, rad
};

/// The parameter table of CurveAngleFeedforwardParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<CurveAngleFeedforwardParams> {
  static constexpr const char* owner = "CurveAngleFeedforward";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &CurveAngleFeedforwardParams::friction, "", non_negative(),
            "mu, the sheath's Coulomb friction coefficient"),
      param("stiffness", &CurveAngleFeedforwardParams::stiffness, "N", positive(),
            "EA of the tendon"),
      param("length", &CurveAngleFeedforwardParams::length, "m", positive(),
            "L, the sheath's length (L / EA enters the statics)"),
      param("pretension", &CurveAngleFeedforwardParams::pretension, "N", non_negative(),
            "T0"),
      param("load_force", &CurveAngleFeedforwardParams::load_force, "N", finite(),
            "F_0 at the distal tendon level"),
      param("load_stiffness", &CurveAngleFeedforwardParams::load_stiffness, "N/m", non_negative(),
            "k_e of a spring environment at the tendon level"),
      param("proximal_radius", &CurveAngleFeedforwardParams::proximal_radius, "m", positive(),
            "r_p"),
      param("distal_radius", &CurveAngleFeedforwardParams::distal_radius, "m", positive(),
            "r_d"),
      param("curve_angle", &CurveAngleFeedforwardParams::curve_angle, "rad", non_negative(),
            "initial Theta (uniform curvature), <= the largest the friction allows"),
      param("play", &CurveAngleFeedforwardParams::play, "rad", non_negative(),
            "motor-side play (gearhead backlash), total width at the motor"),
      param("smoothing", &CurveAngleFeedforwardParams::smoothing, "rad/s", positive(),
            "v_eps, the smoothing speed of the direction switch"),
      param("max_correction_rate", &CurveAngleFeedforwardParams::max_correction_rate, "m/s", documented(0.0, false, kInf, true),
            "the correction's largest rate of change, at the tendon"),
      param("limits", &CurveAngleFeedforwardParams::limits, "", any(),
            "CommandLimits: the command's min, max and max_rate"));
};

/// @brief Curve-angle feedforward of Sun, Wang & Phee (spec B2): the motor input modified by the
/// pull-pull elongation predicted for the route's current shape, with no distal sensor.
///
/// x_in = r_d y_d + phi Delta_fwd(shape, F_L) + (1 - phi) Delta_bwd(shape, F_L), q_in = x_in / r_p,
/// phi = (1 + tanh(y_d' / v_eps)) / 2, F_L = F_0 + k_e r_d y_d. Delta_fwd/bwd are the full-slip
/// elongations (A5)/(A6) with the shape integrals g, G, so non-uniform routes are handled; the
/// shape (set_shape) or curve angle (set_curve_angle) may change every cycle, and the correction's
/// rate of change is limited by max_correction_rate.
class CurveAngleFeedforward {
 public:
  /// The parameter struct its constructor takes.
  using Params = CurveAngleFeedforwardParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range
  /// (friction * curve_angle must be <= 50).
  explicit CurveAngleFeedforward(const Params& p) : p_(p), shaper_(p.limits) {
    const char* w = "CurveAngleFeedforward";
    validate_fields(p, w);  // each field's own bound, from ParamTable<CurveAngleFeedforwardParams>
    // the rules between fields, and the bounds the table cannot hold
    require_positive(p.length / p.stiffness, w, "length / stiffness");
    require(p.curve_angle <= max_curve_angle(p.friction), w, "curve_angle must be <= ",
            max_curve_angle(p.friction), " rad for friction ", p.friction,
            " (friction * curve_angle <= 50; got ", p.curve_angle, ")");
    require(p.max_correction_rate > 0.0, w, "max_correction_rate must be > 0");
    p.limits.validate(w);
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    statics_ = {p.friction, p.length / p.stiffness, p.pretension};
    update_shape(uniform_shape(p.friction, p.curve_angle));
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The route shape in use.
  const ShapeIntegrals& shape() const noexcept { return shape_; }
  /// True when the last set_curve_angle() was beyond max_curve_angle(friction) and clamped.
  bool angle_clamped() const noexcept { return angle_clamped_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    rate_.reset();
    shaper_.reset();
    correction_primed_ = false;
  }

  /// Uniform curvature with total angle theta (rad); an angle beyond max_curve_angle(friction) is
  /// clamped to it (angle_clamped() tells). A non-finite or negative one changes nothing and is
  /// rejected: status() reports input_clamped until an angle or shape is taken (angle_rejected()).
  /// @return whether the angle was taken
  bool set_curve_angle(double theta) noexcept {
    angle_rejected_ = !(std::isfinite(theta) && theta >= 0.0);
    if (angle_rejected_) return false;
    angle_clamped_ = theta > max_curve_angle(p_.friction);
    if (angle_clamped_) theta = max_curve_angle(p_.friction);
    if (!(uniform_ && theta == shape_.curve_angle)) {
      update_shape(uniform_shape(p_.friction, theta));
      uniform_ = true;
    }
    return true;
  }
  /// Any route: its shape integrals g, G (see shape_integrals) and total angle. A shape with a
  /// non-finite or non-positive integral or a negative angle changes nothing and is rejected as
  /// set_curve_angle() rejects an angle.
  /// @return whether the shape was taken
  bool set_shape(const ShapeIntegrals& shape) noexcept {
    angle_rejected_ = !(std::isfinite(shape.g) && std::isfinite(shape.G) && shape.g > 0.0 &&
                        shape.G > 0.0 && std::isfinite(shape.curve_angle) &&
                        shape.curve_angle >= 0.0);
    if (angle_rejected_) return false;
    update_shape(shape);
    uniform_ = false;
    return true;
  }
  /// True when the last set_curve_angle() or set_shape() was rejected (non-finite or negative).
  bool angle_rejected() const noexcept { return angle_rejected_; }

  /// @param y_d the desired distal angle, rad; a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s (the desired rate is y_d's backward difference)
  /// @return the motor angle command, rad, within the limits
  double step(double y_d, double dt) noexcept {
    held_ = !std::isfinite(y_d);
    if (held_) return shaper_.apply(NAN, dt);
    return step_with_rate(y_d, rate_.update(y_d, dt), dt);
  }

  /// The last step's status: held (non-finite y_d), input_clamped (the curve angle in force
  /// was clamped to max_curve_angle, or the last one given was rejected), saturated (the command was cut to its limits).
  Status status() const noexcept {
    Status s = shaper_.status();
    if (held_) s |= Status::held_nonfinite_input;
    if (angle_clamped_ || angle_rejected_) s |= Status::input_clamped;
    return s;
  }

  /// @brief As step(), with the desired output rate given (e.g.\ from a trajectory generator).
  /// @param y_d the desired distal angle, rad
  /// @param y_d_rate its rate, rad/s (a non-finite rate counts as 0)
  /// @param dt the time since the previous cycle, s
  /// @return the motor angle command, rad, within the limits
  double step_with_rate(double y_d, double y_d_rate, double dt) noexcept {
    if (!std::isfinite(y_d_rate)) y_d_rate = 0.0;
    const double x_d = p_.distal_radius * y_d;
    double c = correction(x_d, smooth_direction(y_d_rate, p_.smoothing));
    if (correction_primed_ && std::isfinite(p_.max_correction_rate) && dt > 0.0) {
      const double step = p_.max_correction_rate * dt;
      if (c > correction_ + step) c = correction_ + step;
      if (c < correction_ - step) c = correction_ - step;
    }
    correction_ = c;
    correction_primed_ = true;
    return shaper_.apply((x_d + c) / p_.proximal_radius, dt);
  }

  /// Tendon-level correction for a desired distal displacement x_d and direction blend phi.
  double correction(double x_d, double phi) const noexcept {
    const double load = p_.load_force + p_.load_stiffness * x_d;
    return phi * (affine_.forward_offset + affine_.forward_slope * load) +
           (1.0 - phi) * (affine_.backward_offset + affine_.backward_slope * load) +
           (2.0 * phi - 1.0) * 0.5 * p_.proximal_radius * p_.play;
  }

  /// The tendon-level correction of the last step, m (after its rate limit).
  double last_correction() const noexcept { return correction_; }

 private:
  void update_shape(const ShapeIntegrals& shape) noexcept {
    shape_ = shape;
    affine_ = statics_.affine(shape);
  }

  Params p_;
  PullPullStatics statics_{};
  ShapeIntegrals shape_{};
  PullPullStatics::Affine affine_{};
  bool angle_clamped_ = false;
  bool angle_rejected_ = false;
  bool held_ = false;
  bool uniform_ = true;
  RateEstimator rate_{};
  CommandShaper shaper_{};
  double correction_ = 0.0;
  bool correction_primed_ = false;
};

}  // namespace tendonsheath
