// Single-degree-of-freedom oscillator with a Bouc-Wen restoring force:
//
//   m y'' + c y' + k y + z = u
//   z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu)
//
// force u in, displacement y out. Integrated by RK4 with a fixed number of
// sub-steps per sample (at least `substeps`, raised automatically so that
// h * omega <= 0.5 for stability, never above `max_substeps`).
//
// Input between samples (`input_interpolation`):
//   0 hold: u held at the last sample;
//   1 linear: linear interpolation (the default);
//   2 bandlimited: Kaiser-windowed sinc of half-width `lookahead` samples (see
//     bandlimited.hpp). step() then needs `lookahead` samples after the interval it
//     integrates: its output lags the input by delay() = lookahead - 1 samples (the
//     output returned with input sample k is y at sample k - delay(); before that it is
//     the rest state 0). simulate() in simulate.hpp compensates the delay (the input is
//     held after its last sample). step_dense() integrates one interval from an input
//     already reconstructed on a finer grid (exact FFT upsampling of a periodic record,
//     done by the caller), with no delay.
//
// Softening and hardening: beta (gamma + delta) > 0 bounds z on monotone loading at
// z_u = (alpha / (beta (gamma + delta)))^(1/nu); beta (gamma + delta) < 0 (softening, as
// in the Bouc-Wen benchmark system) lets z grow with the displacement, bounded over a
// bounded excitation when the unloading branch contracts faster than loading expands.
// No sign is rejected: z_bound(range) bounds |z| for a displacement that stays within a
// range, and a state that overflows during a simulation sets diverged() (the state is
// then kept at its last finite value, so step() never returns NaN for finite input).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "bandlimited.hpp"
#include "power.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// How HystereticOscillator reconstructs the input between samples (input_interpolation).
enum InputReconstruction : int { kInputHold = 0, kInputLinear = 1, kInputBandlimited = 2 };

namespace detail {
// One sample interval whose input is given on a grid of Q + 1 points: integrate(u_at, m) runs
// m RK4 sub-steps reading the input at fraction i / (2m) as u_at(i). Q / 2 sub-steps on the
// grid itself when Q is even and that is at least `need`; else `need` sub-steps on the grid
// interpolated linearly.
template <class Integrate>
void on_dense_grid(const double* u, int Q, int need, const Integrate& integrate) noexcept {
  if (Q % 2 == 0 && Q / 2 >= need) {
    integrate([u](int i) { return u[i]; }, Q / 2);
    return;
  }
  const double r = static_cast<double>(Q) / (2 * need);
  integrate(
      [u, r, Q](int i) {
        const double s = i * r;
        int j = static_cast<int>(s);
        if (j >= Q) j = Q - 1;
        return u[j] + (s - j) * (u[j + 1] - u[j]);
      },
      need);
}
}  // namespace detail

/// Parameters of HystereticOscillator and OscillatorSensitivity (validated by their constructors).
struct HystereticOscillatorParams {
  double m = 1.0;  ///< mass, > 0
  double c = 0.1;  ///< viscous damping, >= 0
  double k = 1.0;  ///< linear stiffness, >= 0 (k + alpha > 0)
  double alpha = 1.0;  ///< Bouc-Wen stiffness of the hysteretic force, >= 0
  double beta = 1.0;  ///< Bouc-Wen scale, >= 0
  double gamma = 0.5;  ///< Bouc-Wen shape (any sign)
  double delta = 0.5;  ///< Bouc-Wen shape (any sign)
  double nu = 1.0;  ///< Bouc-Wen sharpness, >= 1
  int substeps = 4;  ///< fewest RK4 sub-steps per sample, >= 1
  int max_substeps = 4096;  ///< most RK4 sub-steps per sample, >= substeps (bounds the work)
  int input_interpolation = kInputLinear;  ///< kInputHold, kInputLinear or kInputBandlimited
  int lookahead = 16;  ///< half-width of the band-limited interpolation kernel, samples

