// Closed-form pull-pull tendon-sheath model with the curve angle as a second
// input (spec B, from the uniform-curvature closed form A.7 and the spring
// slope of A.4).
//
// Linear displacements (m) at the tendon level, a = mu * Theta:
//
//   e_b(Theta) = (T0 L / EA) tanh(a/2)                 backlash half-width
//   e_L(Theta) = (F_L L / EA) tanh(a/2) / a            load offset
//   c(Theta)   = 1 / (1 + k_e (L / EA) tanh(a/2) / a)  branch slope (spring environment)
//
//   forward branch   x_out = c (x_in - e_b - e_L)
//   backward branch  x_out = c (x_in + e_b - e_L)
//   in between        x_out holds (dead zone of input width 2 e_b)
//
// The rule x_out <- clamp(x_out, forward, backward) covers both a moving input
// and a changing curve angle at rest (spec B memory effect): raising Theta
// widens the band and the output stays; lowering it narrows the band and the
// held output creeps onto the new branch. Rotary form: x_in = r_p q_in and
// q_out = x_out / r_d, so the input and the output are angles in rad. The
// model starts in the middle of the band, x_out = c (x_in - e_L).
//
// A non-uniform route (set_shape: the shape integrals g, G of spec A.2 at the
// model's friction) takes the general full-slip elongations (A5)/(A6): with
// u = g e^{a} and v = G e^{-a}, e_b = (T0 L/EA)(u - v)/(u + v) and
// e_L = (F_L L/EA) g G/(u + v) (tanh(a/2) and tanh(a/2)/a for uniform curvature).
//
// Only the products T0 L / EA, F_L L / EA and k_e L / EA enter the output, so
// an identification holds T0 and L known and identifies EA, F_L and k_e.
#pragma once

#include <cmath>
#include <cstddef>

#include "../physics/pull_pull_statics.hpp"
#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of CurveAngleModel (validated by its constructor); SI units, tendon level.
struct CurveAngleParams {
  double friction = 0.1;          ///< mu, Coulomb friction coefficient
  double stiffness = 2.4e4;       ///< EA, tendon axial stiffness, N
  double pretension = 10.0;       ///< T0, N
  double length = 1.2;            ///< L, sheath length, m
  double load_force = 0.0;        ///< F_L, constant distal load at tendon level, N (resists forward)
  double load_stiffness = 0.0;    ///< k_e, environment spring at tendon level, N/m
  double proximal_radius = 5e-3;  ///< r_p, m
  double distal_radius = 5e-3;    ///< r_d, m
  double play = 0.0;              ///< motor-side play (the gearhead's backlash), total width, rad at the motor

  /// How many identifiable parameters assign() reads: the table's Role::parameter rows
  /// (checked against it below the table).
  static constexpr std::size_t vector_size = 9;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the order of the table's
  /// parameter rows (the Python param_names); the options are kept.
  void assign(const double* v) noexcept;
};

/// The parameter table of CurveAngleParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<CurveAngleParams> {
  static constexpr const char* owner = "CurveAngleModel";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &CurveAngleParams::friction, "", non_negative(),
            "mu, Coulomb friction coefficient"),
      param("stiffness", &CurveAngleParams::stiffness, "N", positive(),
            "EA, tendon axial stiffness"),
      param("pretension", &CurveAngleParams::pretension, "N", non_negative(),
            "T0, the tendon's pretension"),
      param("length", &CurveAngleParams::length, "m", positive(),
            "L, sheath length"),
      param("load_force", &CurveAngleParams::load_force, "N", finite(),
            "F_L, constant distal load at tendon level (resists forward)"),
      param("load_stiffness", &CurveAngleParams::load_stiffness, "N/m", non_negative(),
            "k_e, environment spring at tendon level"),
      param("proximal_radius", &CurveAngleParams::proximal_radius, "m", positive(),
            "r_p, the proximal pulley's radius"),
      param("distal_radius", &CurveAngleParams::distal_radius, "m", positive(),
            "r_d, the distal pulley's radius"),
      param("play", &CurveAngleParams::play, "rad", non_negative(),
            "motor-side play (the gearhead's backlash), total width at the motor"));
};

static_assert(CurveAngleParams::vector_size == parameter_count<CurveAngleParams>(),
              "vector_size is the number of the table's parameter rows");
inline void CurveAngleParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

