// Dead zone (Tao & Kokotovic): a memoryless map that passes nothing while the input is inside
// the band [-d_l, d_r], and is linear outside it,
//
//   y = c_r (x - d_r)   for x > d_r
//   y = c_l (x + d_l)   for x < -d_l
//   y = 0               otherwise.
//
// In a tendon-sheath drive it is the slack the motor takes up before the tendon carries load
// (a pull-pull pair's pretension lost, a loose tendon). Rate-independent; continuous; nondecreasing.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "../param_table.hpp"
#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// Parameters of DeadZone (validated by its constructor).
struct DeadZoneParams {
  double c_r = 1.0;  ///< slope right of the band
  double c_l = 1.0;  ///< slope left of the band
  double d_r = 0.1;  ///< right edge of the band, input units
  double d_l = 0.1;  ///< left edge of the band (at -d_l), input units

  /// How many identifiable parameters assign() reads: the table's parameter rows.
  static constexpr std::size_t vector_size = 4;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the table's order.
  void assign(const double* v) noexcept;
};

/// The parameter table of DeadZoneParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<DeadZoneParams> {
  static constexpr const char* owner = "DeadZone";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the bounds with validate_fields()
  /// The rows, in the order of the struct.
  static constexpr auto fields = std::make_tuple(
      param("c_r", &DeadZoneParams::c_r, "output/input", positive(), "slope right of the band"),
      param("c_l", &DeadZoneParams::c_l, "output/input", positive(), "slope left of the band"),
      param("d_r", &DeadZoneParams::d_r, "input", non_negative(), "right edge of the band"),
      param("d_l", &DeadZoneParams::d_l, "input", non_negative(),
            "left edge of the band (at -d_l)"));
};

static_assert(DeadZoneParams::vector_size == parameter_count<DeadZoneParams>(),
              "vector_size is the number of the table's parameter rows");
inline void DeadZoneParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

/// @brief Dead zone (Tao & Kokotovic): y = c_r (x - d_r) right of the band, c_l (x + d_l) left
/// of it, 0 inside [-d_l, d_r].
///
/// Memoryless and rate-independent (step() ignores dt); continuous and nondecreasing.
class DeadZone {
 public:
  /// The parameter struct its constructor takes.
  using Params = DeadZoneParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit DeadZone(const Params& p) : p_(p) { validate_fields(p, "DeadZone"); }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Nothing to reset: the map has no state (output() keeps the last value).
  void reset() noexcept {}

  /// @param x the input; a non-finite x is ignored and the last output held
  /// @return the output y
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    if (held_) return y_;
    double y = 0.0;
    if (x > p_.d_r) y = p_.c_r * (x - p_.d_r);
    else if (x < -p_.d_l) y = p_.c_l * (x + p_.d_l);
    constexpr double big = std::numeric_limits<double>::max();  // c x overflows near the limit
    y_ = y > big ? big : (y < -big ? -big : y);
    return y_;
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input when its input was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }

 private:
  Params p_;
  double y_ = 0.0;
  bool held_ = false;
};

}  // namespace tendonsheath