  /// How many identifiable parameters assign() reads: the table's Role::parameter rows
  /// (checked against it below the table).
  static constexpr std::size_t vector_size = 8;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the order of the table's
  /// parameter rows (the Python param_names); the options are kept.
  void assign(const double* v) noexcept;
};

/// The parameter table of HystereticOscillatorParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<HystereticOscillatorParams> {
  static constexpr const char* owner = "HystereticOscillator";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("m", &HystereticOscillatorParams::m, "", positive(),
            "mass"),
      param("c", &HystereticOscillatorParams::c, "", non_negative(),
            "viscous damping"),
      param("k", &HystereticOscillatorParams::k, "", non_negative(),
            "linear stiffness (k + alpha > 0)"),
      param("alpha", &HystereticOscillatorParams::alpha, "", non_negative(),
            "Bouc-Wen stiffness of the hysteretic force"),
      param("beta", &HystereticOscillatorParams::beta, "", non_negative(),
            "Bouc-Wen scale"),
      param("gamma", &HystereticOscillatorParams::gamma, "", finite(),
            "Bouc-Wen shape (any sign)"),
      param("delta", &HystereticOscillatorParams::delta, "", finite(),
            "Bouc-Wen shape (any sign)"),
      param("nu", &HystereticOscillatorParams::nu, "", at_least(1.0),
            "Bouc-Wen sharpness"),
      option("substeps", &HystereticOscillatorParams::substeps, "", documented(1, true, kInf, false),
            "fewest RK4 sub-steps per sample"),
      option("max_substeps", &HystereticOscillatorParams::max_substeps, "", documented(1, true, kInf, false),
            "most RK4 sub-steps per sample, >= substeps (bounds the work)"),
      option("input_interpolation", &HystereticOscillatorParams::input_interpolation, "", documented(0, true, 2, true),
            "the input between samples: 0 (Python \"hold\"), 1 (\"linear\") or 2 (\"bandlimited\")"),
      option("lookahead", &HystereticOscillatorParams::lookahead, "samples", documented(1, true, 64, true),
            "half-width of the band-limited interpolation kernel"));
};

static_assert(HystereticOscillatorParams::vector_size == parameter_count<HystereticOscillatorParams>(),
              "vector_size is the number of the table's parameter rows");
inline void HystereticOscillatorParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

/// @brief Single-degree-of-freedom oscillator with a Bouc-Wen restoring force, force u in,
/// displacement y out: m y'' + c y' + k y + z = u,
/// z' = alpha y' - beta (gamma |y'| |z|^(nu-1) z + delta y' |z|^nu).
///
/// Integrated by RK4 with a bounded number of sub-steps per sample (at least substeps, raised so
/// that h omega <= 0.5, never above max_substeps). The input between samples is held, linear (the
/// default) or band-limited (a Kaiser-windowed sinc: the output then lags by delay() samples). No
/// sign of the Bouc-Wen shape is rejected: a state that overflows sets diverged() and is kept at
/// its last finite value, so step() never returns NaN for finite input. Not rate-independent:
/// step() needs dt.
class HystereticOscillator {
 public:
  /// The parameter struct its constructor takes.
  using Params = HystereticOscillatorParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = false;
  static constexpr int kWeightCacheSubsteps = 16;  ///< band-limited weights cached up to this m

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range. The
  /// band-limited history is allocated here, once.
  explicit HystereticOscillator(const Params& p) : p_(p) {
    const char* w = "HystereticOscillator";
    validate_fields(p, w);  // m .. nu, from ParamTable<HystereticOscillatorParams>
    require(p.k + p.alpha > 0.0, w, "k + alpha must be > 0 (no restoring force otherwise)");
    require(p.substeps >= 1, w, "substeps must be >= 1");
    require(p.max_substeps >= p.substeps, w, "max_substeps must be >= substeps");
    require(p.input_interpolation >= kInputHold && p.input_interpolation <= kInputBandlimited,
            w, "input_interpolation must be 0 (hold), 1 (linear) or 2 (bandlimited)");
    if (p.input_interpolation == kInputBandlimited) {
      require(p.lookahead >= 1 && p.lookahead <= SincKernel::kMaxHalfWidth, w,
              "lookahead must be in [1, 64] samples (got ", p.lookahead, ")");
      if (detail::failed()) return;  // without exceptions, in make(): no buffers of a bad size
      kernel_ = SincKernel(p.lookahead);
      const std::size_t taps = static_cast<std::size_t>(2 * p.lookahead);
      history_.assign(2 * taps, 0.0);
      weights_.assign((2 * kWeightCacheSubsteps - 1) * taps, 0.0);
    }
    pow_num1_ = detail::AbsPower(p.nu - 1.0);
    omega_ = std::sqrt((p.k + p.alpha) / p.m) + p.c / p.m;
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }

