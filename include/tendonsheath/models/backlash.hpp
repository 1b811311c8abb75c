// Classic backlash (Tao & Kokotovic): two straight branches with slopes c_r,
// c_l and dead-band offsets B_r, B_l; between them the output holds.
//
//   y = c_r (x - B_r)   while x increases and y would fall below that line
//   y = c_l (x + B_l)   while x decreases and y would rise above that line
//   y unchanged          otherwise (inside the dead band)
//
// i.e. y <- clamp(y, c_r (x - B_r), c_l (x + B_l)). With c_r != c_l the lines cross at
// x* = (c_r B_r + c_l B_l)/(c_r - c_l); past it the band would be inverted and a tiny
// reversal would jump from one line to the other. There the band is clamped to zero
// width: y follows the lines' mean, which meets both at x*. So y is continuous, with
// |dy| <= max(c_r, c_l) |dx| for any input, and unchanged wherever the lines do not cross.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of Backlash (validated by its constructor).
struct BacklashParams {
  double c_r = 1.0;  ///< slope of the right (rising) branch
  double c_l = 1.0;  ///< slope of the left (falling) branch
  double B_r = 0.1;  ///< dead-band offset of the right branch, input units
  double B_l = 0.1;  ///< dead-band offset of the left branch, input units

  /// How many identifiable parameters assign() reads: the table's Role::parameter rows
  /// (checked against it below the table).
  static constexpr std::size_t vector_size = 4;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the order of the table's
  /// parameter rows (the Python param_names); the options are kept.
  void assign(const double* v) noexcept;
};

/// The parameter table of BacklashParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<BacklashParams> {
  static constexpr const char* owner = "Backlash";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("c_r", &BacklashParams::c_r, "output/input", positive(),
            "slope of the right (rising) branch"),
      param("c_l", &BacklashParams::c_l, "output/input", positive(),
            "slope of the left (falling) branch"),
      param("B_r", &BacklashParams::B_r, "input", non_negative(),
            "dead-band offset of the right branch"),
      param("B_l", &BacklashParams::B_l, "input", non_negative(),
            "dead-band offset of the left branch"));
};

static_assert(BacklashParams::vector_size == parameter_count<BacklashParams>(),
              "vector_size is the number of the table's parameter rows");
inline void BacklashParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

/// @brief Classic backlash (Tao & Kokotovic): y <- clamp(y, c_r (x - B_r), c_l (x + B_l)).
///
/// Two straight branches with slopes c_r, c_l and dead-band offsets B_r, B_l; between them the
/// output holds. Past the crossing of the lines (c_r != c_l) the band has zero width and y follows
/// their mean, so y is continuous with |dy| <= max(c_r, c_l) |dx|. Rate-independent.
class Backlash {
 public:
  /// The parameter struct its constructor takes.
  using Params = BacklashParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit Backlash(const Params& p) : p_(p) {
    validate_fields(p, "Backlash");  // each field's bound, from ParamTable<BacklashParams>
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { initialised_ = false; }

  /// The first call after reset() starts in the middle of the band at x.
  /// @param x the input; a non-finite x is ignored and the last output held (0 before the first step)
  /// @return the output y
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    if (held_) return initialised_ ? y_ : 0.0;
    const double right = p_.c_r * (x - p_.B_r);
    const double left = p_.c_l * (x + p_.B_l);
    if (!initialised_) {
      y_ = saturated(0.5 * (right + left));
      x_ = x;
      initialised_ = true;
      return y_;
    }
    double lo = right, hi = left;
    if (lo > hi) lo = hi = 0.5 * (right + left);  // past the crossing: a zero-width band
    y_ = saturated(y_ < lo ? lo : (y_ > hi ? hi : y_));
    x_ = x;
    return y_;
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input when its input was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }

  /// Put the model in a given state (for inverses and identification).
  void set_state(double x, double y) noexcept {
    x_ = x;
    y_ = y;
    initialised_ = true;
  }
  /// The input of the last step() (or of set_state()).
  double last_input() const noexcept { return x_; }
  /// False until the first finite step() or set_state() after construction or reset().
  bool initialised() const noexcept { return initialised_; }

 private:
  // c x overflows for a finite x near the largest double: the output saturates there
  static double saturated(double y) noexcept {
    constexpr double big = std::numeric_limits<double>::max();
    return y > big ? big : (y < -big ? -big : y);
  }

  Params p_;
  double x_ = 0.0;
  double y_ = 0.0;
  bool initialised_ = false;
  bool held_ = false;
};

}  // namespace tendonsheath
