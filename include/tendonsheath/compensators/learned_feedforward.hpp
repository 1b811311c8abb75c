// A learned correction table added to any feedforward's command (iterative learning control).
//
// A surgeon repeats a motion and the tool tip's error repeats with it. Iterative learning
// (Python's tendonsheath.compensate.IterativeLearning) learns, over trials with a tip sensor, a
// correction c(t) to add to the feedforward's command at each time t of the motion. This is the
// real-time part that plays it back, with or without the tip sensor:
//   t_k = t_{k-1} + dt_k                      (t = 0 at the first cycle after reset: dt is 0 there
//                                              in a loop that starts at the trajectory's start)
//   c(t) = table interpolated linearly, sample i at t = i table_dt; past the end (by more than
//          1e-9 table_dt: the rounding of the sum) the last sample (hold_last) or 0, and the
//          status input_clamped
//   u_k = shape(target_k + c(t_k))
// A non-finite target holds the last command (held_nonfinite_input); the time still advances.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "command_shaping.hpp"
#include "encoder_loop.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of LearnedCorrection (validated by its constructor, with the table).
struct LearnedFeedforwardParams {
  double table_dt = 1e-3;  ///< time between the table's samples, s, > 0 and finite
  bool hold_last = true;   ///< past the table's end: hold its last sample (true) or add 0 (false)
  CommandLimits limits{};  ///< the command's limits (after the correction)
};

/// The parameter table of LearnedFeedforwardParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<LearnedFeedforwardParams> {
  static constexpr const char* owner = "LearnedCorrection";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("table_dt", &LearnedFeedforwardParams::table_dt, "s", positive(),
            "time between the table's samples"),
      param("hold_last", &LearnedFeedforwardParams::hold_last, "", any(),
            "past the table's end: hold its last sample (true) or add 0 (false)"),
      param("limits", &LearnedFeedforwardParams::limits, "", any(),
            "CommandLimits: the command's min, max and max_rate"));
};

/// @brief A stored correction table played back in time and added to a feedforward's command.
///
/// correct(target, dt) advances the time since reset by dt (dt not finite or <= 0: the time does
/// not advance), interpolates the table linearly there and returns target + correction, shaped to
/// the limits. The table is copied at construction (the only allocation); correct() is noexcept
/// and allocates nothing.
class LearnedCorrection {
 public:
  /// The parameter struct its constructor takes.
  using Params = LearnedFeedforwardParams;

  /// @param table the correction at t = 0, table_dt, 2 table_dt, ... (rad, the command's unit)
  /// @param p the parameters; throws std::invalid_argument naming an empty table, a non-finite
  /// entry (its index) or table_dt out of range
  LearnedCorrection(std::vector<double> table, const Params& p)
      : p_(p), table_(std::move(table)), shaper_(p.limits) {
    const char* w = "LearnedCorrection";
    require(!table_.empty(), w, "the table is empty (give at least one sample)");
    for (std::size_t i = 0; i < table_.size(); ++i)
      require(std::isfinite(table_[i]), w, "table[", i, "] is not finite (got ", table_[i], ")");
    validate_fields(p, w);  // table_dt's bound, from ParamTable<LearnedFeedforwardParams>
    p.limits.validate(w);
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The correction table.
  const std::vector<double>& table() const noexcept { return table_; }
  /// The time the table spans, (n - 1) table_dt, s (past it by more than 1e-9 table_dt: the end).
  double duration() const noexcept { return static_cast<double>(table_.size() - 1) * p_.table_dt; }

  /// Start afresh: the time back to 0, the shaper's history forgotten; the table is kept.
  void reset() noexcept {
    time_ = correction_ = 0.0;
    started_ = beyond_ = false;
    shaper_.reset();
  }

  /// @brief The table at time t (s): linear interpolation; before 0 the first sample, past the
  /// end the last one (hold_last) or 0. A t within 1e-9 samples of the end (the rounding of a sum
  /// of dt) reads the last sample.
  double at(double t) const noexcept {
    const std::size_t n = table_.size();
    if (!(t > 0.0)) return table_[0];  // also a NaN t
    const double pos = t / p_.table_dt, last = static_cast<double>(n - 1);
    if (past_end(pos)) return p_.hold_last ? table_[n - 1] : 0.0;
    if (!(pos < last)) return table_[n - 1];
    const auto i = static_cast<std::size_t>(pos);
    const double f = pos - static_cast<double>(i);
    return table_[i] + f * (table_[i + 1] - table_[i]);
  }

  /// @brief One cycle: the feedforward's target plus the table at the time since reset.
  /// @param target the feedforward's command this cycle; a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s (not finite or <= 0: the time stays)
  /// @return shape(target + c(t)), within the limits
  double correct(double target, double dt) noexcept {
    if (started_ && dt > 0.0 && std::isfinite(dt)) time_ += dt;
    started_ = true;
    beyond_ = past_end(time_ / p_.table_dt);
    correction_ = at(time_);
    return shaper_.apply(std::isfinite(target) ? target + correction_ : NAN, dt);
  }

  /// The time since reset, s (the sum of the finite, positive dt after the first cycle).
  double time() const noexcept { return time_; }
  /// The correction added in the last cycle.
  double correction() const noexcept { return correction_; }

  /// The last cycle's status: input_clamped (the time is past the table's end: its last sample
  /// or 0 was added), held_nonfinite_input (the target was not finite), saturated (the command was
  /// cut to its limits).
  Status status() const noexcept {
    const Status s = shaper_.status();
    return beyond_ ? s | Status::input_clamped : s;
  }

 private:
  // past the last sample by more than the rounding of a sum of dt (pos: t in samples)
  bool past_end(double pos) const noexcept {
    return pos > static_cast<double>(table_.size() - 1) + kEndSlack;
  }
  static constexpr double kEndSlack = 1e-9;  // samples

  Params p_;
  std::vector<double> table_;
  CommandShaper shaper_{};
  double time_ = 0.0, correction_ = 0.0;
  bool started_ = false, beyond_ = false;
};

/// @brief Any feedforward (step(y_d, dt)) with a learned correction table added to its command.
/// @tparam Feedforward BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
/// CurveAngleFeedforward, ContinuumFeedforward, ModelInverse, or any class with step(y_d, dt),
/// reset() and status()
template <class Feedforward>
class LearnedFeedforward {
 public:
  /// @param ff the feedforward
  /// @param learned the correction table added to its command
  LearnedFeedforward(Feedforward ff, LearnedCorrection learned)
      : ff_(std::move(ff)), learned_(std::move(learned)) {}

  /// Start afresh: the feedforward, and the table's time back to 0.
  void reset() noexcept {
    ff_.reset();
    learned_.reset();
  }
  /// @param y_d the desired output
  /// @param dt the time since the previous cycle, s
  /// @return the feedforward's command plus the table at the time since reset, shaped
  double step(double y_d, double dt) noexcept { return learned_.correct(ff_.step(y_d, dt), dt); }
  /// Passes a route shape to a feedforward that follows the route (ignored otherwise).
  void set_shape(const ShapeIntegrals& s) noexcept {
    if constexpr (detail::FollowsShape<Feedforward>::value) ff_.set_shape(s);
  }
  /// The feedforward's and the table's flags of the last step.
  Status status() const noexcept { return ff_.status() | learned_.status(); }
  /// The feedforward inside.
  Feedforward& feedforward() noexcept { return ff_; }
  /// The correction table's player.
  const LearnedCorrection& learned() const noexcept { return learned_; }

 private:
  Feedforward ff_;
  LearnedCorrection learned_;
};

}  // namespace tendonsheath
