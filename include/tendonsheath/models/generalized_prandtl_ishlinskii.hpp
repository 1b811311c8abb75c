// Generalized Prandtl-Ishlinskii model (Al Janaideh, Rakheja & Su): play
// operators whose rising and falling boundaries follow saturating envelope
// functions instead of straight lines, for asymmetric and saturated loops.
//
//   gamma_r(x) = a_r tanh(b_r (x - c_r)) + d_r        (rising envelope)
//   gamma_l(x) = a_l tanh(b_l (x - c_l)) + d_l        (falling envelope)
//   z_i <- max(gamma_r(x) - r_i, min(gamma_l(x) + r_i, z_i)),   y = sum_i p_i z_i
//   z_0  = (gamma_r(x) + gamma_l(x)) / 2   (threshold 0: the centre line)
//
// with 0 = r_0 < r_1 < ..., p_0 > 0 and p_i >= 0, so that y grows with x along
// any monotone input and the inverse exists inside the envelopes' range.
// Beyond an envelope's input range [lo, hi] (set by identification to the
// training inputs' range) it continues along its tangent line instead of
// saturating: past the data, the model extrapolates the slope it saw last.
// The inverse solves that monotone equation each step by safeguarded
// bisection on a bracket (at most 200 iterations, bounded work).
#pragma once

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// A saturating envelope gamma(x) = a tanh(b (x - c)) + d of the generalized play operators.
///
/// Inside [lo, hi] (the input range it was identified on; unbounded by default) it is the tanh;
/// beyond it, the tangent line at lo or hi: continuous, with a continuous slope, and still
/// increasing. The tanh alone would flatten out past the data and predict a saturation that the
/// data never showed.
struct Envelope {
  double a = 1.0;  ///< amplitude (> 0): the envelope saturates at d +- a
  double b = 1.0;  ///< input gain (> 0): initial slope a*b
  double c = 0.0;  ///< input shift
  double d = 0.0;  ///< output shift
  double lo = -std::numeric_limits<double>::infinity();  ///< the tanh's input range: lower end
  double hi = std::numeric_limits<double>::infinity();  ///< the tanh's input range: upper end
  /// The tanh a tanh(b (x - c)) + d, whatever the range.
  double tanh_at(double x) const noexcept { return a * std::tanh(b * (x - c)) + d; }
  /// The tanh's slope a b / cosh^2(b (x - c)) (0 once cosh overflows).
  double slope_at(double x) const noexcept {
    const double ch = std::cosh(b * (x - c));
    return a * b / (ch * ch);
  }
  /// The envelope at x: the tanh inside [lo, hi], its tangent line beyond.
  double operator()(double x) const noexcept {
    if (x > hi) return past(hi, x);
    if (x < lo) return past(lo, x);
    return tanh_at(x);
  }
  /// Inverse: along the tangent lines beyond [lo, hi]; inside, the tanh's, clipped to its open
  /// range (d - a, d + a).
  double inverse(double g) const noexcept {
    if (std::isfinite(hi) && g > tanh_at(hi) && slope_at(hi) > 0.0)
      return hi + (g - tanh_at(hi)) / slope_at(hi);
    if (std::isfinite(lo) && g < tanh_at(lo) && slope_at(lo) > 0.0)
      return lo + (g - tanh_at(lo)) / slope_at(lo);
    double u = (g - d) / a;
    const double lim = 1.0 - 1e-15;
    u = u > lim ? lim : (u < -lim ? -lim : u);
    double x = c + std::atanh(u) / b;
    x = x > hi ? hi : x;  // a flat tangent (slope 0 in double): the range's end
    return x < lo ? lo : x;
  }

 private:
  double past(double end, double x) const noexcept {
    const double s = slope_at(end);
    return s > 0.0 ? tanh_at(end) + s * (x - end) : tanh_at(end);
  }
};

/// Parameters of GeneralizedPrandtlIshlinskii and its inverse (validated by their constructors).
struct GeneralizedPrandtlIshlinskiiParams {
  Envelope rising{};  ///< the rising (loading) envelope gamma_r
  Envelope falling{};  ///< the falling (unloading) envelope gamma_l
  std::vector<double> thresholds{0.0, 0.05, 0.1, 0.2};  ///< play thresholds, 0 = r_0 < r_1 < ..., input units
  std::vector<double> weights{0.6, 0.2, 0.1, 0.1};  ///< play weights, p_0 > 0 and p_i >= 0
};

