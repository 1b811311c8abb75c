// Adaptive output-feedback controller of Do et al. 2015 (spec D.3): the
// tendon-sheath output y = c x + d(t) seen through a torque-driven motor
// J x'' + b x' + tau_d = u is treated as y'' = -a y' + beta u + delta(t), and
// the unknown (J/c, -b/c) and the bound of delta are estimated online:
//
//   e = y - y_d,  s = e' + lambda e,  nu_r = lambda e' - y_d''
//   u = -k_s s - psi y' - phi nu_r - D tanh(s / eps)
//   psi' = g_psi (y' s - s_psi psi)
//   phi' = Proj_[phi_min, phi_max] g_phi (nu_r s - s_phi (phi - phi_0))
//   D'   = Proj_[0, D_max]       g_D (s tanh(s/eps) - s_D D)
//
// y' is a second-order filtered derivative of the measured output. A non-
// finite measurement (sensor dropout) freezes the estimates and hands the
// motor to a fallback: a PD loop on the motor position toward the direct
// inverse feedforward of the backlash model (spec D.2), when one is given.
#pragma once

#include <cmath>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "inverse_feedforward.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of AdaptiveController (validated by its constructor).
struct AdaptiveControllerParams {
  double lambda = 20.0;   ///< 1/s
  double k_s = 1.0;       ///< feedback gain on s, torque per (rad/s)
  double epsilon = 0.05;  ///< boundary layer of the robust term, rad/s
  /// @{
  /// adaptation gains g_psi, g_phi, g_D
  double gamma_psi = 0.5, gamma_phi = 1e-3, gamma_D = 5.0;
  /// @}
  /// @{
  /// leakage s_psi, s_phi, s_D of the adaptation laws, >= 0
  double sigma_psi = 0.0, sigma_phi = 0.0, sigma_D = 0.0;
  /// @}
  /// @{
  /// initial estimates psi_0, phi_0, D_0 (phi_0 is also the prior that the phi leakage pulls toward)
  double psi_0 = 0.0, phi_0 = 0.005, D_0 = 0.0;
  /// @}
  double phi_min = 1e-5;  ///< lower projection bound of phi, > 0
  /// @{
  /// Projection bounds psi in [-psi_max, psi_max], phi in [phi_min, phi_max], D in [0, D_max]. D_max matters most: D/epsilon is a feedback gain on s, and s
  /// contains the filtered derivative, so D_max/(epsilon phi) must stay well below the
  /// derivative filter's bandwidth or the loop goes unstable.
  double psi_max = 10.0, phi_max = 1.0, D_max = 0.2;
  /// @}
  double adaptation_deadzone = 0.0;  ///< no adaptation while |s| is below this (noise floor)
  double derivative_cutoff_hz = 40.0;  ///< natural frequency of the second-order derivative filter of y, Hz
  double derivative_damping = 0.7071067811865476;  ///< damping ratio of that filter
  double max_torque = std::numeric_limits<double>::infinity();  ///< torque limit, |u| <= max_torque
  /// Fallback on sensor dropout: true when `feedforward` holds a backlash model, whose direct
  /// inverse is the fallback's motor target (else the target is y_d itself).
  bool has_feedforward = false;
  BacklashInverseParams feedforward{};  ///< the backlash model of the fallback's feedforward (used when has_feedforward)
  double fallback_kp = 1.0;   ///< torque per rad of motor position error
  double fallback_kd = 0.05;  ///< torque per rad/s of motor velocity error
  /// With a feedforward model: take the acceleration the model asks of the output,
  /// c * x_ff'' (which includes the quick crossing of the dead band at a reversal), in
  /// place of y_d'' in nu_r, so the inertial term pushes the motor across the band
  /// before the output error shows it. The difference is part of the bounded delta.
  bool model_acceleration = false;
};

