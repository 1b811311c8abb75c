// Feedforward of Lau et al. 2015 (spec C) for a tendon-sheath-driven
// continuum segment: bending angle in, motor angle out.
//
// mode Published, the paper's equations as printed (eqs. 11-38):
//   X_d = r_t theta_d,  F = (theta_d / l) EI / r_t
//   [A1, -A2; e^{-xi Theta}, -e^{xi Theta}] [T1; T3] = [2 T0 L; F]
//   delta_pull = (T1 A1 - T0 L)/EA,  delta_0 = 2 T0 L (1 - e^{-xi Theta})/EA
//   X_in = X_d + S (delta_pull + delta_0) + F L / EA,  S = tanh(theta_d' / v_eps)
// mode Exact, capstan-consistent and without double counting (spec A.4, C.6):
//   X_in = X_d + phi Delta_fwd(F) + (1 - phi) Delta_bwd(F),  phi = (1 + S)/2
// and q_motor = X_in / r_p in both, plus S r_p p / 2 for a motor-side play p (the gearhead's
// backlash, crossed at each reversal).
#pragma once

#include <cmath>

#include "../physics/pull_pull_statics.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Which equations ContinuumFeedforward runs: Exact, capstan-consistent without double counting
/// (spec A.4, C.6), or Published, the paper's equations as printed (eqs. 11-38).
enum class ContinuumMode { Exact = 0, Published = 1 };

/// Parameters of ContinuumFeedforward (validated by its constructor).
struct ContinuumFeedforwardParams {
  double friction = 0.1;            ///< mu (xi = gap_factor * mu)
  double gap_factor = 1.0;          ///< gamma * delta_r of Kesner & Howe; 1 = plain capstan
  double length = 1.0;              ///< L, the sheath's length, m
  double stiffness = 2.4e4;         ///< EA, N
  double pretension = 10.0;         ///< T0, N
  double curve_angle = 3.141592653589793;  ///< Theta of a constant-radius route, rad
  double bending_stiffness = 4e-4;  ///< EI of the backbone, N m^2
  double tendon_offset = 2e-3;      ///< r_t, m
  double backbone_length = 0.03;    ///< l, m
  double proximal_radius = 5e-3;    ///< r_p, m
  double smoothing = 0.1;           ///< v_eps, the smoothing speed of the direction switch, rad/s
  double play = 0.0;                ///< motor-side play (gearhead backlash), total width, rad at the motor
  ContinuumMode mode = ContinuumMode::Exact;  ///< which equations: the capstan-consistent ones or the paper's
  CommandLimits limits{};           ///< the motor command's limits, on the motor angle, rad
};

/// The parameter table of ContinuumFeedforwardParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<ContinuumFeedforwardParams> {
  static constexpr const char* owner = "ContinuumFeedforward";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("friction", &ContinuumFeedforwardParams::friction, "", non_negative(),
            "mu (xi = gap_factor * mu)"),
      param("gap_factor", &ContinuumFeedforwardParams::gap_factor, "", positive(),
            "gamma * delta_r of Kesner and Howe; 1 = plain capstan"),
      param("length", &ContinuumFeedforwardParams::length, "m", positive(),
            "L, the sheath's length"),
      param("stiffness", &ContinuumFeedforwardParams::stiffness, "N", positive(),
            "EA"),
      param("pretension", &ContinuumFeedforwardParams::pretension, "N", non_negative(),
            "T0"),
      param("curve_angle", &ContinuumFeedforwardParams::curve_angle, "rad", non_negative(),
            "Theta of a constant-radius route, <= the largest the friction allows"),
      param("bending_stiffness", &ContinuumFeedforwardParams::bending_stiffness, "N m^2", positive(),
            "EI of the backbone"),
      param("tendon_offset", &ContinuumFeedforwardParams::tendon_offset, "m", positive(),
            "r_t"),
      param("backbone_length", &ContinuumFeedforwardParams::backbone_length, "m", positive(),
            "l"),
      param("proximal_radius", &ContinuumFeedforwardParams::proximal_radius, "m", positive(),
            "r_p"),
      param("smoothing", &ContinuumFeedforwardParams::smoothing, "rad/s", positive(),
            "v_eps, the smoothing speed of the direction switch"),
      param("play", &ContinuumFeedforwardParams::play, "rad", non_negative(),
            "motor-side play (gearhead backlash), total width at the motor"),
      param("mode", &ContinuumFeedforwardParams::mode, "", any(),
            "ContinuumMode: the capstan-consistent equations (exact) or the paper's (published)"),
      param("limits", &ContinuumFeedforwardParams::limits, "", any(),
            "CommandLimits: the command's min, max and max_rate"));
};

