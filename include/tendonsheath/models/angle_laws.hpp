// The laws of Python's models.AngleDependent: each parameter of a base model as a function of
// the route (PLAN convention 2).
//
//   "constant": p = c0
//   "linear":   p = c0 + c1 Theta
//   "tanh":     p = c0 + c1 tanh(mu |Theta| / 2)         (a curve angle only: uniform curvature)
//               p = c0 + c1 F(g, G, mu Theta)            (a route's shape integrals g, G)
//
// with F = shape_dead_zone_factor (the pull-pull dead zone per unit T0 L / EA; tanh(a/2) for a
// uniform route) and mu the model's angle_friction. Fixed-size arrays: evaluating allocates
// nothing.
#pragma once

#include <cmath>
#include <cstddef>

#include "../physics/pull_pull_statics.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// How one parameter of an AngleDependent model follows the route.
enum class AngleLaw : int {
  constant = 0,  ///< p = c0
  linear = 1,    ///< p = c0 + c1 Theta
  tanh = 2,      ///< p = c0 + c1 tanh(mu |Theta| / 2), or c0 + c1 F(g, G, mu Theta) for a shape
};

/// @brief The laws of an AngleDependent model's base parameters (in the base's parameter order).
struct AngleLaws {
  static constexpr std::size_t kMaxParams = 8;  ///< the most base parameters (HystereticOscillator)
  std::size_t count = 0;                        ///< the base's parameters, <= kMaxParams
  AngleLaw law[kMaxParams] = {};                ///< each parameter's law
  double c0[kMaxParams] = {};                   ///< each law's constant term
  double c1[kMaxParams] = {};                   ///< each law's slope (unused by constant laws)
  double angle_friction = 0.0;                  ///< mu of the tanh laws (> 0 when one is tanh)

  /// Throws std::invalid_argument (message starting with `where`) naming a bad law.
  void validate(const char* where) const {
    require(count <= kMaxParams, where, "at most ", kMaxParams, " angle laws (got ", count, ")");
    if (detail::failed()) return;  // without exceptions, in make(): no law read past the arrays
    bool any_tanh = false;
    for (std::size_t i = 0; i < count; ++i) {
      require(std::isfinite(c0[i]) && std::isfinite(c1[i]), where,
              "angle law coefficients must be finite (parameter ", i, ")");
      any_tanh = any_tanh || law[i] == AngleLaw::tanh;
    }
    if (any_tanh) require_positive(angle_friction, where, "angle_friction");
  }
  /// The parameters at curve angle theta (rad), uniform curvature; out receives count values.
  void at_angle(double theta, double* out) const noexcept {
    const double f = std::tanh(0.5 * angle_friction * std::fabs(theta));
    evaluate(theta, f, out);
  }
  /// The parameters for a route of shape s (its g, G computed with mu = angle_friction).
  void at_shape(const ShapeIntegrals& s, double* out) const noexcept {
    evaluate(s.curve_angle, shape_dead_zone_factor(s.g, s.G, angle_friction * s.curve_angle),
             out);
  }

 private:
  void evaluate(double theta, double factor, double* out) const noexcept {
    for (std::size_t i = 0; i < count; ++i) {
      switch (law[i]) {
        case AngleLaw::linear: out[i] = c0[i] + c1[i] * theta; break;
        case AngleLaw::tanh: out[i] = c0[i] + c1[i] * factor; break;
        default: out[i] = c0[i]; break;
      }
    }
  }
};

}  // namespace tendonsheath