/// The parameter table of AdaptiveControllerParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<AdaptiveControllerParams> {
  static constexpr const char* owner = "AdaptiveController";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("lambda_", &AdaptiveControllerParams::lambda, "1/s", positive(),
            "lambda, the sliding surface's pole (C++ member lambda)"),
      param("k_s", &AdaptiveControllerParams::k_s, "N m s/rad", non_negative(),
            "feedback gain on s"),
      param("epsilon", &AdaptiveControllerParams::epsilon, "rad/s", positive(),
            "boundary layer of the robust term"),
      param("gamma_psi", &AdaptiveControllerParams::gamma_psi, "", non_negative(),
            "adaptation gain of psi"),
      param("gamma_phi", &AdaptiveControllerParams::gamma_phi, "", non_negative(),
            "adaptation gain of phi"),
      param("gamma_D", &AdaptiveControllerParams::gamma_D, "", non_negative(),
            "adaptation gain of D"),
      param("sigma_psi", &AdaptiveControllerParams::sigma_psi, "", non_negative(),
            "sigma-modification (leakage) of psi"),
      param("sigma_phi", &AdaptiveControllerParams::sigma_phi, "", non_negative(),
            "sigma-modification (leakage) of phi"),
      param("sigma_D", &AdaptiveControllerParams::sigma_D, "", non_negative(),
            "sigma-modification (leakage) of D"),
      param("psi_0", &AdaptiveControllerParams::psi_0, "", documented(-kInf, true, kInf, true),
            "initial psi, in [-psi_max, psi_max]"),
      param("phi_0", &AdaptiveControllerParams::phi_0, "", documented(0.0, false, kInf, true),
            "initial phi, in [phi_min, phi_max]"),
      param("D_0", &AdaptiveControllerParams::D_0, "", documented(0.0, true, kInf, true),
            "initial D, in [0, D_max]"),
      param("phi_min", &AdaptiveControllerParams::phi_min, "", positive(),
            "lower projection bound of phi"),
      param("psi_max", &AdaptiveControllerParams::psi_max, "", positive(),
            "projection bound of |psi|"),
      param("phi_max", &AdaptiveControllerParams::phi_max, "", documented(0.0, false, kInf, false),
            "upper projection bound of phi, > phi_min"),
      param("D_max", &AdaptiveControllerParams::D_max, "", positive(),
            "projection bound of D"),
      param("adaptation_deadzone", &AdaptiveControllerParams::adaptation_deadzone, "rad/s", non_negative(),
            "no adaptation while |s| is below this (noise floor)"),
      param("derivative_cutoff_hz", &AdaptiveControllerParams::derivative_cutoff_hz, "Hz", positive(),
            "natural frequency of the second-order derivative filter of y"),
      param("derivative_damping", &AdaptiveControllerParams::derivative_damping, "", positive(),
            "damping ratio of that filter"),
      param("max_torque", &AdaptiveControllerParams::max_torque, "N m", documented(0.0, false, kInf, true),
            "torque limit, |u| <= max_torque"),
      param("has_feedforward", &AdaptiveControllerParams::has_feedforward, "", any(),
            "the fallback has a backlash feedforward"),
      param("feedforward", &AdaptiveControllerParams::feedforward, "", any(),
            "BacklashInverseParams of the fallback's feedforward (used when has_feedforward)"),
      param("fallback_kp", &AdaptiveControllerParams::fallback_kp, "N m/rad", non_negative(),
            "torque per rad of motor position error"),
      param("fallback_kd", &AdaptiveControllerParams::fallback_kd, "N m s/rad", non_negative(),
            "torque per rad/s of motor velocity error"),
      param("model_acceleration", &AdaptiveControllerParams::model_acceleration, "", any(),
            "include the model's acceleration term"));
};

/// The adaptive controller's online estimates.
struct AdaptiveEstimates {
  /// @{
  /// the estimates psi (of -b/c), phi (of J/c) and D (of the bound of the disturbance delta)
  double psi = 0.0, phi = 0.0, D = 0.0;
  /// @}
};

