// Motor models that turn a command into the proximal pulley angle (rad) or,
// for a SingleTendonPlant, the proximal displacement (m).
//
// Position: a position-controlled drive seen as a second-order lag,
//   q'' = w^2 (q_cmd - q) - 2 zeta w q',   w = 2 pi f_n,
// with |q''| <= max_accel and |q'| <= max_speed; integrated with backward
// Euler on sub-steps of w h <= 0.1 (at most max_substeps). The first step
// after reset() starts at rest at the command. With integral action
// (integral_time T_i > 0, a PID servo) it becomes
//   q'' = w^2 [(q_cmd - q) + z / T_i] - 2 zeta w q' + ...,   z' = q_cmd - q,
// stable for T_i > 1 / (2 zeta w) (Routh on s^3 + 2 zeta w s^2 + w^2 s + w^2 / T_i);
// z is integrated by the same backward-Euler sub-steps (z_new = z + h (q_cmd - q_new))
// and held while the speed or acceleration limit cuts the motion (anti-windup).
// Torque: J q'' + b q' = sat(tau_cmd, max_torque) + tau_ext, where tau_ext
// is the torque the tendons exert on the pulley (supplied by the caller);
// semi-implicit Euler on the same sub-steps (h <= J/b/10 when b > 0). It
// starts at rest at q = 0.
//
// Drive-train effects (both kinds, all off by default):
// - Coulomb friction tau_c and viscous friction b_m on the motor shaft. The
//   position servo then feels torques through its reflected inertia J_r
//   (inertia > 0): q'' = w^2 (q_cmd - q) - 2 zeta w q'
//   + (tau_ext - b_m q' - tau_c sgn q') / J_r, so the tendons' torque deflects
//   it and friction leaves a steady error up to tau_c / (J_r w^2) (a constant
//   torque tau leaves tau / (J_r w^2); with integral action, none). With
//   J_r = 0 (default) it is the ideal lag above and ignores torques.
//   Coulomb friction is implicit at the velocity level: the shaft sticks when
//   the friction impulse h tau_c / J can stop it within a sub-step, so it
//   sticks exactly, never chatters.
// - Gear backlash: a play of total width g between the motor shaft (q, what a
//   motor encoder reads: position()) and the proximal pulley (output()): the
//   pulley keeps its angle while the shaft crosses the gap (bearing friction
//   holds it) and is carried at q -+ g/2 otherwise. step() returns the pulley
//   angle, which drives the plant.
#pragma once

#include <cmath>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// What a Motor's command is: Position (a position-controlled drive: a commanded angle) or Torque (a
/// commanded torque).
enum class MotorKind : int { Position = 0, Torque = 1 };

/// Parameters of Motor (validated by its constructor); angles in rad (m for a SingleTendonPlant).
struct MotorParams {
  MotorKind kind = MotorKind::Position;  ///< a position-controlled drive or a torque-driven one
  double bandwidth_hz = 1.5;  ///< natural frequency f_n (position)
  double damping = 0.7;       ///< zeta (position)
  double max_speed = std::numeric_limits<double>::infinity();  ///< largest speed |q'|, rad/s (both)
  double max_accel = std::numeric_limits<double>::infinity();  ///< largest acceleration |q''|, rad/s^2 (position)
  /// J, kg m^2: the rotor's inertia (torque, > 0) or the inertia reflected to a position servo
  /// (position, >= 0; 0 = the ideal lag, which ignores torques)
  double inertia = 0.0;
  double viscous = 0.2;       ///< b (torque)
  double max_torque = std::numeric_limits<double>::infinity();  ///< torque limit of the command, N m (torque)
  int max_substeps = 256;  ///< most integration sub-steps in one step(), >= 1 (bounds its work)
  double coulomb_friction = 0.0;   ///< tau_c, N m (both; position needs inertia > 0)
  double viscous_friction = 0.0;   ///< b_m, N m s/rad (position; torque kind: use viscous)
  double gear_backlash = 0.0;      ///< g, rad: total play between shaft and pulley (both)
  /// T_i, s (position): integral time of a PID servo, q'' gains w^2 z / T_i with z' = q_cmd - q,
  /// so a constant load leaves no steady error; 0 = none (the PD servo); else > 1/(2 zeta w)
  double integral_time = 0.0;
};

