// Closed-form statics of a bidirectional pull-pull tendon-sheath pair in full
// slip (spec A.2, A.4: equations A5-A7), for any distribution of curvature.
//
// Tendon 1 is pulled (forward) or released (backward); the output is
// x_out = x_in - Delta1, with Delta1 the elongation of tendon 1 relative to
// the pretensioned state:
//   forward:  T1p = (2 T0 + F_L G e^{-a}) / (g + G e^{-2a}),  Delta1 = (L/EA)(T1p g - T0)
//   backward: T1p = (2 T0 + F_L g e^{a})  / (G + g e^{2a}),   Delta1 = (L/EA)(T1p G - T0)
// with a = mu Theta, g = (1/L) int e^{-mu theta(s)} ds and G = (1/L) int e^{+mu theta(s)} ds.
// Uniform curvature reduces this to (A7): Delta1 = (L/EA) tanh(a/2) [T0 sigma + F_L / a].
#pragma once

#include <cmath>
#include <limits>
#include <cstddef>

namespace tendonsheath {

/// The closed forms' removable singularities at a = mu Theta = 0 ((e^x - 1)/x, tanh(a/2)/a,
/// a/sinh a) switch to their Taylor series below one threshold, kSeriesSwitch. Why 1e-4:
/// the direct forms go through std::expm1, std::tanh and std::sinh, which carry no
/// cancellation (a few ulp for any x != 0), so the series is needed only near 0/0; each series
/// below keeps the terms whose truncation error at 1e-4 is under 1e-18 relative, far below
/// double rounding (1.1e-16), so both branches agree at the switch to rounding. A larger
/// switch would need more terms (at 1e-3 the a^2 series of tanh(a/2)/a is off by 8e-15).
constexpr double kSeriesSwitch = 1e-4;

/// (exp(x) - 1) / x; truncation x^4/120 <= 8e-19.
inline double expm1_over(double x) noexcept {
  if (std::fabs(x) < kSeriesSwitch) return 1.0 + x * (0.5 + x * (1.0 / 6.0 + x / 24.0));
  return std::expm1(x) / x;
}

/// tanh(a/2) / a; truncation a^4/240 (relative a^4/120 <= 8e-19).
inline double tanh_half_over(double a) noexcept {
  if (std::fabs(a) < kSeriesSwitch) return 0.5 - a * a / 24.0;
  return std::tanh(0.5 * a) / a;
}

/// a / sinh(a); truncation 7 a^4/360 <= 2e-18.
inline double a_over_sinh(double a) noexcept {
  if (std::fabs(a) < kSeriesSwitch) return 1.0 - a * a / 6.0;
  return a / std::sinh(a);
}

/// @brief The uniform-curvature closed forms (spec A.4, A.7) at the tendon level (m, N), a = mu Theta;
/// the Python functions of tendonsheath.physics and the CurveAngleModel call these.
namespace uniform {
/// e_b = (T0 L / EA) tanh(a/2): half the dead zone of a pull-pull pair.
inline double backlash_half_width(double length, double stiffness, double pretension,
                                  double a) noexcept {
  return pretension * length / stiffness * std::tanh(0.5 * a);
}
/// C_L = (L / EA) tanh(a/2) / a: the output shift per newton of distal load (m/N).
inline double load_compliance(double length, double stiffness, double a) noexcept {
  return length / stiffness * tanh_half_over(a);
}
/// e_L = (F_L L / EA) tanh(a/2) / a: the load offset of both branches.
inline double load_offset(double length, double stiffness, double load, double a) noexcept {
  return load * length / stiffness * tanh_half_over(a);
}
/// c = 1 / (1 + k_e C_L): the branch slope with a spring load F_L = k_e x_out.
inline double spring_slope(double length, double stiffness, double spring, double a) noexcept {
  return 1.0 / (1.0 + spring * length / stiffness * tanh_half_over(a));
}
/// The largest distal load before the released tendon goes slack: T0 (a / sinh a)(1 + e^-a).
inline double no_slack_limit(double pretension, double a) noexcept {
  return pretension * a_over_sinh(a) * (1.0 + std::exp(-a));
}
}  // namespace uniform

/// The shape of a route as the closed forms need it: the friction-weighted integrals g, G and the
/// total curve angle (see shape_integrals() and uniform_shape()).
struct ShapeIntegrals {
  double g = 1.0;            ///< (1/L) int e^{-mu theta} ds
  double G = 1.0;            ///< (1/L) int e^{+mu theta} ds
  double curve_angle = 0.0;  ///< Theta, the route's curve angle
};

/// The largest friction angle mu Theta the closed forms accept: the capstan ratio e^{-50}
/// (2e-22) already transmits nothing, and e^{mu Theta} must stay far from overflow.
constexpr double kMaxFrictionAngle = 50.0;

/// Uniform curvature: g = (1 - e^{-a})/a, G = (e^a - 1)/a. (G through e^{-a} divided by
/// zero once e^{-a} - 1 rounded to -1, at a of about 37.4.)
inline ShapeIntegrals uniform_shape(double mu, double curve_angle) noexcept {
  const double a = mu * curve_angle;
  return {expm1_over(-a), expm1_over(a), curve_angle};
}

/// The pull-pull dead zone's half-width per unit T0 L / EA for a route of shape integrals g, G
/// (computed with friction mu) and friction angle a = mu Theta (spec A5/A6 with F_L = 0):
///   F(g, G, a) = g / (g + G e^{-2a}) - G / (G + g e^{2a}) = (g - G e^{-2a}) / (g + G e^{-2a}),
/// the second form computed (no e^{2a} overflow). Uniform curvature gives tanh(a/2) exactly
/// (up to rounding); an AngleDependent model's "tanh" law uses it when the route is known.
/// @param g (1/L) int e^{-mu theta} ds, > 0
/// @param G (1/L) int e^{+mu theta} ds, > 0
/// @param a the friction angle mu Theta
/// @return the factor, in [0, 1) for a >= 0
inline double shape_dead_zone_factor(double g, double G, double a) noexcept {
  const double Ge = G * std::exp(-2.0 * a);
  return (g - Ge) / (g + Ge);
}

/// The largest curve angle (rad) a friction mu admits: kMaxFrictionAngle / mu (inf for mu = 0).
inline double max_curve_angle(double mu) noexcept {
  return mu > 0.0 ? kMaxFrictionAngle / mu : std::numeric_limits<double>::infinity();
}

/// max_curve_angle() by its old name (docs/vocabulary.md).
[[deprecated("use max_curve_angle()")]] inline double max_total_angle(double mu) noexcept {
  return max_curve_angle(mu);
}

/// Exact for a piecewise-linear theta(s) given at samples (s_i, theta_i), s
/// non-decreasing from 0 to L (repeated s = a jump of theta, which adds no length).
inline ShapeIntegrals shape_integrals(const double* s, const double* theta, std::size_t n,
                                      double mu) noexcept {
  if (n < 2 || !(s[n - 1] > 0.0)) return uniform_shape(mu, n ? theta[n - 1] : 0.0);
  double g = 0.0, G = 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double ds = s[i] - s[i - 1];
    if (!(ds > 0.0)) continue;
    const double d = mu * (theta[i] - theta[i - 1]);
    g += ds * std::exp(-mu * theta[i - 1]) * expm1_over(-d);
    G += ds * std::exp(mu * theta[i - 1]) * expm1_over(d);
  }
  const double L = s[n - 1];
  return {g / L, G / L, theta[n - 1]};
}

