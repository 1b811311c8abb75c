// Direct inverse feedforward of backlash-like hysteresis (spec D.2), and the
// exact inverse of a Prandtl-Ishlinskii operator, as streaming compensators.
//
// Backlash / BoucWenBacklash with branches c_r (x - B_r) and c_l (x + B_l):
//   phi_d = (1 + tanh(y_d' / v_eps)) / 2
//   x_ff  = [y_d + phi_d c_r B_r - (1 - phi_d) c_l B_l] / [phi_d c_r + (1 - phi_d) c_l]
// No iteration; the denominator is >= min(c_r, c_l) > 0. v_eps -> 0 gives the
// exact backlash inverse (a jump of B_r + B_l at each reversal).
#pragma once

#include <cmath>

#include "../models/backlash.hpp"
#include "../models/prandtl_ishlinskii.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of BacklashInverseFeedforward: the identified backlash branches (a BacklashParams:
/// c_r, c_l, B_r, B_l, in the command's units), the smoothing and the command limits (validated
/// by its constructor).
struct BacklashInverseParams : BacklashParams {
  double smoothing = 0.05;  ///< v_eps, the smoothing speed of the direction switch, output units per s
  CommandLimits limits{};  ///< the motor command's limits
};

/// The parameter table of BacklashInverseParams (param_table.hpp): the model's rows (those of
/// BacklashParams, not a copy), then the smoothing and the limits.
template <>
struct ParamTable<BacklashInverseParams> {
  static constexpr const char* owner = "BacklashInverseFeedforward";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::tuple_cat(
      rows_of<BacklashInverseParams, BacklashParams>(),
      std::make_tuple(
          param("smoothing", &BacklashInverseParams::smoothing, "output/s", positive(),
                "v_eps, the smoothing speed of the direction switch"),
          param("limits", &BacklashInverseParams::limits, "", any(),
                "CommandLimits: the command's min, max and max_rate")));
};

/// @brief Direct inverse feedforward of backlash-like hysteresis (spec D.2): no iteration.
///
/// phi_d = (1 + tanh(y_d' / v_eps)) / 2 and x_ff = [y_d + phi_d c_r B_r - (1 - phi_d) c_l B_l] /
/// [phi_d c_r + (1 - phi_d) c_l] (the denominator is >= min(c_r, c_l) > 0), then shaped to the
/// command limits. v_eps -> 0 gives the exact backlash inverse. Inverts Backlash and
/// BoucWenBacklash.
class BacklashInverseFeedforward {
 public:
  /// The parameter struct its constructor takes.
  using Params = BacklashInverseParams;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit BacklashInverseFeedforward(const Params& p) : p_(p), shaper_(p.limits) {
    const char* w = "BacklashInverseFeedforward";
    validate_fields(p, w);  // c_r .. smoothing, from ParamTable<BacklashInverseParams>
    p.limits.validate(w);
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    rate_.reset();
    shaper_.reset();
  }

  /// Desired output y_d at this cycle, dt since the previous one; returns the motor command.
  /// @param y_d the desired output; a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s (the desired rate is y_d's backward difference)
  /// @return the motor command, within the limits
  double step(double y_d, double dt) noexcept {
    if (!std::isfinite(y_d)) return shaper_.apply(NAN, dt);
    return step_with_rate(y_d, rate_.update(y_d, dt), dt);
  }

  /// Same, with the desired output rate given (e.g.\ from a trajectory generator).
  double step_with_rate(double y_d, double y_d_rate, double dt) noexcept {
    if (!std::isfinite(y_d_rate)) y_d_rate = 0.0;
    return shaper_.apply(inverse(y_d, smooth_direction(y_d_rate, p_.smoothing)), dt);
  }
  /// The last step's status: held_nonfinite_input (y_d not finite) and the command shaper's
  /// (saturated: the command was cut to its limits).
  Status status() const noexcept { return shaper_.status(); }

  /// New branches (c_r, c_l, B_r, B_l = values[0..3]: a route that changed them), the rate and
  /// the shaper kept. False (nothing changed) when c_r or c_l is not > 0 or B_r or B_l not >= 0.
  bool set_branches(const double* values) noexcept {
    const double c_r = values[0], c_l = values[1], B_r = values[2], B_l = values[3];
    const bool ok = std::isfinite(c_r) && c_r > 0.0 && std::isfinite(c_l) && c_l > 0.0 &&
                    std::isfinite(B_r) && B_r >= 0.0 && std::isfinite(B_l) && B_l >= 0.0;
    if (!ok) return false;
    p_.c_r = c_r;
    p_.c_l = c_l;
    p_.B_r = B_r;
    p_.B_l = B_l;
    return true;
  }

  /// The unshaped inverse x_ff for desired output y_d and direction weight phi in [0, 1].
  double inverse(double y_d, double phi) const noexcept {
    return (y_d + phi * p_.c_r * p_.B_r - (1.0 - phi) * p_.c_l * p_.B_l) /
           (phi * p_.c_r + (1.0 - phi) * p_.c_l);
  }

 private:
  Params p_;
  RateEstimator rate_{};
  CommandShaper shaper_{};
};

/// The exact Prandtl-Ishlinskii inverse (PrandtlIshlinskiiInverse) as a compensator: its command
/// shaped to the motor's limits.
class PrandtlIshlinskiiFeedforward {
 public:
  /// @param p the identified operator (thresholds[0] must be 0)
  /// @param limits the motor command's limits
  /// Throws std::invalid_argument naming the first bad parameter.
  PrandtlIshlinskiiFeedforward(const PrandtlIshlinskiiParams& p, const CommandLimits& limits)
      : inverse_(p), shaper_(limits) {
    limits.validate("PrandtlIshlinskiiFeedforward");
  }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    inverse_.reset();
    shaper_.reset();
  }
  /// @param y_d the desired output; a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s
  /// @return the motor command
  double step(double y_d, double dt) noexcept { return shaper_.apply(inverse_.step(y_d), dt); }
  /// The inverse's status (held, input_clamped, out_of_range) and the shaper's (saturated).
  Status status() const noexcept { return inverse_.status() | shaper_.status(); }
  /// Keep the commands inside `range` before the limits (see PrandtlIshlinskiiInverse::set_range).
  void set_range(const InputRange& range) { inverse_.set_range(range); }

 private:
  PrandtlIshlinskiiInverse inverse_;
  CommandShaper shaper_;
};

}  // namespace tendonsheath