/// @brief Closed-form pull-pull tendon-sheath model with the curve angle as a second input (spec B,
/// from the uniform-curvature closed form A.7 and the spring slope of A.4).
///
/// With a = mu Theta: backlash half-width e_b = (T0 L / EA) tanh(a/2), load offset
/// e_L = (F_L L / EA) tanh(a/2) / a and branch slope c = 1 / (1 + k_e (L / EA) tanh(a/2) / a);
/// x_out <- clamp(x_out, c (x_in - e_b - e_L), c (x_in + e_b - e_L)). The clamp covers a moving
/// input and a changing curve angle at rest (raising Theta widens the band, lowering it lets the
/// held output creep onto the new branch). Input and output are angles (rad): x_in = r_p q_in,
/// q_out = x_out / r_d. It starts in the middle of the band, x_out = c (x_in - e_L). A motor-side
/// play of total width p (a gearhead's backlash between the motor and the pulley) is a dead zone in
/// series with the tendons': it widens the band by r_p p / 2 on each side, at any curve angle.
///
/// A route of any shape (set_shape(): the shape integrals g, G computed with this model's
/// friction) replaces tanh(a/2) by the pull-pull dead-zone factor of spec A5/A6,
/// (u - v)/(u + v) with u = g e^{a}, v = G e^{-a}, and tanh(a/2)/a by g G/(u + v); the terms are
/// computed when the curve angle or the shape changes, not at every step.
class CurveAngleModel {
 public:
  /// The parameter struct its constructor takes.
  using Params = CurveAngleParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit CurveAngleModel(const Params& p) : p_(p) {
    const char* w = "CurveAngleModel";
    validate_fields(p, w);  // every field's bound, from ParamTable<CurveAngleParams>
    require(std::isfinite(p.play), w, "play must be finite");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    half_play_ = 0.5 * p.proximal_radius * p.play;
    set_curve_angle(0.0);
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    initialised_ = false;
    slack_ = step_slack_ = false;
  }

  /// Closed-form terms at a curve angle (linear units, m; physics/pull_pull_statics.hpp): the
  /// backlash half-width e_b at curve angle theta (rad).
  double backlash_half_width(double theta) const noexcept {
    return uniform::backlash_half_width(p_.length, p_.stiffness, p_.pretension,
                                        p_.friction * std::fabs(theta));
  }
  /// The load offset e_L at curve angle theta (rad), m.
  double load_offset(double theta) const noexcept {
    return uniform::load_offset(p_.length, p_.stiffness, p_.load_force, p_.friction * std::fabs(theta));
  }
  /// The branch slope c at curve angle theta (rad), in (0, 1].
  double slope(double theta) const noexcept {
    return uniform::spring_slope(p_.length, p_.stiffness, p_.load_stiffness,
                                 p_.friction * std::fabs(theta));
  }

  /// Streaming: proximal angle q_in (rad), curve angle theta (rad) -> distal angle (rad).
  /// @param q_in the proximal angle, rad; a non-finite q_in holds the last output
  /// @param theta the curve angle, rad (its magnitude is used, a uniform route of that angle);
  /// a non-finite theta keeps the last curve angle or shape
  /// @return the distal angle, rad
  double step(double q_in, double /*dt*/, double theta) noexcept {
    set_curve_angle(theta);
    return step(q_in);
  }
  /// Keeps the last curve angle or shape (0, a straight sheath, before any was given).
  /// @param q_in the proximal angle, rad; a non-finite q_in holds the last output
  /// @return the distal angle, rad
  double step(double q_in, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(q_in);
    if (held_) {
      step_slack_ = false;
      return initialised_ ? y_ : 0.0;
    }
    const double x_in = p_.proximal_radius * q_in;
    const double fwd = c_ * (x_in - eb_ - half_play_ - eL_);
    const double bwd = c_ * (x_in + eb_ + half_play_ - eL_);
    if (!initialised_) {
      x_out_ = c_ * (x_in - eL_);
      initialised_ = true;
    } else {
      x_out_ = x_out_ < fwd ? fwd : (x_out_ > bwd ? bwd : x_out_);
    }
    // No-slack condition of spec A.4 on the total distal load.
    const double force = p_.load_force + p_.load_stiffness * x_out_;
    step_slack_ = std::fabs(force) >= slack_limit_;
    if (step_slack_) slack_ = true;
    y_ = x_out_ / p_.distal_radius;
    return y_;
  }