/// @brief Adaptive output-feedback controller of Do et al.\ (spec D.3) for a torque-driven motor
/// behind a tendon-sheath drive; returns the motor torque.
///
/// The output y = c x + d(t) seen through J x'' + b x' + tau_d = u is treated as
/// y'' = -a y' + beta u + delta(t). With e = y - y_d, s = e' + lambda e, nu_r = lambda e' - y_d'':
/// u = -k_s s - psi y' - phi nu_r - D tanh(s / eps); psi, phi and D adapt online (leakage,
/// projection onto their bounds). y' is a second-order filtered derivative of the measured output.
/// A non-finite measurement (sensor dropout) freezes the estimates and runs the fallback: a PD loop
/// on the motor position toward the direct inverse feedforward of the backlash model.
class AdaptiveController {
 public:
  /// The parameter struct its constructor takes.
  using Params = AdaptiveControllerParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit AdaptiveController(const Params& p)
      : p_(p), ff_(checked_feedforward(p)), slope_(0.5 * (p.feedforward.c_r + p.feedforward.c_l)) {
    const char* w = "AdaptiveController";
    validate_fields(p, w);  // each field's own bound, from ParamTable<AdaptiveControllerParams>
    // the bounds that depend on other fields (phi_min, psi_max and D_max are checked above)
    require(p.phi_max > p.phi_min, w, "phi_max must be > phi_min");
    require_in_range(p.phi_0, p.phi_min, p.phi_max, w, "phi_0");
    require_in_range(p.psi_0, -p.psi_max, p.psi_max, w, "psi_0");
    require_in_range(p.D_0, 0.0, p.D_max, w, "D_0");
    require(p.max_torque > 0.0, w, "max_torque must be > 0");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    reset();
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The current estimates psi, phi, D.
  const AdaptiveEstimates& estimates() const noexcept { return est_; }
  /// True when the last step ran the fallback (its measurement was not finite).
  bool in_fallback() const noexcept { return fallback_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    est_ = {p_.psi_0, p_.phi_0, p_.D_0};
    yd_rate_.reset();
    yd_acc_.reset();
    motor_rate_.reset();
    ff_rate_.reset();
    ff_acc_.reset();
    ff_.reset();
    filter_primed_ = false;
    filtered_ = filtered_rate_ = 0.0;
    fallback_ = false;
    torque_ = 0.0;
  }

  /// One control cycle: desired output y_d, measured output y (NaN on dropout),
  /// motor position (used by the fallback only), dt since the previous cycle.
  /// Returns the motor torque command, within +-max_torque; a non-finite y_d holds the last one.
  /// @param y_d the desired output
  /// @param y_measured the measured output, NaN on dropout (runs the fallback)
  /// @param motor_position the motor position (used by the fallback only)
  /// @param dt the time since the previous cycle, s
  /// @return the motor torque command
  double step(double y_d, double y_measured, double motor_position, double dt) noexcept {
    held_ = !std::isfinite(y_d);
    if (held_) return torque_;
    // The rate is known from the second sample on, the acceleration from the third.
    const bool rate_known = yd_rate_.primed();
    const double yd_rate = yd_rate_.update(y_d, dt);
    const double yd_acc = rate_known ? yd_acc_.update(yd_rate, dt) : 0.0;
    return step_with_derivatives(y_d, yd_rate, yd_acc, y_measured, motor_position, dt);
  }

  /// @brief As step(), with the desired output's rate and acceleration given (e.g.\ from a trajectory
  /// generator; a non-finite one counts as 0).
  /// @param y_d the desired output
  /// @param yd_rate its rate
  /// @param yd_acc its acceleration
  /// @param y_measured the measured output, NaN on dropout
  /// @param motor_position the motor position (used by the fallback only)
  /// @param dt the time since the previous cycle, s
  /// @return the motor torque command, within +-max_torque
  double step_with_derivatives(double y_d, double yd_rate, double yd_acc, double y_measured,
                               double motor_position, double dt) noexcept {
    if (!(dt > 0.0) || !std::isfinite(dt)) dt = 0.0;
    if (!std::isfinite(yd_rate)) yd_rate = 0.0;
    if (!std::isfinite(yd_acc)) yd_acc = 0.0;
    const double motor_rate = motor_rate_.update(motor_position, dt);
    const double x_ff = ff_.step_with_rate(y_d, yd_rate, dt);
    // acceleration of the feedforward motor path, known from its third sample on
    const bool ff_rate_known = ff_rate_.primed();
    const double ff_rate = ff_rate_.update(x_ff, dt);
    const double ff_acc = ff_rate_known ? ff_acc_.update(ff_rate, dt) : 0.0;
    if (p_.has_feedforward && p_.model_acceleration) yd_acc = slope_ * ff_acc;
    if (!std::isfinite(y_measured)) {
      fallback_ = true;
      filter_primed_ = false;  // restart the derivative filter when the sensor returns
      double u = 0.0;
      if (std::isfinite(motor_position)) {
        const double target = p_.has_feedforward ? x_ff : y_d;
        u = p_.fallback_kp * (target - motor_position) -
            p_.fallback_kd * (std::isfinite(motor_rate) ? motor_rate : 0.0);
      }
      return torque_ = saturate(u);
    }
    fallback_ = false;
    const double y_rate = filter(y_measured, dt);
    const double e = y_measured - y_d;
    const double e_rate = y_rate - yd_rate;
    const double s = e_rate + p_.lambda * e;
    const double nu_r = p_.lambda * e_rate - yd_acc;
    const double th = std::tanh(s / p_.epsilon);
    const double u = -p_.k_s * s - est_.psi * y_rate - est_.phi * nu_r - est_.D * th;
    if (dt > 0.0 && std::fabs(s) > p_.adaptation_deadzone) adapt(s, th, y_rate, nu_r, dt);
    return torque_ = saturate(u);
  }

  /// The filtered derivative y' of the measured output.
  double filtered_rate() const noexcept { return filtered_rate_; }

  /// The last step's status: held (non-finite y_d), fallback (no measurement), saturated
  /// (|torque| at max_torque).
  Status status() const noexcept {
    Status s = Status::ok;
    if (held_) s |= Status::held_nonfinite_input;
    if (fallback_) s |= Status::fallback;
    if (std::fabs(torque_) >= p_.max_torque) s |= Status::saturated;
    return s;
  }

 private:
  static BacklashInverseParams checked_feedforward(const Params& p) {
    BacklashInverseParams f = p.feedforward;
    f.limits = CommandLimits{};
    return f;
  }

  double saturate(double u) const noexcept {
    if (!std::isfinite(u)) return 0.0;
    return u > p_.max_torque ? p_.max_torque : (u < -p_.max_torque ? -p_.max_torque : u);
  }

  // Second-order low-pass differentiator: p'' = w^2 (y - p) - 2 zeta w p', by the
  // trapezoidal rule on at most 256 sub-steps: A-stable, so any dt is safe (semi-implicit
  // Euler diverged once w h > 2, e.g. one 4 s cycle, and its NaN then froze the torque at 0),
  // and second-order accurate without the numerical damping of backward Euler.
  double filter(double y, double dt) noexcept {
    if (!filter_primed_) {
      filtered_ = y;
      filtered_rate_ = 0.0;
      filter_primed_ = true;
      return 0.0;
    }
    const double w = 2.0 * 3.141592653589793 * p_.derivative_cutoff_hz;
    const double need = std::ceil(w * dt / 0.05);
    const int m = need < 1.0 ? 1 : (need > 256.0 ? 256 : static_cast<int>(need));
    const double h = dt / m;
    const double zw = p_.derivative_damping * w, hh = 0.5 * h;
    const double det = 1.0 + h * zw + hh * hh * w * w;
    for (int i = 0; i < m; ++i) {
      // (I - h/2 A) s_new = (I + h/2 A) s + h B y with s = (p, p'), A = [0 1; -w^2 -2 zeta w]
      const double r0 = filtered_ + hh * filtered_rate_;
      const double r1 = filtered_rate_ + hh * (-w * w * filtered_ - 2.0 * zw * filtered_rate_) +
                        h * w * w * y;
      filtered_rate_ = (r1 - hh * w * w * r0) / det;
      filtered_ = r0 + hh * filtered_rate_;
    }
    if (!std::isfinite(filtered_) || !std::isfinite(filtered_rate_)) {  // re-prime, stay finite
      filtered_ = y;
      filtered_rate_ = 0.0;
    }
    return filtered_rate_;
  }

  void adapt(double s, double th, double y_rate, double nu_r, double dt) noexcept {
    double psi = est_.psi + dt * p_.gamma_psi * (y_rate * s - p_.sigma_psi * est_.psi);
    double phi = est_.phi + dt * p_.gamma_phi * (nu_r * s - p_.sigma_phi * (est_.phi - p_.phi_0));
    double D = est_.D + dt * p_.gamma_D * (s * th - p_.sigma_D * est_.D);
    if (!std::isfinite(psi) || !std::isfinite(phi) || !std::isfinite(D)) return;
    est_.psi = psi > p_.psi_max ? p_.psi_max : (psi < -p_.psi_max ? -p_.psi_max : psi);
    est_.phi = phi > p_.phi_max ? p_.phi_max : (phi < p_.phi_min ? p_.phi_min : phi);
    est_.D = D > p_.D_max ? p_.D_max : (D < 0.0 ? 0.0 : D);
  }

  Params p_;
  AdaptiveEstimates est_{};
  RateEstimator yd_rate_{}, yd_acc_{}, motor_rate_{}, ff_rate_{}, ff_acc_{};
  BacklashInverseFeedforward ff_;
  double slope_ = 1.0;
  bool filter_primed_ = false;
  double filtered_ = 0.0, filtered_rate_ = 0.0;
  bool fallback_ = false;
  bool held_ = false;
  double torque_ = 0.0;
};

}  // namespace tendonsheath