/// The parameter table of GeneralizedPrandtlIshlinskiiParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<GeneralizedPrandtlIshlinskiiParams> {
  static constexpr const char* owner = "GeneralizedPrandtlIshlinskii";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = false;  ///< its constructor checks every bound by hand (an order of checks or a message of its own)
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("rising", &GeneralizedPrandtlIshlinskiiParams::rising, "", any(),
            "the rising (loading) envelope gamma_r: a tanh(b (x - c)) + d on [lo, hi]"),
      param("falling", &GeneralizedPrandtlIshlinskiiParams::falling, "", any(),
            "the falling (unloading) envelope gamma_l: a tanh(b (x - c)) + d on [lo, hi]"),
      param("thresholds", &GeneralizedPrandtlIshlinskiiParams::thresholds, "input", any(),
            "play thresholds, 0 = r_0 < r_1 < ..."),
      param("weights", &GeneralizedPrandtlIshlinskiiParams::weights, "", any(),
            "play weights, p_0 > 0 and p_i >= 0"));
};

/// Bounds on an envelope's input gain and shift: its input range c +- kEnvelopeSpan / b (past
/// which tanh is 1 to double precision) must stay a representable, finite interval.
constexpr double kEnvelopeSpan = 20.0;
/// The smallest envelope input gain b accepted.
constexpr double kMinEnvelopeGain = 1e-9;
/// The largest envelope input shift |c| accepted.
constexpr double kMaxEnvelopeShift = 1e12;

namespace detail {
inline void validate_gpi(const GeneralizedPrandtlIshlinskiiParams& p, const char* w) {
  const Envelope* env[2] = {&p.rising, &p.falling};
  const char* names[2] = {"rising", "falling"};
  for (int e = 0; e < 2; ++e) {  // each coefficient by its Python (and file) name: rising_a, ...
    const std::string n = names[e];
    require_positive(env[e]->a, w, (n + "_a").c_str());
    require_positive(env[e]->b, w, (n + "_b").c_str());
    require(env[e]->b >= kMinEnvelopeGain, w, n, "_b must be >= ", kMinEnvelopeGain,
            " (the envelope spans 20/b of input; got ", env[e]->b, ")");
    require_finite(env[e]->c, w, (n + "_c").c_str());
    require(std::fabs(env[e]->c) <= kMaxEnvelopeShift, w, n, "_c must be within +-",
            kMaxEnvelopeShift, " (got ", env[e]->c, ")");
    require_finite(env[e]->d, w, (n + "_d").c_str());
    require(env[e]->lo < env[e]->hi, w, n, ".lo must be < ", n, ".hi (the tanh's input range; got [",
            env[e]->lo, ", ", env[e]->hi, "])");
  }
  require(!p.thresholds.empty(), w, "thresholds must not be empty");
  require(p.thresholds.size() == p.weights.size(), w,
          "thresholds and weights must have the same length");
  if (detail::failed()) return;  // without exceptions, in make(): the vectors are not indexed
  require(p.thresholds[0] == 0.0, w, "thresholds[0] must be 0");
  require_positive(p.weights[0], w, "weights[0]");
  for (std::size_t i = 1; i < p.thresholds.size(); ++i) {
    require(std::isfinite(p.thresholds[i]) && p.thresholds[i] > p.thresholds[i - 1], w,
            "thresholds must be finite and strictly increasing");
    const std::string pi = "weights[" + std::to_string(i) + "]";
    require_non_negative(p.weights[i], w, pi.c_str());
  }
}

// The threshold-0 play is the centre line (gamma_r + gamma_l)/2, a strictly
// increasing static map: it keeps the whole operator invertible.
inline double gpi_play(double z, double x, double r, const Envelope& up, const Envelope& down) noexcept {
  if (r == 0.0) return 0.5 * (up(x) + down(x));
  const double hi = down(x) + r;
  const double lo = up(x) - r;
  const double zz = z > hi ? hi : z;
  return zz < lo ? lo : zz;
}
}  // namespace detail

