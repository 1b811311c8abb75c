// A real-time inverse of any copyable forward model by root finding, one control cycle at a
// time: find the command x with forward(state, x, dt) == y_d, the root NEAREST the previous
// command, inside the input range.
//
// Each cycle: a "peek" copy-assigns the model into a scratch member built once (vectors of equal
// size keep their storage: no allocation) and steps the scratch; a bracket is expanded from the
// previous command in both directions with geometric steps (alternating sides, so the nearest
// sign change is found first), clipped to the input range; Brent's method narrows it; the real
// model is then stepped with the root (the commit). At most max_evaluations peeks per cycle.
//
// No root inside a bounded range (every probe on one side of the target up to both edges): the
// command is the probe closest to the target, the cycle is flagged out_of_range. No root within
// the evaluation budget otherwise: the closest probe, flagged not_converged.
#pragma once

#include <cmath>
#include <limits>

#include "../status.hpp"
#include "../validate.hpp"
#include "input_range.hpp"

namespace tendonsheath {

/// Settings of RootInverse's search (validated by its constructor).
struct RootSearchSettings {
  double initial_step = 1e-4;  ///< the first bracket step, input units, > 0
  double tolerance = 1e-13;    ///< relative tolerance on the command (bracket width), > 0
  int max_evaluations = 160;   ///< model evaluations per cycle at most (bounds the work), >= 8

  /// Throws std::invalid_argument (message starting with `where`) naming a bad setting.
  void validate(const char* where) const {
    require_positive(initial_step, where, "initial_step");
    require_positive(tolerance, where, "tolerance");
    require(max_evaluations >= 8, where, "max_evaluations must be >= 8 (got ", max_evaluations,
            ")");
  }
};

namespace detail {
// a command tried by the root search and its residual forward(x) - y_d
struct RootProbe {
  double x, f;
};
}  // namespace detail

/// @brief The inverse of a forward model by root finding: each cycle the command x nearest the
/// previous one with model.step(x, dt) == y_d, inside the input range.
///
/// Forward must be copy-assignable without allocation once built (the core's models are), with
/// `double step(double x, double dt) noexcept`, `void reset() noexcept` and `Status status() const
/// noexcept`. step() does at most settings.max_evaluations + 1 model steps.
/// @tparam Forward the forward model (e.g. ForwardModel)
template <class Forward>
class RootInverse {
 public:
  /// @param model the forward model (copied twice: the committed model and the scratch)
  /// @param range the commands allowed (validated)
  /// @param settings the search settings (validated)
  /// Throws std::invalid_argument naming a bad range or setting.
  RootInverse(const Forward& model, const InputRange& range, const RootSearchSettings& settings)
      : model_(model), scratch_(model), range_(range), s_(settings) {
    range.validate("RootInverse");
    settings.validate("RootInverse");
  }

  /// Start afresh: the model from its initial state, no previous command.
  void reset() noexcept {
    model_.reset();
    primed_ = false;
    status_ = Status::ok;
  }

  /// @param y_d the desired output; a non-finite one holds the last command (model untouched)
  /// @param dt the time since the previous cycle, s (passed to the model)
  /// @return the command, inside the range
  double step(double y_d, double dt) noexcept {
    if (!std::isfinite(y_d)) {
      status_ = Status::held_nonfinite_input;
      return primed_ ? x_ : start();
    }
    const double x = solve(y_d, dt);
    y_ = model_.step(x, dt);
    status_ = status_ | model_.status();
    x_ = x;
    primed_ = true;
    return x;
  }

  /// The last step's status: out_of_range, not_converged (see the file's comment), held
  /// (non-finite y_d) and the model's own flags at the committed command.
  Status status() const noexcept { return status_; }
  /// The model's output at the last committed command.
  double output() const noexcept { return y_; }
  /// The committed model (e.g.\ to update its parameters; the scratch copies it every peek).
  Forward& model() noexcept { return model_; }
  /// The committed model.
  const Forward& model() const noexcept { return model_; }
  /// The input range.
  const InputRange& range() const noexcept { return range_; }
  /// Model evaluations of the last step's search.
  int evaluations() const noexcept { return evals_; }

 private:
  using Probe = detail::RootProbe;

  double start() const noexcept { return range_.clamp(0.0); }

  // forward(state, x, dt) - target from the committed state
  double peek(double x, double dt) noexcept {
    scratch_ = model_;
    ++evals_;
    const double f = scratch_.step(x, dt) - target_;
    return std::isnan(f) ? std::numeric_limits<double>::infinity() : f;
  }

  void keep_best(const Probe& p) noexcept {
    if (std::fabs(p.f) < std::fabs(best_.f)) best_ = p;
  }

  static bool straddle(double fa, double fb) noexcept { return (fa < 0.0) != (fb < 0.0); }