namespace detail {
/// The rows of a position motor only (bandwidth_hz, damping, ...).
constexpr bool is_position_motor(const MotorParams& p) { return p.kind == MotorKind::Position; }
/// The rows of a torque motor only (viscous, max_torque).
constexpr bool is_torque_motor(const MotorParams& p) { return p.kind == MotorKind::Torque; }
}  // namespace detail

/// The parameter table of MotorParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<MotorParams> {
  static constexpr const char* owner = "Motor";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("kind", &MotorParams::kind, "", any(),
            "MotorKind: a position-controlled drive or a torque-driven one"),
      only_if(param("bandwidth_hz", &MotorParams::bandwidth_hz, "Hz", positive(),
                    "natural frequency f_n of the position loop (position)"),
              &detail::is_position_motor, "position"),
      only_if(param("damping", &MotorParams::damping, "", positive(),
                    "zeta of the position loop (position)"),
              &detail::is_position_motor, "position"),
      param("max_speed", &MotorParams::max_speed, "rad/s", positive_or_inf(),
            "largest speed |q'| (both)"),
      only_if(param("max_accel", &MotorParams::max_accel, "rad/s^2", positive_or_inf(),
                    "largest acceleration |q''| (position)"),
              &detail::is_position_motor, "position"),
      param("inertia", &MotorParams::inertia, "kg m^2", documented(0.0, true, kInf, false),
            "J of the rotor (> 0 for a torque motor)"),
      only_if(param("viscous", &MotorParams::viscous, "N m s/rad", non_negative(),
                    "b, the rotor's viscous friction (torque)"),
              &detail::is_torque_motor, "torque"),
      only_if(param("max_torque", &MotorParams::max_torque, "N m", positive_or_inf(),
                    "torque limit of the command (torque)"),
              &detail::is_torque_motor, "torque"),
      param("max_substeps", &MotorParams::max_substeps, "", at_least(1),
            "most integration sub-steps in one step() (bounds its work)"),
      param("coulomb_friction", &MotorParams::coulomb_friction, "N m", non_negative(),
            "tau_c (both; position needs inertia > 0)"),
      only_if(param("viscous_friction", &MotorParams::viscous_friction, "N m s/rad", non_negative(),
                    "b_m (position; torque kind: use viscous)"),
              &detail::is_position_motor, "position"),
      param("gear_backlash", &MotorParams::gear_backlash, "rad", non_negative(),
            "g: total play between shaft and pulley (both)"),
      only_if(param("integral_time", &MotorParams::integral_time, "s", non_negative(),
                    "T_i of the position loop's integral action, 0 = none (position)"),
              &detail::is_position_motor, "position"));
};

/// @brief A motor model that turns a command into the proximal pulley angle (rad), or for a
/// SingleTendonPlant the proximal displacement (m).
///
/// Position: a second-order lag q'' = w^2 (q_cmd - q) - 2 zeta w q', w = 2 pi f_n, with
/// |q''| <= max_accel and |q'| <= max_speed, backward Euler on sub-steps of w h <= 0.1; the first
/// step after reset() starts at rest at the command. With integral_time T_i > 0 (a PID servo)
/// q'' gains w^2 z / T_i, z' = q_cmd - q (held while a limit cuts the motion). Torque:
/// J q'' + b q' = sat(tau_cmd, max_torque) + tau_ext, with tau_ext the tendons' torque on the
/// pulley; it starts at rest at 0.
/// Optional (off by default): Coulomb and viscous shaft friction (the position servo feels torques
/// through its reflected inertia J_r) and gear backlash between the shaft (position()) and the
/// pulley (output()). step() is noexcept, allocates nothing and takes at most max_substeps
/// sub-steps.
class Motor {
  static constexpr double kPi = 3.14159265358979323846;