/// @brief Generalized Prandtl-Ishlinskii model (Al Janaideh, Rakheja & Su): plays whose rising and
/// falling boundaries follow saturating envelopes, for asymmetric and saturated loops.
///
/// z_i <- max(gamma_r(x) - r_i, min(gamma_l(x) + r_i, z_i)), y = sum_i p_i z_i, with the play of
/// threshold 0 on the centre line (gamma_r + gamma_l) / 2. The play states are allocated once, in
/// the constructor; step() does O(number of plays) work. Rate-independent.
class GeneralizedPrandtlIshlinskii {
 public:
  /// The parameter struct its constructor takes.
  using Params = GeneralizedPrandtlIshlinskiiParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the envelopes, thresholds and weights; throws std::invalid_argument naming the first
  /// bad one.
  explicit GeneralizedPrandtlIshlinskii(const Params& p) : p_(p), z_(p.thresholds.size(), 0.0) {
    detail::validate_gpi(p, "GeneralizedPrandtlIshlinskii");
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { initialised_ = false; }

  /// @param x the input; a non-finite x holds the last output (0 before the first step)
  /// @return the output y; the first step after reset() starts every play on the centre line
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    if (held_) return initialised_ ? y_ : 0.0;
    if (!initialised_) {  // every play starts on the centre line (clamped into its band)
      for (std::size_t i = 0; i < z_.size(); ++i) z_[i] = centre(x);
      initialised_ = true;
    }
    y_ = advance(x, z_.data());
    x_ = x;
    return y_;
  }

  /// Output if the input moved to x from the current state (the state is kept).
  double output_if(double x) const noexcept {
    double y = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i)
      y += p_.weights[i] * detail::gpi_play(z_[i], x, p_.thresholds[i], p_.rising, p_.falling);
    return y;
  }

  /// Output of the first sample when it is x: increasing in x.
  double initial_output(double x) const noexcept {
    double y = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i)
      y += p_.weights[i] * detail::gpi_play(centre(x), x, p_.thresholds[i], p_.rising, p_.falling);
    return y;
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input when its input was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }
  /// The input of the last step().
  double last_input() const noexcept { return x_; }
  /// False until the first finite step() after construction or reset().
  bool initialised() const noexcept { return initialised_; }
  /// The play outputs z_i after the last step (y = sum_i weights[i] z_i).
  const std::vector<double>& play_states() const noexcept { return z_; }

 protected:
  /// Move the plays z (one per threshold) to input x; returns y = sum_i p_i z_i.
  double advance(double x, double* z) noexcept {
    double y = 0.0;
    for (std::size_t i = 0; i < z_.size(); ++i) {
      z[i] = detail::gpi_play(z[i], x, p_.thresholds[i], p_.rising, p_.falling);
      y += p_.weights[i] * z[i];
    }
    return y;
  }

  /// The centre line (gamma_r(x) + gamma_l(x)) / 2, where the plays start.
  double centre(double x) const noexcept { return 0.5 * (p_.rising(x) + p_.falling(x)); }

  Params p_;              ///< the parameters
  std::vector<double> z_;  ///< the play states, one per threshold
  /// the last input (x_); the last output (y_)
  double x_ = 0.0, y_ = 0.0;  ///< the last output
  bool initialised_ = false;  ///< false until the first finite step
  bool held_ = false;         ///< the last input was not finite
};

/// @brief The inverse of GeneralizedPrandtlIshlinskii: each step solves the monotone equation
/// y(x) = y_desired by safeguarded bisection on a bracket (at most 200 iterations: bounded work).
class GeneralizedPrandtlIshlinskiiInverse {
 public:
  /// The parameter struct its constructor takes.
  using Params = GeneralizedPrandtlIshlinskiiParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the forward model's parameters; throws std::invalid_argument naming the first bad one.
  explicit GeneralizedPrandtlIshlinskiiInverse(const Params& p) : model_(p) {
    if (detail::failed()) return;  // without exceptions, in make(): the model's check failed
    const double gain = std::fmin(p.rising.b, p.falling.b);
    x_min_ = std::fmin(p.rising.c, p.falling.c) - 2.0 * kEnvelopeSpan / gain;
    x_max_ = std::fmax(p.rising.c, p.falling.c) + 2.0 * kEnvelopeSpan / gain;
    // never narrower than the tanh's input ranges
    for (const Envelope* e : {&p.rising, &p.falling}) {
      if (std::isfinite(e->lo)) x_min_ = std::fmin(x_min_, e->lo);
      if (std::isfinite(e->hi)) x_max_ = std::fmax(x_max_, e->hi);
    }
  }
  /// The last target was out of reach: the command sits at the end of the envelopes' input
  /// range, [c_min - 40/b, c_max + 40/b], past which the output no longer changes.
  bool input_clamped() const noexcept { return clamped_; }
  /// The parameters it was built with.
  const Params& params() const noexcept { return model_.params(); }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { model_.reset(); }