/// @brief Closed-form statics of a bidirectional pull-pull tendon-sheath pair in full slip
/// (spec A.2, A.4: equations A5-A7), for any distribution of curvature.
///
/// Tendon 1 is pulled (forward) or released (backward); the output is x_out = x_in - Delta1. Forward:
/// T1p = (2 T0 + F_L G e^{-a}) / (g + G e^{-2a}), Delta1 = (L/EA)(T1p g - T0); backward:
/// T1p = (2 T0 + F_L g e^{a}) / (G + g e^{2a}), Delta1 = (L/EA)(T1p G - T0), with a = mu Theta.
/// Uniform curvature reduces this to (A7): Delta1 = (L/EA) tanh(a/2) [T0 sigma + F_L / a]. All
/// members are noexcept and allocate nothing.
struct PullPullStatics {
  double friction = 0.1;     ///< mu
  double compliance = 5e-5;  ///< L / EA, m/N
  double pretension = 10.0;  ///< T0, N

  /// Elongation Delta1 of the pulled tendon in forward full slip under load F_L.
  /// @param sh the route's shape
  /// @param load F_L, the distal load at the tendon level, N
  /// @return Delta1, m
  double forward_elongation(const ShapeIntegrals& sh, double load) const noexcept {
    return forward_elongation(sh, sh, 1.0, load);
  }
  /// Elongation Delta1 of tendon 1 in backward full slip under load F_L.
  /// @param sh the route's shape
  /// @param load F_L, the distal load at the tendon level, N
  /// @return Delta1, m
  double backward_elongation(const ShapeIntegrals& sh, double load) const noexcept {
    return backward_elongation(sh, sh, 1.0, load);
  }
  /// Two sheaths of different shape and length (A5, A6): sh1 and sh2 are the shapes of
  /// tendon 1's and tendon 2's sheaths, length_ratio = L2 / L1 and compliance = L1 / EA.
  /// Tension balance L1 g1 T1p + L2 G2 T2p = T0 (L1 + L2) and load e^{-a1} T1p - e^{a2} T2p =
  /// F_L, solved for T1p (r = 1 gives the single-shape forms bit for bit).
  double forward_elongation(const ShapeIntegrals& sh1, const ShapeIntegrals& sh2,
                            double length_ratio, double load) const noexcept {
    const double r = length_ratio;
    const double ema1 = std::exp(-friction * sh1.curve_angle);
    const double ema2 = std::exp(-friction * sh2.curve_angle);
    const double t1p = (pretension * (1.0 + r) + load * r * sh2.G * ema2) /
                       (sh1.g + r * sh2.G * ema1 * ema2);
    return compliance * (t1p * sh1.g - pretension);
  }
  /// Backward: tendon 1 released (e^{+a1}), tendon 2 pulled (e^{-a2}).
  double backward_elongation(const ShapeIntegrals& sh1, const ShapeIntegrals& sh2,
                             double length_ratio, double load) const noexcept {
    const double r = length_ratio;
    const double ea1 = std::exp(friction * sh1.curve_angle);
    const double ea2 = std::exp(friction * sh2.curve_angle);
    const double t1p = (pretension * (1.0 + r) + load * r * sh2.g * ea2) /
                       (sh1.G + r * sh2.g * ea1 * ea2);
    return compliance * (t1p * sh1.G - pretension);
  }
  /// Both elongations are affine in the load: Delta = offset + slope * F_L.
  struct Affine {
    /// @{
    /// forward: Delta1 = forward_offset + forward_slope F_L; backward: Delta1 = backward_offset + backward_slope F_L (m, and m/N)
    double forward_offset, forward_slope, backward_offset, backward_slope;
    /// @}
  };
  /// The forward and backward elongations for route shape sh as affine functions of the load.
  Affine affine(const ShapeIntegrals& sh) const noexcept {
    const double ema = std::exp(-friction * sh.curve_angle), ea = 1.0 / ema;
    const double df = sh.g + sh.G * ema * ema, db = sh.G + sh.g * ea * ea;
    return {compliance * (2.0 * pretension * sh.g / df - pretension),
            compliance * sh.G * ema * sh.g / df,
            compliance * (2.0 * pretension * sh.G / db - pretension),
            compliance * sh.g * ea * sh.G / db};
  }

  /// Half-width of the dead zone: (forward - backward)/2 at the same load.
  /// @param sh the route's shape
  /// @param load F_L, N
  /// @return the half-width, m (at the tendon level)
  double backlash_half_width(const ShapeIntegrals& sh, double load = 0.0) const noexcept {
    return 0.5 * (forward_elongation(sh, load) - backward_elongation(sh, load));
  }
};

}  // namespace tendonsheath