 public:
  /// The parameter struct its constructor takes.
  using Params = MotorParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit Motor(const Params& p) : p_(p) {
    const char* w = "Motor";
    require(p.kind == MotorKind::Position || p.kind == MotorKind::Torque, w, "unknown kind");
    // each field's own bound, from ParamTable<MotorParams> (a row of one kind only for it)
    validate_fields(p, w);
    // the inertia's bound by kind, and the rules between fields
    if (p.kind == MotorKind::Position) {
      require_non_negative(p.inertia, w, "inertia");
      const double bound = 1.0 / (2.0 * p.damping * 2.0 * kPi * p.bandwidth_hz);
      require(p.integral_time == 0.0 || p.integral_time > bound, w,
              "integral_time must be 0 (no integral action) or > 1 / (2 damping w) = ", bound,
              " s for a stable loop (got ", p.integral_time, ")");
      require((p.coulomb_friction == 0.0 && p.viscous_friction == 0.0) ||
                  p.inertia > 0.0,
              w, "coulomb_friction and viscous_friction of a position motor act through its "
                 "inertia, which must then be > 0");
    } else {
      require_positive(p.inertia, w, "inertia");
    }
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    q_ = 0.0;
    v_ = 0.0;
    z_ = 0.0;
    pulley_ = 0.0;
    initialised_ = false;
  }

  /// Advance by dt under command u (angle or torque); returns the proximal
  /// pulley angle (the shaft angle without gear backlash). A non-finite command
  /// holds the last position.
  /// @param u the command: an angle (Position kind) or a torque (Torque kind)
  /// @param dt the time since the previous step, s
  /// @param tau_ext the torque the tendons exert on the pulley (the plant's drive_reaction())
  /// @return the proximal pulley angle, the plant's input
  double step(double u, double dt, double tau_ext = 0.0) noexcept {
    held_ = !std::isfinite(u);
    if (held_) {
      clamped_ = saturated_ = false;
      return pulley_;
    }
    if (!std::isfinite(tau_ext)) tau_ext = 0.0;
    if (!initialised_) {
      initialised_ = true;
      if (p_.kind == MotorKind::Position) q_ = u;
      v_ = 0.0;
      pulley_ = q_;
    }
    clamped_ = saturated_ = false;
    if (!(dt > 0.0) || !std::isfinite(dt)) return pulley_;
    const bool position = p_.kind == MotorKind::Position;
    const double w = 2.0 * kPi * p_.bandwidth_hz;
    // torques act through J (the rotor's, or a position servo's reflected one: 0 ignores them)
    const double J = p_.inertia;
    const double inv_J = J > 0.0 ? 1.0 / J : 0.0;
    const double b = position ? p_.viscous_friction : p_.viscous;
    const double rate = position ? w : (b > 0.0 ? b * inv_J : 0.0);
    double m = std::ceil(dt * rate / 0.1);
    const int n = m >= p_.max_substeps ? p_.max_substeps : (m >= 1.0 ? static_cast<int>(m) : 1);
    // A sub-step spans at most 10 time constants (1 s without one): a longer step covers
    // only n such sub-steps, by when the drive has settled, and is flagged (clamped()).
    const double h_max = rate > 0.0 ? 10.0 / rate : 1.0;
    double h = dt / n;
    if (h > h_max) {
      h = h_max;
      clamped_ = true;
    }
    double tau = u;
    if (!position && std::fabs(tau) > p_.max_torque) {
      tau = std::copysign(p_.max_torque, tau);
      saturated_ = true;
    }
    const double stick = h * p_.coulomb_friction * inv_J;  // friction impulse per sub-step
    // integral gain w^2 / T_i (0: none; the PD servo's arithmetic is then untouched)
    const double ki = position && p_.integral_time > 0.0 ? w * w / p_.integral_time : 0.0;
    for (int i = 0; i < n; ++i) {
      double num, den;
      if (position) {
        num = v_ + h * (w * w * (u - q_) + tau_ext * inv_J);
        den = 1.0 + 2.0 * p_.damping * w * h + w * w * h * h + h * b * inv_J;
        if (ki > 0.0) {  // backward Euler on z too: z_new = z + h (u - q - h v_new)
          num += h * ki * (z_ + h * (u - q_));
          den += ki * h * h * h;
        }
      } else {
        num = v_ + h * (tau + tau_ext) * inv_J;
        den = 1.0 + h * b * inv_J;
      }
      double v_new = std::fabs(num) <= stick ? 0.0 : (num - std::copysign(stick, num)) / den;
      const bool limited = limit(v_new, h, position);
      const double q_new = q_ + h * v_new;
      // anti-windup: z is held while a limit cuts the motion
      const double z_new = ki > 0.0 && !limited ? z_ + h * (u - q_new) : z_;
      if (!std::isfinite(v_new) || !std::isfinite(q_new) || !std::isfinite(z_new)) {
        v_ = 0.0;  // hold a finite state
        z_ = 0.0;
        clamped_ = true;
        break;
      }
      v_ = v_new;
      q_ = q_new;
      z_ = z_new;
    }
    const double half = 0.5 * p_.gear_backlash;
    if (pulley_ < q_ - half) pulley_ = q_ - half;
    if (pulley_ > q_ + half) pulley_ = q_ + half;
    return pulley_;
  }

