// Band-limited reconstruction of a uniformly sampled input between its samples.
//
// A Kaiser-windowed sinc of half-width L samples (2L taps):
//
//   u(t_j + tau dt) = sum_{i=-L+1..L} u_{j+i} h(tau - i) / sum_i h(tau - i),   0 <= tau <= 1,
//   h(x) = sinc(x) I0(b sqrt(1 - (x/L)^2)) / I0(b),  b = 0.6 L + 2.5,
//
// normalised so that a constant is reproduced exactly and u(t_j) = u_j. The kernel is
// tabulated at construction (kPhases points per sample, linear interpolation between
// them; exact when tau is a multiple of 1/kPhases). Measured on sums of random sines
// (scripts in tests/test_reconstruction.py): L = 16 reconstructs a signal band-limited to
// 0.3 of the sampling rate to ~2e-7 of its range, one band-limited to 0.2 to ~1e-7.
//
// Used in real time (HystereticOscillator::step) the interpolation between samples j and
// j + 1 needs the samples up to j + L: the output lags the input by L - 1 samples (the
// look-ahead delay). Before the first sample and after the last one the input is held
// (constant extension).
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "../validate.hpp"

namespace tendonsheath {

namespace detail {
// Modified Bessel function of the first kind, order 0 (power series; converges for all x).
inline double bessel_i0(double x) noexcept {
  const double q = 0.25 * x * x;
  double term = 1.0, sum = 1.0;
  for (int k = 1; k < 200; ++k) {
    term *= q / (static_cast<double>(k) * k);
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return sum;
}
}  // namespace detail

/// @brief A Kaiser-windowed sinc of half-width L samples (2L taps), h(x) = sinc(x)
/// I0(b sqrt(1 - (x/L)^2)) / I0(b) with b = 0.6 L + 2.5, for band-limited reconstruction of a
/// uniformly sampled input between its samples.
///
/// Tabulated once, at construction (kPhases points per sample, linear interpolation between them);
/// the evaluations are noexcept and allocate nothing. In real time the interpolation between
/// samples j and j + 1 needs the samples up to j + L: a look-ahead delay of L - 1 samples.
class SincKernel {
 public:
  static constexpr int kPhases = 512;  ///< table points per sample
  static constexpr int kMaxHalfWidth = 64;  ///< the largest half-width accepted, samples

  SincKernel() = default;
  /// @param half_width L, in [1, kMaxHalfWidth] samples; throws std::invalid_argument otherwise.
  explicit SincKernel(int half_width) : L_(half_width) {
    require(half_width >= 1 && half_width <= kMaxHalfWidth, "SincKernel",
            "the look-ahead (half-width) must be in [1, 64] samples (got ", half_width, ")");
    if (detail::failed()) return;  // without exceptions, in make(): no table of a bad size
    beta_ = 0.6 * L_ + 2.5;
    const int n = L_ * kPhases + 1;
    table_.resize(static_cast<std::size_t>(n) + 1, 0.0);
    const double pi = 3.14159265358979323846;
    const double i0b = detail::bessel_i0(beta_);
    for (int k = 0; k < n; ++k) {
      const double x = static_cast<double>(k) / kPhases;
      const double r = x / L_;
      const double w = r < 1.0 ? detail::bessel_i0(beta_ * std::sqrt(1.0 - r * r)) / i0b : 0.0;
      const double s = k == 0 ? 1.0 : std::sin(pi * x) / (pi * x);
      table_[static_cast<std::size_t>(k)] = s * w;
    }
  }

  /// The half-width L, samples.
  int half_width() const noexcept { return L_; }
  /// The number of taps, 2 L.
  int taps() const noexcept { return 2 * L_; }
  /// The Kaiser window's shape b = 0.6 L + 2.5.
  double beta() const noexcept { return beta_; }

  /// h(x), x in any sign (0 outside (-L, L)).
  double value(double x) const noexcept {
    const double a = std::fabs(x) * kPhases;
    if (!(a < static_cast<double>(L_) * kPhases)) return 0.0;
    const std::size_t i = static_cast<std::size_t>(a);
    const double f = a - static_cast<double>(i);
    return table_[i] + f * (table_[i + 1] - table_[i]);
  }

  /// Normalised weights w[0..2L-1] of the samples at offsets -L+1..L from the interval's
  /// first sample, for the fraction tau in [0, 1] of the interval.
  void weights(double tau, double* w) const noexcept {
    double sum = 0.0;
    for (int i = 0; i < 2 * L_; ++i) {
      w[i] = value(tau - static_cast<double>(i - L_ + 1));
      sum += w[i];
    }
    const double inv = 1.0 / sum;
    for (int i = 0; i < 2 * L_; ++i) w[i] *= inv;
  }

 private:
  int L_ = 0;
  double beta_ = 0.0;
  std::vector<double> table_;
};

/// Offline reconstruction on a grid Q times finer: out[k Q + i] = u(t_k + (i / Q) dt) for
/// k in [0, n), i in [0, Q) (out has n Q values). The same values as the streaming
/// interpolation of HystereticOscillator (input held before the first and after the last
/// sample).
inline void reconstruct_bandlimited(const SincKernel& kernel, const double* x, std::size_t n,
                                    int Q, double* out) {
  require(n >= 1, "reconstruct_bandlimited", "the input is empty");
  require(Q >= 1, "reconstruct_bandlimited", "the upsampling factor must be >= 1");
  const int L = kernel.half_width();
  std::vector<double> w(static_cast<std::size_t>(Q) * 2 * L);
  for (int i = 1; i < Q; ++i) kernel.weights(static_cast<double>(i) / Q, &w[i * 2 * L]);
  const auto at = [&](long long k) {
    if (k < 0) return x[0];
    if (k >= static_cast<long long>(n)) return x[n - 1];
    return x[k];
  };
  for (std::size_t k = 0; k < n; ++k) {
    out[k * Q] = x[k];
    for (int i = 1; i < Q; ++i) {
      const double* wi = &w[i * 2 * L];
      double s = 0.0;
      for (int j = 0; j < 2 * L; ++j) s += wi[j] * at(static_cast<long long>(k) + j - L + 1);
      out[k * Q + i] = s;
    }
  }
}

}  // namespace tendonsheath