  /// Samples by which step()'s output lags its input (lookahead - 1 when band-limited).
  int delay() const noexcept {
    return p_.input_interpolation == kInputBandlimited ? p_.lookahead - 1 : 0;
  }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    initialised_ = false;
    y_ = v_ = z_ = 0.0;
    samples_ = 0;
    diverged_at_ = -1;
  }

  /// Starts at rest (y = y' = z = 0) at the first sample. A non-finite input sample is
  /// ignored (held at the previous one when band-limited, so the timing is kept).
  /// @param u the force input
  /// @param dt the sample interval, s; a dt that is not finite and > 0 integrates nothing
  /// @return the displacement y (delay() samples late when band-limited)
  double step(double u, double dt) noexcept {
    held_ = !std::isfinite(u);
    kept_ = false;
    if (held_) {
      if (p_.input_interpolation != kInputBandlimited || !initialised_) return y_;
      u = last_input();
    }
    if (!initialised_ || !(dt > 0.0) || !std::isfinite(dt)) {
      if (!initialised_) {
        initialised_ = true;
        u_ = u;
        if (p_.input_interpolation == kInputBandlimited) {
          for (double& h : history_) h = u;
          head_ = 0;
          cached_m_ = 0;
        }
      }
      return y_;
    }
    ++samples_;
    const int m = substeps(dt);
    if (p_.input_interpolation == kInputHold) {
      const double u0 = u_;
      integrate([u0](int) { return u0; }, m, dt);
    } else if (p_.input_interpolation == kInputLinear) {
      const double u0 = u_, du = (u - u_) / (2 * m);
      integrate([u0, du](int i) { return u0 + du * i; }, m, dt);
    } else {
      push(u);
      // the interval [j, j + 1] with j = samples_ - L is ready once j >= 0
      if (samples_ >= static_cast<long>(p_.lookahead)) integrate_bandlimited(m, dt);
    }
    u_ = u;
    return y_;
  }

  /// One sample interval with the input given on a grid Q times finer: u[i] = u(t0 + i dt / Q),
  /// i = 0..Q (Q + 1 values; u[Q] is the next sample). The first call after reset() only
  /// initialises (at rest) and reads nothing. When Q is even and Q / 2 sub-steps are enough,
  /// RK4 takes exactly Q / 2 sub-steps on the grid; otherwise the grid is interpolated linearly.
  /// @param u the Q + 1 input values of the interval
  /// @param Q the refinement of the grid, >= 1 (else nothing is integrated)
  /// @param dt the sample interval, s
  /// @return the displacement y at the end of the interval
  double step_dense(const double* u, int Q, double dt) noexcept {
    held_ = kept_ = false;
    if (!initialised_) {
      initialised_ = true;
      return y_;
    }
    if (!(dt > 0.0) || !std::isfinite(dt) || Q < 1) return y_;
    ++samples_;
    detail::on_dense_grid(u, Q, substeps(dt),
                          [&](const auto& u_at, int m) { integrate(u_at, m, dt); });
    return y_;
  }

  /// The RK4 sub-steps one sample interval of dt seconds takes.
  int substeps(double dt) const noexcept {
    const double need = std::ceil(dt * omega_ / 0.5);
    double m = need > p_.substeps ? need : p_.substeps;
    if (!(m <= p_.max_substeps)) m = p_.max_substeps;
    return static_cast<int>(m);
  }

  /// The displacement y after the last step().
  double output() const noexcept { return y_; }
  /// The velocity y' after the last step().
  double velocity() const noexcept { return v_; }
  /// The hysteretic force z after the last step().
  double hysteretic_force() const noexcept { return z_; }

  /// True once the state overflowed (z diverged) since reset(); the sample (1-based count of
  /// integrated intervals) where it first happened is diverged_at().
  bool diverged() const noexcept { return diverged_at_ >= 0; }
  /// The sample (1-based count of integrated intervals) where the state first overflowed, or -1.
  long diverged_at() const noexcept { return diverged_at_; }
  /// The last step's status: held_nonfinite_input (input not finite), not_converged (the
  /// integration overflowed in this step and the state was kept).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return kept_ ? s | Status::not_converged : s;
  }

  /// Bound on |z| while the displacement stays within an interval of width `range`: the
  /// largest |z| on the outer loop of repeated full-range excursions (the steady cycle of
  /// the half-cycle map, found by bisection) and on the first full-range loading from rest.
  /// +inf when that cycle does not exist or is unstable (z ratchets up from cycle to cycle,
  /// or escapes in finite displacement when nu > 1 and beta (gamma + delta) < 0), or when
  /// |z| would exceed 1e12 alpha range. Not real-time (a few thousand RK4 steps).
  double z_bound(double range) const noexcept {
    constexpr double inf = std::numeric_limits<double>::infinity();
    if (!(range > 0.0) || !std::isfinite(range) || p_.alpha == 0.0) return 0.0;
    const double scale = p_.alpha * range;
    const double huge = 1e12 * scale;
    double zmax0 = 0.0;
    const double h0 = half_cycle(0.0, range, huge, &zmax0);
    if (!(h0 < huge)) return inf;
    // g(s) = H(-s) - s, decreasing in s; its root is the steady outer loop.
    auto g = [&](double s, double* zmax) { return half_cycle(-s, range, huge, zmax) - s; };
    double zm = 0.0;
    double lo = 0.0, hi = h0 > scale ? h0 : scale;
    for (;;) {
      const double gh = g(hi, &zm);
      if (std::isnan(gh) || gh > 0.0) {
        if (gh > 0.0 && hi < huge) {
          lo = hi;
          hi *= 4.0;
          continue;
        }
        return inf;
      }
      break;
    }
    for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (g(mid, &zm) > 0.0 ? lo : hi) = mid;
    }
    const double s = 0.5 * (lo + hi);
    double zmax = 0.0;
    const double hs = half_cycle(-s, range, huge, &zmax);
    const double ds = 1e-6 * (s > 0.0 ? s : scale);
    const double hd = half_cycle(-(s + ds), range, huge, &zm);
    if (!(std::fabs(hd - hs) <= 1.000001 * ds) || !(zmax < huge)) return inf;  // unstable
    return zmax > zmax0 ? zmax : zmax0;
  }

 private:
  void rhs(const double* s, double u, double* d) const noexcept {
    const double y = s[0], v = s[1], z = s[2];
    const double az = std::fabs(z);
    const double q = pow_num1_(az);  // |z|^(nu-1)
    d[0] = v;
    d[1] = (u - p_.c * v - p_.k * y - z) / p_.m;
    d[2] = p_.alpha * v - p_.beta * (p_.gamma * std::fabs(v) * q * z + p_.delta * v * q * az);
  }

  // RK4 over one interval with m sub-steps; u_at(i) is the input at fraction i / (2m).
  template <class U>
  void integrate(const U& u_at, int m, double dt) noexcept {
    const double h = dt / m;
    double st[3] = {y_, v_, z_};
    for (int i = 0; i < m; ++i) {
      const double ua = u_at(2 * i), ub = u_at(2 * i + 1), uc = u_at(2 * i + 2);
      double k1[3], k2[3], k3[3], k4[3], tmp[3];
      rhs(st, ua, k1);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + 0.5 * h * k1[j];
      rhs(tmp, ub, k2);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + 0.5 * h * k2[j];
      rhs(tmp, ub, k3);
      for (int j = 0; j < 3; ++j) tmp[j] = st[j] + h * k3[j];
      rhs(tmp, uc, k4);
      for (int j = 0; j < 3; ++j) st[j] += h * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j]) / 6.0;
    }
    if (std::isfinite(st[0]) && std::isfinite(st[1]) && std::isfinite(st[2])) {
      y_ = st[0];
      v_ = st[1];
      z_ = st[2];
    } else {
      kept_ = true;
      if (diverged_at_ < 0) diverged_at_ = samples_;
    }
  }

  // -- band-limited streaming: the last 2L samples, stored twice so a window is contiguous
  double last_input() const noexcept {
    const std::size_t taps = history_.size() / 2;
    return history_[(head_ + taps - 1) % taps];
  }
  void push(double u) noexcept {
    const std::size_t taps = history_.size() / 2;
    history_[head_] = u;
    history_[head_ + taps] = u;
    head_ = (head_ + 1) % taps;  // the window starts at head_ (oldest sample)
  }
  void integrate_bandlimited(int m, double dt) noexcept {
    const int taps = 2 * p_.lookahead;
    const double* win = &history_[head_];  // u_{j-L+1} .. u_{j+L}
    const double u0 = win[p_.lookahead - 1], u1 = win[p_.lookahead];
    if (m <= kWeightCacheSubsteps) {
      if (m != cached_m_) {
        for (int i = 1; i < 2 * m; ++i)
          kernel_.weights(static_cast<double>(i) / (2 * m), &weights_[(i - 1) * taps]);
        cached_m_ = m;
      }
      const double* w = weights_.data();
      integrate(
          [=](int i) {
            if (i == 0) return u0;
            if (i == 2 * m) return u1;
            const double* wi = w + (i - 1) * taps;
            double s = 0.0;
            for (int j = 0; j < taps; ++j) s += wi[j] * win[j];
            return s;
          },
          m, dt);
    } else {
      const SincKernel& kern = kernel_;
      const int L = p_.lookahead;
      integrate(
          [=, &kern](int i) {
            if (i == 0) return u0;
            if (i == 2 * m) return u1;
            const double tau = static_cast<double>(i) / (2 * m);
            double s = 0.0, sum = 0.0;
            for (int j = 0; j < taps; ++j) {
              const double wj = kern.value(tau - (j - L + 1));
              s += wj * win[j];
              sum += wj;
            }
            return s / sum;
          },
          m, dt);
    }
  }

  // dz/dy for a rising displacement (y' > 0); falling is the mirror image (y, z) -> (-y, -z).
  double dz_dy(double z) const noexcept {
    const double az = std::fabs(z);
    return p_.alpha - p_.beta * pow_num1_(az) * (p_.gamma * z + p_.delta * az);
  }

  // z after a rise of `range` from z0 (adaptive RK4 in y); *zmax gets the largest |z| on the
  // way. Returns +inf when |z| passes `huge` upwards, -inf downwards, NaN if it fails.
  double half_cycle(double z0, double range, double huge, double* zmax) const noexcept {
    double z = z0, y = 0.0, top = std::fabs(z0);
    const double zscale = 1e-3 * p_.alpha * range;
    for (int it = 0; it < 100000 && y < range; ++it) {
      const double f = std::fabs(dz_dy(z));
      double h = range / 32.0;
      const double lim = 0.02 * (std::fabs(z) + zscale) / (f > 0.0 ? f : 1e-300);
      if (lim < h) h = lim;
      // and keep RK4 stable where z relaxes fast: h |d f / d z| <= 0.5
      const double stiff = p_.beta * p_.nu * pow_num1_(std::fabs(z) + zscale) *
                           (std::fabs(p_.gamma) + std::fabs(p_.delta));
      if (stiff * h > 0.5) h = 0.5 / stiff;
      if (h > range - y) h = range - y;
      const double k1 = dz_dy(z);
      const double k2 = dz_dy(z + 0.5 * h * k1);
      const double k3 = dz_dy(z + 0.5 * h * k2);
      const double k4 = dz_dy(z + h * k3);
      z += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
      y += h;
      if (!std::isfinite(z)) return std::numeric_limits<double>::quiet_NaN();
      if (std::fabs(z) > top) top = std::fabs(z);
      if (z > huge) return std::numeric_limits<double>::infinity();
      if (z < -huge) return -std::numeric_limits<double>::infinity();
    }
    *zmax = top;
    return y < range ? std::numeric_limits<double>::quiet_NaN() : z;
  }

  Params p_;
  detail::AbsPower pow_num1_{};
  double omega_ = 1.0;
  double y_ = 0.0, v_ = 0.0, z_ = 0.0, u_ = 0.0;
  bool initialised_ = false;
  bool held_ = false, kept_ = false;
  long samples_ = 0;
  long diverged_at_ = -1;
  // band-limited reconstruction (allocated at construction when used)
  SincKernel kernel_{};
  std::vector<double> history_;
  std::vector<double> weights_;
  std::size_t head_ = 0;
  int cached_m_ = 0;
};

