// Forward sensitivities of the HystereticOscillator's displacement to its parameters
// (m, c, k, alpha, beta, gamma, delta, nu), for the simulation-error least squares of the
// identification: the tangent-linear model of the very RK4 scheme that step_dense() runs
// (same sub-steps, same input grid), so dy/dp is the exact derivative of the simulated output,
// not of the continuous equations. Where |v| or |z| has a kink (v = 0, z = 0) the one-sided
// derivative of the branch in use is taken.
//
//   state s = (y, v, z), tangent S = ds/dp (3 x 8); per RK4 stage K_i = A(s_i) S_i + B(s_i)
//   with A = df/ds, B = df/dp, and S advances with the same weights as s.
#pragma once

#include <cmath>

#include "hysteretic_oscillator.hpp"

namespace tendonsheath {

/// @brief Forward sensitivities dy/dp of the HystereticOscillator's displacement to its eight
/// parameters (m, c, k, alpha, beta, gamma, delta, nu), for the identification's least squares.
///
/// The tangent-linear model of the very RK4 scheme that step_dense() runs (same sub-steps, same
/// input grid), so dy/dp is the exact derivative of the simulated output; at a kink of |v| or |z|
/// the one-sided derivative of the branch in use is taken.
class OscillatorSensitivity {
 public:
  static constexpr int kParams = 8;  ///< m, c, k, alpha, beta, gamma, delta, nu

  /// @param p the oscillator's parameters; throws std::invalid_argument as HystereticOscillator does.
  explicit OscillatorSensitivity(const HystereticOscillatorParams& p) : osc_(p), p_(p) { reset(); }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    initialised_ = false;
    for (double& x : s_) x = 0.0;
    for (double& x : S_) x = 0.0;
  }

  /// As HystereticOscillator::step_dense(); dy[0..7] receives dy/dp at the end of the interval.
  /// @param u the Q + 1 input values of the interval
  /// @param Q the refinement of the grid, >= 1
  /// @param dt the sample interval, s
  /// @param dy receives the kParams sensitivities dy/dp
  /// @return the displacement y at the end of the interval
  double step_dense(const double* u, int Q, double dt, double* dy) noexcept {
    if (initialised_ && dt > 0.0 && std::isfinite(dt) && Q >= 1)
      detail::on_dense_grid(u, Q, osc_.substeps(dt),
                            [&](const auto& u_at, int m) { integrate(u_at, m, dt); });
    initialised_ = true;
    for (int j = 0; j < kParams; ++j) dy[j] = S_[j];
    return s_[0];
  }

 private:
  // f(s, u) into d, and K = A S + B into K (3 x 8, row-major).
  void tangent(const double* s, const double* S, double u, double* d, double* K) const noexcept {
    const double y = s[0], v = s[1], z = s[2];
    const double az = std::fabs(z), av = std::fabs(v);
    const double sz = z > 0.0 ? 1.0 : (z < 0.0 ? -1.0 : 0.0);
    const double sv = v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
    const double q = p_.nu == 1.0 ? 1.0 : (az > 0.0 ? std::pow(az, p_.nu - 1.0) : 0.0);
    const double hyst = p_.gamma * av * q * z + p_.delta * v * q * az;
    const double acc = (u - p_.c * v - p_.k * y - z) / p_.m;
    d[0] = v;
    d[1] = acc;
    d[2] = p_.alpha * v - p_.beta * hyst;
    // A = df/ds
    const double a1y = -p_.k / p_.m, a1v = -p_.c / p_.m, a1z = -1.0 / p_.m;
    const double a2v = p_.alpha - p_.beta * (p_.gamma * sv * q * z + p_.delta * q * az);
    const double a2z = -p_.beta * p_.nu * q * (p_.gamma * av + p_.delta * v * sz);
    const double lz = az > 0.0 ? std::log(az) : 0.0;
    // B = df/dp, rows 1 and 2 (row 0 is zero)
    const double b1[kParams] = {-acc / p_.m, -v / p_.m, -y / p_.m, 0, 0, 0, 0, 0};
    const double b2[kParams] = {0.0, 0.0, 0.0, v, -hyst, -p_.beta * av * q * z,
                                -p_.beta * v * q * az, -p_.beta * hyst * lz};
    for (int j = 0; j < kParams; ++j) {
      const double Sy = S[j], Sv = S[kParams + j], Sz = S[2 * kParams + j];
      K[j] = Sv;
      K[kParams + j] = a1y * Sy + a1v * Sv + a1z * Sz + b1[j];
      K[2 * kParams + j] = a2v * Sv + a2z * Sz + b2[j];
    }
  }

  template <class U>
  void integrate(const U& u_at, int m, double dt) noexcept {
    constexpr int n = 3 * kParams;
    const double h = dt / m;
    double st[3] = {s_[0], s_[1], s_[2]};
    double S[n];
    for (int j = 0; j < n; ++j) S[j] = S_[j];
    for (int i = 0; i < m; ++i) {
      const double ua = u_at(2 * i), ub = u_at(2 * i + 1), uc = u_at(2 * i + 2);
      double k[4][3], K[4][n], ts[3], TS[n];
      tangent(st, S, ua, k[0], K[0]);
      const double c[3] = {0.5 * h, 0.5 * h, h};
      const double us[3] = {ub, ub, uc};
      for (int r = 0; r < 3; ++r) {
        for (int j = 0; j < 3; ++j) ts[j] = st[j] + c[r] * k[r][j];
        for (int j = 0; j < n; ++j) TS[j] = S[j] + c[r] * K[r][j];
        tangent(ts, TS, us[r], k[r + 1], K[r + 1]);
      }
      for (int j = 0; j < 3; ++j)
        st[j] += h * (k[0][j] + 2.0 * k[1][j] + 2.0 * k[2][j] + k[3][j]) / 6.0;
      for (int j = 0; j < n; ++j)
        S[j] += h * (K[0][j] + 2.0 * K[1][j] + 2.0 * K[2][j] + K[3][j]) / 6.0;
    }
    bool ok = std::isfinite(st[0]) && std::isfinite(st[1]) && std::isfinite(st[2]);
    for (int j = 0; j < n && ok; ++j) ok = std::isfinite(S[j]);
    if (!ok) return;  // kept at the last finite state (the simulation itself reports divergence)
    for (int j = 0; j < 3; ++j) s_[j] = st[j];
    for (int j = 0; j < n; ++j) S_[j] = S[j];
  }

  HystereticOscillator osc_;  // sub-step count, and the parameters validated once
  HystereticOscillatorParams p_;
  bool initialised_ = false;
  double s_[3] = {0.0, 0.0, 0.0};
  double S_[3 * kParams] = {};
};

}  // namespace tendonsheath
