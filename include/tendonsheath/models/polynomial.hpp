// Static output map y = sum_k a_k u^k (k = 0..degree, or odd powers only):
// composed after a hysteresis model it bends straight branches into the
// asymmetric, saturating loops that real tendon drives show.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of Polynomial (validated by its constructor).
struct PolynomialParams {
  std::vector<double> coefficients{0.0, 1.0};  ///< a_0, a_1, ... (all powers) or a_1, a_3, ... (odd)
  bool odd = false;  ///< true: the coefficients are those of the odd powers a_1, a_3, ...
};

/// The parameter table of PolynomialParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<PolynomialParams> {
  static constexpr const char* owner = "Polynomial";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = false;  ///< its constructor checks every bound by hand (an order of checks or a message of its own)
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("coefficients", &PolynomialParams::coefficients, "", any(),
            "a_0, a_1, ... (all powers) or a_1, a_3, ... (odd), finite, not empty"),
      option("odd", &PolynomialParams::odd, "", any(),
            "true: the coefficients are those of the odd powers a_1, a_3, ..."));
};

/// @brief Static output map y = sum_k a_k u^k (k = 0..degree, or odd powers only).
///
/// Composed after a hysteresis model (Chain) it bends straight branches into the asymmetric,
/// saturating loops that real tendon drives show. Memoryless; step() ignores dt.
class Polynomial {
 public:
  /// The parameter struct its constructor takes.
  using Params = PolynomialParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the coefficients (at least one, all finite); throws std::invalid_argument otherwise.
  explicit Polynomial(const Params& p) : p_(p) {
    const char* w = "Polynomial";
    require(!p.coefficients.empty(), w, "coefficients must not be empty");
    for (std::size_t i = 0; i < p.coefficients.size(); ++i) {
      const std::string name = "coefficients[" + std::to_string(i) + "]";
      require_finite(p.coefficients[i], w, name.c_str());
    }
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The degree of the polynomial (2 n - 1 for n odd-power coefficients).
  std::size_t degree() const noexcept {
    const std::size_t n = p_.coefficients.size();
    return p_.odd ? 2 * n - 1 : n - 1;
  }

  /// The map at u (Horner), without touching output() or status().
  double evaluate(double u) const noexcept {
    const auto& a = p_.coefficients;
    double acc = 0.0;
    if (p_.odd) {  // u * (a_1 + a_3 u^2 + a_5 u^4 + ...), Horner in u^2
      const double u2 = u * u;
      for (std::size_t i = a.size(); i-- > 0;) acc = acc * u2 + a[i];
      return acc * u;
    }
    for (std::size_t i = a.size(); i-- > 0;) acc = acc * u + a[i];
    return acc;
  }

  /// Nothing to reset: the map has no state (output() keeps the last value).
  void reset() noexcept {}
  /// @param u the input; a non-finite u is ignored and the last output held
  /// @return y = sum_k a_k u^k
  double step(double u, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(u);
    if (!held_) y_ = evaluate(u);
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

/// A hysteresis model followed by a static map: y = Second(First(x)).
/// @tparam First a model of the core (step(x, dt), output(), status(), reset())
/// @tparam Second a static map such as Polynomial
template <class First, class Second>
class Chain {
 public:
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = First::rate_independent && Second::rate_independent;
  /// @param first the hysteresis model (copied)
  /// @param second the static map applied to its output (copied)
  Chain(const First& first, const Second& second) : first_(first), second_(second) {}
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    first_.reset();
    second_.reset();
  }
  /// @return second.step(first.step(x, dt), dt)
  double step(double x, double dt) noexcept { return second_.step(first_.step(x, dt), dt); }
  /// The output of the last step().
  double output() const noexcept { return second_.output(); }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return first_.status() | second_.status(); }
  /// The hysteresis model.
  const First& first() const noexcept { return first_; }
  /// The static map.
  const Second& second() const noexcept { return second_; }

 private:
  First first_;
  Second second_;
};

}  // namespace tendonsheath