  /// The distal angle of the last step(), rad.
  double output() const noexcept { return y_; }
  /// The curve angle in use, rad (>= 0): the last set_curve_angle() or the shape's total angle.
  double curve_angle() const noexcept { return shape_.curve_angle; }
  /// The route shape in use (g, G with this model's friction, and the total angle); a curve
  /// angle alone is the uniform route's shape.
  const ShapeIntegrals& shape() const noexcept { return shape_; }
  /// True while the terms come from a curve angle (uniform curvature), false after set_shape().
  bool uniform() const noexcept { return uniform_; }
  /// Set the curve angle |theta| (rad) for the next steps: a uniform route of that angle,
  /// the closed forms of spec A.7 (bit for bit those of backlash_half_width(), load_offset()
  /// and slope()); a non-finite theta is ignored.
  void set_curve_angle(double theta) noexcept {
    if (!std::isfinite(theta)) return;
    theta = std::fabs(theta);
    if (uniform_ && theta == shape_.curve_angle) return;
    uniform_ = true;
    shape_ = uniform_shape(p_.friction, theta);
    eb_ = backlash_half_width(theta);
    eL_ = load_offset(theta);
    c_ = slope(theta);
    slack_limit_ = uniform::no_slack_limit(p_.pretension, p_.friction * theta);
  }
  /// Set the route's shape for the next steps: its integrals g, G computed with this model's
  /// friction (shape_integrals()) and its total angle. The branches are spec A5/A6 with the
  /// loads (PullPullStatics::affine(shape), written so that nothing overflows): with
  /// u = g e^{a}, v = G e^{-a} and a = mu Theta, e_b = (T0 L/EA) (u - v)/(u + v),
  /// C_L = (L/EA) u v/(u + v) and e_L = F_L C_L, and the no-slack limit 2 T0 e^{-a}/g (the
  /// uniform shape gives tanh(a/2), tanh(a/2)/a and T0 (a/sinh a)(1 + e^{-a}) of spec A.7).
  /// A shape with g or G not finite and > 0, or a total angle not finite and >= 0, is ignored;
  /// a is capped at kMaxFrictionAngle and g, G are held within what a route of that angle can
  /// have (e^{-a} <= g <= 1 <= G <= e^{a}), so the terms stay finite for any input.
  /// @param shape the route's shape integrals
  void set_shape(const ShapeIntegrals& shape) noexcept {
    if (!(std::isfinite(shape.g) && std::isfinite(shape.G) && shape.g > 0.0 && shape.G > 0.0 &&
          std::isfinite(shape.curve_angle) && shape.curve_angle >= 0.0))
      return;
    uniform_ = false;
    shape_ = shape;
    const double a = std::fmin(p_.friction * shape.curve_angle, kMaxFrictionAngle);
    const double ea = std::exp(a), ema = std::exp(-a);
    const double u = std::fmin(std::fmax(shape.g, ema), 1.0) * ea;   // in [1, e^a]
    const double v = std::fmin(std::fmax(shape.G, 1.0), ea) * ema;   // in [e^-a, 1]
    const double compliance = p_.length / p_.stiffness;
    const double load_compliance = compliance * u * v / (u + v);
    eb_ = compliance * p_.pretension * (u - v) / (u + v);
    eL_ = p_.load_force * load_compliance;
    c_ = 1.0 / (1.0 + p_.load_stiffness * load_compliance);
    slack_limit_ = 2.0 * p_.pretension / u;
  }
  /// True once the distal load exceeded the no-slack limit since reset().
  bool slack() const noexcept { return slack_; }
  /// The last step's status: held_nonfinite_input (input not finite), slack (this step's
  /// distal load broke the no-slack condition; slack() keeps it since reset()).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return step_slack_ ? s | Status::slack : s;
  }

 private:
  Params p_;
  ShapeIntegrals shape_{};  // the route's shape in use (uniform: of the curve angle)
  double eb_ = 0.0, eL_ = 0.0, c_ = 1.0, slack_limit_ = 0.0;  // the terms of that shape
  double half_play_ = 0.0;  // r_p play / 2, m at the tendon
  double x_out_ = 0.0, y_ = 0.0;
  bool uniform_ = false, initialised_ = false, slack_ = false, held_ = false, step_slack_ = false;
};

/// Batch simulation with a per-sample curve angle (theta may be nullptr: keep the last);
/// status, when given, receives each sample's Status flags. Not real-time: it validates the
/// series and throws std::invalid_argument (message starting with `where`) on a bad sample.
/// @param model reset, then stepped once per sample
/// @param t the n sample times, s, finite and increasing, or nullptr (the model ignores dt)
/// @param x the n proximal angles, rad, finite
/// @param theta the n curve angles, rad, finite, or nullptr (keep the model's)
/// @param y receives the n distal angles, rad
/// @param n the number of samples, >= 1
/// @param where the name that starts an error message
/// @param status receives the n samples' Status flags, or nullptr
inline void simulate(CurveAngleModel& model, const double* t, const double* x,
                     const double* theta, double* y, std::size_t n, const char* where,
                     unsigned char* status = nullptr) {
  check_series(t, x, n, where);
  if (theta != nullptr) {
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite(theta[k]))
        detail::fail(where, "curve angle sample [", k, "] is not finite (", theta[k], ")");
  }
  model.reset();
  for (std::size_t k = 0; k < n; ++k) {
    y[k] = theta ? model.step(x[k], 0.0, theta[k]) : model.step(x[k], 0.0);
    if (status != nullptr) status[k] = static_cast<unsigned char>(model.status());
  }
}

}  // namespace tendonsheath
