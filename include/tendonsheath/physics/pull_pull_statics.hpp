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

/// (exp(x) - 1) / x without cancellation near 0.
inline double expm1_over(double x) noexcept {
  return std::fabs(x) < 1e-8 ? 1.0 + 0.5 * x : std::expm1(x) / x;
}

/// The shape of a route as the closed forms need it: the friction-weighted integrals g, G and the
/// total curve angle (see shape_integrals() and uniform_shape()).
struct ShapeIntegrals {
  double g = 1.0;            ///< (1/L) int e^{-mu theta} ds
  double G = 1.0;            ///< (1/L) int e^{+mu theta} ds
  double total_angle = 0.0;  ///< Theta
};

/// The largest friction angle mu Theta the closed forms accept: the capstan ratio e^{-50}
/// (2e-22) already transmits nothing, and e^{mu Theta} must stay far from overflow.
constexpr double kMaxFrictionAngle = 50.0;

/// Uniform curvature: g = (1 - e^{-a})/a, G = (e^a - 1)/a. (G through e^{-a} divided by
/// zero once e^{-a} - 1 rounded to -1, at a of about 37.4.)
inline ShapeIntegrals uniform_shape(double mu, double total_angle) noexcept {
  const double a = mu * total_angle;
  if (std::fabs(a) < 1e-4) return {expm1_over(-a), expm1_over(a), total_angle};
  return {-std::expm1(-a) / a, std::expm1(a) / a, total_angle};
}

/// The largest total angle (rad) a friction mu admits: kMaxFrictionAngle / mu (inf for mu = 0).
inline double max_total_angle(double mu) noexcept {
  return mu > 0.0 ? kMaxFrictionAngle / mu : std::numeric_limits<double>::infinity();
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
    const double a = friction * sh.total_angle;
    const double ema = std::exp(-a);
    const double t1p = (2.0 * pretension + load * sh.G * ema) / (sh.g + sh.G * ema * ema);
    return compliance * (t1p * sh.g - pretension);
  }
  /// Elongation Delta1 of tendon 1 in backward full slip under load F_L.
  /// @param sh the route's shape
  /// @param load F_L, the distal load at the tendon level, N
  /// @return Delta1, m
  double backward_elongation(const ShapeIntegrals& sh, double load) const noexcept {
    const double a = friction * sh.total_angle;
    const double ea = std::exp(a);
    const double t1p = (2.0 * pretension + load * sh.g * ea) / (sh.G + sh.g * ea * ea);
    return compliance * (t1p * sh.G - pretension);
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
    const double ema = std::exp(-friction * sh.total_angle), ea = 1.0 / ema;
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
