// The input range an inverse's command stays in: the range of the inputs its model was
// identified on, widened by a margin. A command that would leave it is held at its edge and
// the step reports Status::out_of_range (the target is unreachable inside the range).
#pragma once

#include <cmath>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// @brief The closed interval [lo, hi] an inverse's command must stay in (+-inf: unbounded).
struct InputRange {
  double lo = -std::numeric_limits<double>::infinity();  ///< smallest command
  double hi = std::numeric_limits<double>::infinity();   ///< largest command

  /// The identified range [lo, hi] widened by margin * (hi - lo) beyond each end.
  /// @param lo the smallest training input
  /// @param hi the largest training input (>= lo)
  /// @param margin the fraction of the span allowed beyond each end, >= 0
  /// @return the widened range; throws std::invalid_argument on bad values
  static InputRange identified(double lo, double hi, double margin) {
    const char* w = "InputRange";
    require(std::isfinite(lo) && std::isfinite(hi) && lo <= hi, w,
            "the input range needs finite lo <= hi (got ", lo, ", ", hi, ")");
    require_non_negative(margin, w, "range_margin");
    const double m = margin * (hi - lo);
    return {lo - m, hi + m};
  }

  /// Throws std::invalid_argument (message starting with `where`) unless lo <= hi, neither NaN.
  void validate(const char* where) const {
    require(!std::isnan(lo) && !std::isnan(hi) && lo <= hi, where,
            "the input range needs lo <= hi (got lo=", lo, ", hi=", hi, ")");
  }
  /// True when either end is finite.
  bool bounded() const noexcept { return std::isfinite(lo) || std::isfinite(hi); }
  /// True when lo <= x <= hi.
  bool contains(double x) const noexcept { return x >= lo && x <= hi; }
  /// x clamped to [lo, hi].
  double clamp(double x) const noexcept { return x < lo ? lo : (x > hi ? hi : x); }
  /// The range mapped through x -> offset + scale * x (scale > 0).
  InputRange mapped(double offset, double scale) const noexcept {
    return {offset + scale * lo, offset + scale * hi};
  }
  /// The range mapped through x -> (x - offset) / scale (scale > 0): into a Scaled model's units.
  InputRange unmapped(double offset, double scale) const noexcept {
    return {(lo - offset) / scale, (hi - offset) / scale};
  }
};

/// @brief A command held inside an InputRange, with the flag of the last hold.
class RangeGuard {
 public:
  RangeGuard() = default;
  /// @param range the range (validated by the owner)
  explicit RangeGuard(const InputRange& range) : range_(range) {}
  /// @param x the command
  /// @return x clamped to the range; out_of_range() tells whether it was moved
  double apply(double x) noexcept {
    held_ = !range_.contains(x) && !std::isnan(x);
    return held_ ? range_.clamp(x) : x;
  }
  /// Status::out_of_range when the last apply() moved its command, else ok.
  Status status() const noexcept { return held_ ? Status::out_of_range : Status::ok; }
  /// Forget the last flag.
  void reset() noexcept { held_ = false; }
  /// The range.
  const InputRange& range() const noexcept { return range_; }

 private:
  InputRange range_{};
  bool held_ = false;
};

}  // namespace tendonsheath