  double solve(double y_d, double dt) noexcept {
    target_ = y_d;
    evals_ = 0;
    status_ = Status::ok;
    const double x0 = primed_ ? x_ : start();
    best_ = {x0, peek(x0, dt)};
    if (best_.f == 0.0) return x0;
    Probe lo{}, hi{};
    if (bracket(x0, dt, lo, hi)) return refine(lo, hi, dt);
    return best_.x;
  }

  // expand from x0 both ways; true with [lo, hi] straddling the target (or best_.f == 0)
  bool bracket(double x0, double dt, Probe& lo, Probe& hi) noexcept {
    Probe right = best_, left = best_;
    bool r_open = x0 < range_.hi, l_open = x0 > range_.lo;
    double h = s_.initial_step;
    const int budget = s_.max_evaluations - 2;
    while ((r_open || l_open) && evals_ < budget) {
      if (r_open && expand(right, x0 + h, range_.hi, r_open, dt, lo, hi, true)) return true;
      if (l_open && expand(left, x0 - h, range_.lo, l_open, dt, lo, hi, false)) return true;
      h *= 2.0;
    }
    status_ = (!r_open && !l_open && range_.bounded()) ? Status::out_of_range
                                                      : Status::not_converged;
    return false;
  }

  // one probe on one side: to x (clipped to the edge); true when it closes a bracket
  bool expand(Probe& side, double x, double edge, bool& open, double dt, Probe& lo, Probe& hi,
              bool rising) noexcept {
    if (rising ? !(x < edge) : !(x > edge)) {
      x = edge;
      open = false;
    }
    if (!std::isfinite(x)) {  // an unbounded side overflowed: stop it
      open = false;
      return false;
    }
    const Probe p{x, peek(x, dt)};
    keep_best(p);
    if (p.f == 0.0 || straddle(side.f, p.f)) {
      lo = rising ? side : p;
      hi = rising ? p : side;
      return true;
    }
    side = p;
    return false;
  }

  // Brent's method on [a, b] (f(a), f(b) of opposite signs, or one of them 0)
  double refine(Probe a, Probe b, double dt) noexcept {
    if (a.f == 0.0) return a.x;
    if (b.f == 0.0) return b.x;
    Probe c = a;
    double d = b.x - a.x, e = d;
    while (evals_ < s_.max_evaluations) {
      if (straddle(b.f, c.f) == false) {
        c = a;
        d = e = b.x - a.x;
      }
      if (std::fabs(c.f) < std::fabs(b.f)) {
        a = b;
        b = c;
        c = a;
      }
      const double tol = 2.0 * std::numeric_limits<double>::epsilon() * std::fabs(b.x) +
                         0.5 * s_.tolerance * (std::fabs(b.x) > 1.0 ? std::fabs(b.x) : 1.0);
      const double m = 0.5 * (c.x - b.x);
      if (std::fabs(m) <= tol || b.f == 0.0) return b.x;
      if (std::fabs(e) >= tol && std::fabs(a.f) > std::fabs(b.f)) {
        interpolate(a, b, c, m, tol, d, e);
      } else {
        d = e = m;
      }
      a = b;
      b.x += std::fabs(d) > tol ? d : (m > 0.0 ? tol : -tol);
      b.f = peek(b.x, dt);
      keep_best(b);
    }
    status_ = Status::not_converged;
    return std::fabs(b.f) <= std::fabs(c.f) ? b.x : c.x;
  }

  // Brent's inverse quadratic / secant step, accepted when it stays well inside the bracket
  static void interpolate(const Probe& a, const Probe& b, const Probe& c, double m, double tol,
                          double& d, double& e) noexcept {
    const double s = b.f / a.f;
    double p, q;
    if (a.x == c.x) {
      p = 2.0 * m * s;
      q = 1.0 - s;
    } else {
      const double qa = a.f / c.f, r = b.f / c.f;
      p = s * (2.0 * m * qa * (qa - r) - (b.x - a.x) * (r - 1.0));
      q = (qa - 1.0) * (r - 1.0) * (s - 1.0);
    }
    if (p > 0.0) q = -q;
    else p = -p;
    const double bound1 = 3.0 * m * q - std::fabs(tol * q), bound2 = std::fabs(e * q);
    if (2.0 * p < (bound1 < bound2 ? bound1 : bound2)) {
      e = d;
      d = p / q;
    } else {
      d = e = m;
    }
  }

  Forward model_;
  Forward scratch_;
  InputRange range_;
  RootSearchSettings s_;
  Probe best_{0.0, 0.0};
  double target_ = 0.0;
  double x_ = 0.0, y_ = 0.0;
  int evals_ = 0;
  bool primed_ = false;
  Status status_ = Status::ok;
};

}  // namespace tendonsheath