/// The Bouc-Wen state along a sampled displacement path y[0..n-1], scaled by alpha
/// (z = alpha w), starting at w = 0:
///
///   dw/dy = 1 - |w|^(nu-1) (G s w + D |w|),  s = sign(dy),  G = alpha^(nu-1) beta gamma,
///   D = alpha^(nu-1) beta delta,
///
/// rate-independent, integrated by RK4 in y (a few sub-steps per sample). Used by the
/// equation-error stage of the identification, where y is the measured displacement (on a
/// fine grid). Returns false if w overflows (the rest of w is then NaN).
inline bool bouc_wen_path(const double* y, std::size_t n, double G, double D, double nu,
                          double* w) noexcept {
  const detail::AbsPower pw(nu - 1.0);
  double wk = 0.0;
  if (n == 0) return true;
  w[0] = 0.0;
  const double gd = std::fabs(G) + std::fabs(D);
  for (std::size_t k = 1; k < n; ++k) {
    const double dy = y[k] - y[k - 1];
    const double s = dy > 0.0 ? 1.0 : -1.0;
    const auto f = [&](double v) {
      const double a = std::fabs(v);
      return 1.0 - pw(a) * (G * s * v + D * a);
    };
    const double rate = gd * pw(std::fabs(wk) + std::fabs(dy));
    double mm = std::ceil(20.0 * std::fabs(dy) * rate);
    const int m = mm < 1.0 ? 1 : (mm > 256.0 ? 256 : static_cast<int>(mm));
    const double h = dy / m;
    for (int i = 0; i < m; ++i) {
      const double k1 = f(wk);
      const double k2 = f(wk + 0.5 * h * k1);
      const double k3 = f(wk + 0.5 * h * k2);
      const double k4 = f(wk + h * k3);
      wk += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    }
    if (!std::isfinite(wk) || std::fabs(wk) > 1e150) {
      for (std::size_t j = k; j < n; ++j) w[j] = std::numeric_limits<double>::quiet_NaN();
      return false;
    }
    w[k] = wk;
  }
  return true;
}

}  // namespace tendonsheath