  /// The input x for which the forward model reaches y_desired (clipped to the
  /// reachable range: the envelopes saturate).
  /// @param y_desired the desired output; a non-finite one holds the last command
  /// @return the command x
  double step(double y_desired, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(y_desired);
    if (held_) {
      clamped_ = false;
      return model_.initialised() ? model_.last_input() : 0.0;
    }
    if (!model_.initialised()) model_.step(initial_guess(y_desired));
    double lo = model_.last_input(), hi = lo;
    const double y_now = model_.output_if(lo);
    const double span = 1.0 / std::fmin(params().rising.b, params().falling.b);
    if (y_desired > y_now) {
      for (int k = 0; k < 60 && hi < x_max_ && model_.output_if(hi) < y_desired; ++k)
        hi = std::fmin(x_max_, hi + span * (1 << (k < 20 ? k : 20)));
    } else {
      for (int k = 0; k < 60 && lo > x_min_ && model_.output_if(lo) > y_desired; ++k)
        lo = std::fmax(x_min_, lo - span * (1 << (k < 20 ? k : 20)));
    }
    clamped_ = y_desired > y_now ? (hi >= x_max_ && model_.output_if(x_max_) < y_desired)
                                 : (lo <= x_min_ && model_.output_if(x_min_) > y_desired);
    for (int k = 0; k < 200 && hi - lo > 1e-14 * (1.0 + std::fabs(lo) + std::fabs(hi)); ++k) {
      const double mid = 0.5 * (lo + hi);
      if (model_.output_if(mid) < y_desired) lo = mid;
      else hi = mid;
    }
    double x = (std::fabs(model_.output_if(lo) - y_desired) <=
                std::fabs(model_.output_if(hi) - y_desired)) ? lo : hi;
    if (clamped_) x = y_desired > y_now ? x_max_ : x_min_;  // out of reach: the range's end
    model_.step(x);
    return x;
  }

  /// The command x of the last step().
  double output() const noexcept { return model_.last_input(); }
  /// The last step's status: held_nonfinite_input (input not finite), input_clamped (see
  /// input_clamped()).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return clamped_ ? s | Status::input_clamped : s;
  }

 private:
  // The first input x_0 solves initial_output(x_0) = y_0 (increasing in x), so the
  // inverse starts from the same play states as the forward model would.
  double initial_guess(double y) const noexcept {
    const double span = 1.0 / std::fmin(params().rising.b, params().falling.b);
    double lo = std::fmax(x_min_, -span), hi = std::fmin(x_max_, span);
    for (int k = 0; k < 60 && lo > x_min_ && model_.initial_output(lo) > y; ++k)
      lo = std::fmax(x_min_, lo - span * (1 << (k < 20 ? k : 20)));
    for (int k = 0; k < 60 && hi < x_max_ && model_.initial_output(hi) < y; ++k)
      hi = std::fmin(x_max_, hi + span * (1 << (k < 20 ? k : 20)));
    for (int k = 0; k < 200 && hi - lo > 1e-15 * (1.0 + std::fabs(lo) + std::fabs(hi)); ++k) {
      const double mid = 0.5 * (lo + hi);
      if (model_.initial_output(mid) < y) lo = mid;
      else hi = mid;
    }
    return 0.5 * (lo + hi);
  }
  GeneralizedPrandtlIshlinskii model_;
  double x_min_ = -1.0, x_max_ = 1.0;
  bool clamped_ = false;
  bool held_ = false;
};

}  // namespace tendonsheath