/// @brief Feedforward of Lau et al.\ (spec C) for a tendon-sheath-driven continuum segment: desired
/// bending angle in, motor angle out.
///
/// Published: X_d = r_t theta_d, F = (theta_d / l) EI / r_t, the paper's tensions and
/// X_in = X_d + S (delta_pull + delta_0) + F L / EA with S = tanh(theta_d' / v_eps). Exact:
/// X_in = X_d + phi Delta_fwd(F) + (1 - phi) Delta_bwd(F), phi = (1 + S)/2. In both the command is
/// q_motor = X_in / r_p, shaped to the limits. The route is fixed at construction.
class ContinuumFeedforward {
 public:
  /// The parameter struct its constructor takes.
  using Params = ContinuumFeedforwardParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit ContinuumFeedforward(const Params& p) : p_(p), shaper_(p.limits) {
    const char* w = "ContinuumFeedforward";
    validate_fields(p, w, "friction", "curve_angle");  // from ParamTable<ContinuumFeedforwardParams>
    require(p.curve_angle <= max_curve_angle(p.gap_factor * p.friction), w,
            "curve_angle must be <= ", max_curve_angle(p.gap_factor * p.friction),
            " rad for gap_factor * friction = ", p.gap_factor * p.friction,
            " (xi * curve_angle <= 50; got ", p.curve_angle, ")");
    validate_fields(p, w, "bending_stiffness", "play");
    require(std::isfinite(p.play), w, "play must be finite");
    require(p.mode == ContinuumMode::Exact || p.mode == ContinuumMode::Published, w,
            "mode must be exact or published");
    require(p.mode == ContinuumMode::Exact || p.friction * p.curve_angle > 0.0, w,
            "published mode needs friction * curve_angle > 0 (its equations divide by xi)");
    p.limits.validate(w);
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    const double xi = p.gap_factor * p.friction;
    statics_ = {xi, p.length / p.stiffness, p.pretension};
    affine_ = statics_.affine(uniform_shape(xi, p.curve_angle));
    if (p.mode == ContinuumMode::Published) {  // the route is fixed: constants of eqs. 11-28
      const double L = p.length, Theta = p.curve_angle;
      const double R = L / Theta;
      em_ = std::exp(-xi * Theta);
      ep_ = 1.0 / em_;
      A1_ = (R / xi) * (1.0 - em_);
      A2_ = (R / xi) * (1.0 - ep_);
      det_ = -A1_ * ep_ + A2_ * em_;
    }
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    rate_.reset();
    shaper_.reset();
  }

  /// Desired bending angle (rad) -> motor angle (rad).
  /// @param theta_d the desired bending angle, rad; a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s (S uses theta_d's backward difference)
  /// @return the motor angle command, rad, within the limits
  double step(double theta_d, double dt) noexcept {
    if (!std::isfinite(theta_d)) return shaper_.apply(NAN, dt);
    const double rate = rate_.update(theta_d, dt);
    const double s = std::tanh(rate / p_.smoothing);
    return shaper_.apply(tendon_input(theta_d, s) / p_.proximal_radius + 0.5 * s * p_.play, dt);
  }

  /// The last step's status: held_nonfinite_input (y_d not finite) and the command shaper's
  /// (saturated: the command was cut to its limits).
  Status status() const noexcept { return shaper_.status(); }

  /// Pulling force of the bent segment (Li & Rahn): F = kappa EI / r_t.
  double bending_force(double theta_d) const noexcept {
    return theta_d / p_.backbone_length * p_.bending_stiffness / p_.tendon_offset;
  }

  /// X_in for the desired bending angle and a direction S in [-1, 1].
  double tendon_input(double theta_d, double s) const noexcept {
    const double x_d = p_.tendon_offset * theta_d;
    const double F = bending_force(theta_d);
    if (p_.mode == ContinuumMode::Exact) {
      const double phi = 0.5 * (1.0 + s);
      return x_d + phi * (affine_.forward_offset + affine_.forward_slope * F) +
             (1.0 - phi) * (affine_.backward_offset + affine_.backward_slope * F);
    }
    const double L = p_.length, EA = p_.stiffness, T0 = p_.pretension;
    // Cramer's rule on [A1, -A2; e^{-xi Theta}, -e^{xi Theta}] [T1; T3] = [2 T0 L; F]
    const double T1 = (-(2.0 * T0 * L) * ep_ + A2_ * F) / det_;
    const double delta_pull = (T1 * A1_ - T0 * L) / EA;
    const double delta_0 = 2.0 * T0 * L * (1.0 - em_) / EA;
    return x_d + s * (delta_pull + delta_0) + F * L / EA;
  }

 private:
  Params p_;
  PullPullStatics statics_{};
  PullPullStatics::Affine affine_{};
  double em_ = 1.0, ep_ = 1.0, A1_ = 0.0, A2_ = 0.0, det_ = 1.0;
  RateEstimator rate_{};
  CommandShaper shaper_{};
};

}  // namespace tendonsheath
