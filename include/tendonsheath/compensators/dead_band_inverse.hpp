// The classical dead-zone inverse (Tao and Kokotovic, "Adaptive control of systems with unknown
// output backlash/dead-zone", 1994; Zhou, Wen and Zhang 2006 for the smoothed form): the command
// that makes a dead zone's output equal the desired one.
//
// The dead zone: y = c_r (u - d_r) for u > d_r, 0 for -d_l <= u <= d_r, c_l (u + d_l) for u < -d_l.
// Its inverse: u = y_d / c_r + d_r for y_d > 0, y_d / c_l - d_l for y_d < 0, and the middle of
// the dead zone, (d_r - d_l) / 2, at y_d = 0. The jump of d_r + d_l at 0 makes a controller
// chatter about 0; a smoothing width eps > 0 joins the middle to each branch's value at +-eps by
// a straight line, so the command is continuous (exact outside [-eps, eps]; inside it the output
// has the desired one's sign and is no larger).
#pragma once

#include <cmath>
#include <tuple>

#include "../param_table.hpp"
#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// Parameters of DeadBandInverse (validated by its constructor).
struct DeadBandInverseParams {
  double c_r = 1.0;   ///< slope of the dead zone's right branch, > 0
  double c_l = 1.0;   ///< slope of the dead zone's left branch, > 0
  double d_r = 0.0;   ///< right edge of the dead zone (input units), >= 0
  double d_l = 0.0;   ///< left edge of the dead zone, as a distance below 0 (input units), >= 0
  double eps = 0.0;   ///< smoothing width around y_d = 0 (output units), >= 0; 0: the exact jump
};

/// The parameter table of DeadBandInverseParams (param_table.hpp): unit, range and doc of each
/// field.
template <>
struct ParamTable<DeadBandInverseParams> {
  static constexpr const char* owner = "DeadBandInverse";  ///< the class its constructor takes it
  /// its constructor checks the bounds with validate_fields()
  static constexpr bool checked_from_table = true;
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("c_r", &DeadBandInverseParams::c_r, "", positive(),
            "slope of the dead zone's right branch (output per input)"),
      param("c_l", &DeadBandInverseParams::c_l, "", positive(),
            "slope of the dead zone's left branch (output per input)"),
      param("d_r", &DeadBandInverseParams::d_r, "rad", non_negative(),
            "right edge of the dead zone: no output for 0 <= u <= d_r"),
      param("d_l", &DeadBandInverseParams::d_l, "rad", non_negative(),
            "left edge of the dead zone, below 0: no output for -d_l <= u <= 0"),
      option("eps", &DeadBandInverseParams::eps, "", non_negative(),
             "smoothing width around y_d = 0, in output units; 0: the exact jump"));
};

/// @brief The inverse of a dead zone (see the file's comment): desired output in, command out;
/// step() is noexcept, allocation-free and O(1).
class DeadBandInverse {
 public:
  /// The parameter struct its constructor takes.
  using Params = DeadBandInverseParams;

  /// @param p the dead zone and the smoothing width; throws std::invalid_argument naming a bad one.
  explicit DeadBandInverse(const Params& p) : p_(p) {
    validate_fields(p, "DeadBandInverse");  // each field's bound, from the table
  }

  /// The parameters.
  const Params& params() const noexcept { return p_; }
  /// Start afresh: the held command back to 0.
  void reset() noexcept {
    u_ = 0.0;
    held_ = false;
  }
  /// @param y_d the desired output; a non-finite one holds the last command
  /// @param dt the time since the previous step, s (unused: the inverse is static)
  /// @return the command u that the dead zone maps to y_d (outside the smoothing width)
  double step(double y_d, double dt) noexcept {
    (void)dt;
    held_ = !std::isfinite(y_d);
    if (!held_) u_ = command(y_d);
    return u_;
  }
  /// The last step's status: held_nonfinite_input when its input was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }

 private:
  // the exact inverse; at 0 the middle of the dead zone (its output is 0 there too)
  double branch(double y) const noexcept {
    if (y > 0.0) return y / p_.c_r + p_.d_r;
    if (y < 0.0) return y / p_.c_l - p_.d_l;
    return 0.5 * (p_.d_r - p_.d_l);
  }
  // within the smoothing width, the line from the middle (at 0) to the branch's value at +-eps:
  // continuous, and the dead zone's output has y's sign and no more than its size
  double command(double y) const noexcept {
    if (std::fabs(y) >= p_.eps) return branch(y);
    const double middle = branch(0.0), end = branch(std::copysign(p_.eps, y));
    return middle + (end - middle) * std::fabs(y) / p_.eps;
  }

  Params p_;
  double u_ = 0.0;
  bool held_ = false;
};

}  // namespace tendonsheath