  /// Motor shaft angle (what a motor encoder reads).
  double position() const noexcept { return q_; }
  /// The integral of the position error, z = int (q_cmd - q) dt, rad s (0 without integral
  /// action).
  double integral() const noexcept { return z_; }
  /// Motor shaft velocity, rad/s.
  double velocity() const noexcept { return v_; }
  /// The last step was longer than the sub-steps can span, or its command would have driven
  /// the state beyond a double: the motor then covered less (or held), and stayed finite.
  bool clamped() const noexcept { return clamped_; }
  /// The last step's status: held (non-finite command), input_clamped (see clamped()),
  /// saturated (the torque limit, or the speed limit, cut the drive in this step).
  Status status() const noexcept {
    Status s = Status::ok;
    if (held_) s |= Status::held_nonfinite_input;
    if (clamped_) s |= Status::input_clamped;
    if (saturated_) s |= Status::saturated;
    return s;
  }
  /// Proximal pulley angle (after the gear play), the plant's input.
  double output() const noexcept { return pulley_; }
  /// Put the shaft (and the pulley) at angle q with velocity v, and the integral of the
  /// position error at z (a snapshot: position(), velocity(), integral()).
  /// @param q the shaft angle
  /// @param v the shaft velocity
  /// @param z the integral of the position error (used with integral action only)
  void set_state(double q, double v, double z = 0.0) noexcept {
    q_ = q;
    v_ = v;
    z_ = z;
    pulley_ = q;
    initialised_ = true;
  }

 private:
  // The acceleration (position kind) and speed limits on a sub-step's new velocity; true when
  // either cut it (the speed limit also flags saturated_).
  bool limit(double& v_new, double h, bool position) noexcept {
    bool cut = false;
    if (position) {
      const double amax = p_.max_accel * h;
      if (v_new - v_ > amax) {
        v_new = v_ + amax;
        cut = true;
      }
      if (v_new - v_ < -amax) {
        v_new = v_ - amax;
        cut = true;
      }
    }
    if (std::fabs(v_new) > p_.max_speed) {
      v_new = std::copysign(p_.max_speed, v_new);
      saturated_ = true;
      cut = true;
    }
    return cut;
  }

  Params p_;
  double q_ = 0.0, v_ = 0.0, z_ = 0.0, pulley_ = 0.0;
  bool clamped_ = false;
  bool saturated_ = false;
  bool held_ = false;
  bool initialised_ = false;
};

}  // namespace tendonsheath
