// Batch evaluation of model populations for identification (NOT real-time:
// allocates, spawns threads). It lives beside the bindings, outside the installed
// real-time tree include/tendonsheath/, and only the Python extension uses it.
//
// A population is P parameter vectors; each is evaluated on R recordings, with
// its own vector per recording (so that a parameter may depend on the
// recording's configuration). params has P * R * Params::vector_size values,
// laid out [member][recording][parameter]. The cost of a member is the sum over
// recordings of the squared simulation error after the recording's warm-up.
//
// Separable models (a part of the output is linear in some parameters given
// the others) are evaluated through a Features kernel: it simulates the
// nonlinear state and emits K regressors per sample; the K linear
// coefficients, shared by all recordings, are solved by least squares and the
// cost is the residual sum of squares (variable projection).
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <exception>
#include <limits>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include <tendonsheath/models/bouc_wen.hpp>
#include <tendonsheath/models/bouc_wen_backlash.hpp>
#include <tendonsheath/models/curve_angle.hpp>
#include <tendonsheath/models/generalized_prandtl_ishlinskii.hpp>
#include <tendonsheath/models/hysteretic_oscillator.hpp>
#include <tendonsheath/models/prandtl_ishlinskii.hpp>
#include <tendonsheath/models/simulate.hpp>
#include <tendonsheath/validate.hpp>

namespace tendonsheath::batch {

// One logged experiment. t may be nullptr (rate-independent models: dt = 1),
// y may be nullptr (simulate only), theta (curve angle per sample) may be nullptr.
// A route (route_n samples (s, theta(s)), held over the whole recording) replaces theta
// for models that take a route's shape (CurveAngleModel: g, G at each member's friction).
struct Recording {
  const double* t = nullptr;
  const double* x = nullptr;
  const double* y = nullptr;
  const double* theta = nullptr;
  const double* route_s = nullptr;
  const double* route_theta = nullptr;
  std::size_t route_n = 0;
  std::size_t n = 0;
  std::size_t warmup = 0;  // samples excluded from the cost
  // Optional input reconstructed on a grid `fine` times finer (n * fine values, see
  // HystereticOscillator::step_dense); used by models that have step_dense().
  const double* x_fine = nullptr;
  int fine = 0;
};

inline unsigned default_workers() noexcept {
  const unsigned h = std::thread::hardware_concurrency();
  return h > 0 ? h : 1;
}

// f(i) for i in [0, count), dynamically scheduled on `workers` threads (0: all
// cores). f must not throw.
template <class F>
void parallel_for(std::size_t count, unsigned workers, const F& f) {
  if (workers == 0) workers = default_workers();
  if (workers > count) workers = static_cast<unsigned>(count);
  if (workers <= 1) {
    for (std::size_t i = 0; i < count; ++i) f(i);
    return;
  }
  std::atomic<std::size_t> next{0};
  auto work = [&]() {
    for (std::size_t i = next++; i < count; i = next++) f(i);
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (unsigned w = 1; w < workers; ++w) pool.emplace_back(work);
  work();
  for (auto& th : pool) th.join();
}

namespace detail {
template <class Model>
inline double step_model(Model& m, double x, double dt, double /*theta*/) noexcept {
  return m.step(x, dt);
}
inline double step_model(CurveAngleModel& m, double x, double dt, double theta) noexcept {
  return std::isnan(theta) ? m.step(x, dt) : m.step(x, dt, theta);
}

// Before the first step: a model that takes a route's shape gets the recording's route.
template <class Model>
inline void prepare(Model& /*m*/, const Recording& /*r*/) noexcept {}
inline void prepare(CurveAngleModel& m, const Recording& r) noexcept {
  if (r.route_n > 0)
    m.set_shape(shape_integrals(r.route_s, r.route_theta, r.route_n, m.params().friction));
}

inline double dt_at(const Recording& r, std::size_t k) noexcept {
  if (k == 0) return 0.0;
  return r.t ? r.t[k] - r.t[k - 1] : 1.0;
}

constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace detail

inline void check_recordings(const std::vector<Recording>& recs, bool need_y, const char* where) {
  require(!recs.empty(), where, "no recordings");
  for (std::size_t r = 0; r < recs.size(); ++r) {
    const Recording& rec = recs[r];
    const std::string w = std::string(where) + " (recording " + std::to_string(r) + ")";
    check_series(rec.t, rec.x, rec.n, w.c_str());
    require(!need_y || rec.y != nullptr, w, "no measured output");
    require(rec.warmup < rec.n, w, "warm-up leaves no samples");
  }
}

// Simulate one parameter set on one recording: writes yhat (may be nullptr) and
// returns the sum of squared errors after warm-up (0 when rec.y is nullptr).
// Invalid parameters or a non-finite output give +inf.
namespace detail {
template <class M, class = void>
struct has_step_dense : std::false_type {};
template <class M>
struct has_step_dense<M, std::void_t<decltype(std::declval<M&>().step_dense(
                             static_cast<const double*>(nullptr), 1, 1.0))>> : std::true_type {};
}  // namespace detail

// A model with a look-ahead delay (delay() > 0) is fed delay() more samples, the last one
// held, and its output realigned; a diverged state (diverged()) counts as invalid (+inf).
template <class Model>
double simulate_one(const typename Model::Params& p, const Recording& rec, double* yhat) noexcept {
  try {
    Model model(p);
    detail::prepare(model, rec);
    double sse = 0.0;
    bool dense = false;
    if constexpr (detail::has_step_dense<Model>::value) dense = rec.x_fine != nullptr;
    const std::size_t D = dense ? 0 : static_cast<std::size_t>(tendonsheath::detail::delay_of(model));
    double dt = 0.0;
    for (std::size_t k = 0; k < rec.n + D; ++k) {
      const std::size_t kk = k < rec.n ? k : rec.n - 1;
      if (k < rec.n) dt = detail::dt_at(rec, k);
      double yk;
      if constexpr (detail::has_step_dense<Model>::value) {
        if (dense) {
          yk = model.step_dense(rec.x_fine + (k > 0 ? (k - 1) * rec.fine : 0), rec.fine, dt);
        } else {
          yk = model.step(rec.x[kk], dt);
        }
      } else {
        const double th = rec.theta && rec.route_n == 0
                              ? rec.theta[kk]
                              : std::numeric_limits<double>::quiet_NaN();
        yk = detail::step_model(model, rec.x[kk], dt, th);
      }
      if (k < D) continue;
      const std::size_t i = k - D;
      if (yhat) yhat[i] = yk;
      if (rec.y && i >= rec.warmup) {
        const double e = rec.y[i] - yk;
        sse += e * e;
      }
    }
    if (tendonsheath::detail::diverged(model)) {
      if (yhat)
        for (std::size_t k = 0; k < rec.n; ++k) yhat[k] = std::numeric_limits<double>::quiet_NaN();
      return detail::kInf;
    }
    return std::isfinite(sse) ? sse : detail::kInf;
  } catch (...) {
    if (yhat)
      for (std::size_t k = 0; k < rec.n; ++k) yhat[k] = std::numeric_limits<double>::quiet_NaN();
    return detail::kInf;
  }
}

// costs[p] = sum_r SSE(member p on recording r).
template <class Model>
void population_cost(const typename Model::Params& base, const double* params, std::size_t P,
                     const std::vector<Recording>& recs, double* costs, unsigned workers = 0) {
  constexpr std::size_t np = Model::Params::vector_size;
  const std::size_t R = recs.size();
  parallel_for(P, workers, [&](std::size_t p) {
    double total = 0.0;
    for (std::size_t r = 0; r < R && std::isfinite(total); ++r) {
      typename Model::Params q = base;
      q.assign(params + (p * R + r) * np);
      total += simulate_one<Model>(q, recs[r], nullptr);
    }
    costs[p] = total;
  });
}

// out[p][k] over the concatenated samples of all recordings.
template <class Model>
void population_simulate(const typename Model::Params& base, const double* params, std::size_t P,
                         const std::vector<Recording>& recs, double* out, unsigned workers = 0) {
  constexpr std::size_t np = Model::Params::vector_size;
  const std::size_t R = recs.size();
  std::size_t total = 0;
  for (const auto& r : recs) total += r.n;
  parallel_for(P, workers, [&](std::size_t p) {
    double* o = out + p * total;
    for (std::size_t r = 0; r < R; ++r) {
      typename Model::Params q = base;
      q.assign(params + (p * R + r) * np);
      simulate_one<Model>(q, recs[r], o);
      o += recs[r].n;
    }
  });
}

// ---------------------------------------------------------------------------
// Separable models: regressors given the nonlinear parameters.
//
// A Features type has: using Params; int size(Params) (K); std::size_t
// vector_size (nonlinear parameters); void assign(Params&, const double*);
// and template <class Sink> void run(const Params&, const Recording&, Sink&&)
// that calls sink(k, const double* row) for every sample (row has K values).
// run() may throw std::invalid_argument for invalid parameters.

// Bouc-Wen backlash: w depends on (rho, sigma, n) only, and
//   y = c_r [phi x] + (c_r B_r) [-phi] + c_l [(1-phi) x] + (c_l B_l) [1-phi].
struct BoucWenBacklashFeatures {
  using Params = BoucWenBacklashParams;
  static constexpr std::size_t vector_size = 3;  // rho, sigma, n
  static int size(const Params&) noexcept { return 4; }
  static void assign(Params& p, const double* v) noexcept {
    p.rho = v[0];
    p.sigma = v[1];
    p.n = v[2];
  }
  template <class Sink>
  static void run(const Params& p, const Recording& rec, Sink&& sink) {
    Params q = p;
    q.c_r = q.c_l = 1.0;
    q.B_r = q.B_l = 0.0;
    BoucWenBacklash model(q);
    double row[4];
    for (std::size_t k = 0; k < rec.n; ++k) {
      model.step(rec.x[k]);
      const double phi = 0.5 * (1.0 + model.state());
      const double x = rec.x[k];
      row[0] = phi * x;
      row[1] = -phi;
      row[2] = (1.0 - phi) * x;
      row[3] = 1.0 - phi;
      sink(k, row);
    }
  }
};

// Classic Bouc-Wen: z depends on (A, beta, gamma, n), and y = a [x] + ((1-a) k) [z].
struct BoucWenFeatures {
  using Params = BoucWenParams;
  static constexpr std::size_t vector_size = 4;  // A, beta, gamma, n
  static int size(const Params&) noexcept { return 2; }
  static void assign(Params& p, const double* v) noexcept {
    p.A = v[0];
    p.beta = v[1];
    p.gamma = v[2];
    p.n = v[3];
  }
  template <class Sink>
  static void run(const Params& p, const Recording& rec, Sink&& sink) {
    Params q = p;
    q.alpha = 0.5;
    q.k = 1.0;
    BoucWen model(q);
    double row[2];
    for (std::size_t k = 0; k < rec.n; ++k) {
      model.step(rec.x[k]);
      row[0] = rec.x[k];
      row[1] = model.state();
      sink(k, row);
    }
  }
};

// Prandtl-Ishlinskii: the play outputs for given thresholds; weights are linear.
// The nonlinear vector is the thresholds (their count is fixed by Params).
struct PrandtlIshlinskiiFeatures {
  using Params = PrandtlIshlinskiiParams;
  static int size(const Params& p) noexcept { return static_cast<int>(p.thresholds.size()); }
  static void assign(Params& p, const double* v) noexcept {
    for (std::size_t i = 0; i < p.thresholds.size(); ++i) p.thresholds[i] = v[i];
  }
  template <class Sink>
  static void run(const Params& p, const Recording& rec, Sink&& sink) {
    Params q = p;
    q.weights.assign(q.thresholds.size(), 1.0);
    PrandtlIshlinskii model(q);
    for (std::size_t k = 0; k < rec.n; ++k) {
      model.step(rec.x[k]);
      sink(k, model.play_states().data());
    }
  }
};

// Generalized Prandtl-Ishlinskii: the play outputs for given envelopes and
// thresholds, plus a constant column (an output offset, folded into the
// envelopes' d by the caller). The weights are >= 0 (bounded least squares);
// the constant is free. Nonlinear vector: rising a, b, c, d, falling a, b, c,
// d, then the K thresholds (their count is fixed by Params).
struct GeneralizedPrandtlIshlinskiiFeatures {
  using Params = GeneralizedPrandtlIshlinskiiParams;
  static constexpr bool nonnegative = true;  // all but the last coefficient
  static int size(const Params& p) noexcept { return static_cast<int>(p.thresholds.size()) + 1; }
  static void assign(Params& p, const double* v) noexcept {
    p.rising = Envelope{v[0], v[1], v[2], v[3]};
    p.falling = Envelope{v[4], v[5], v[6], v[7]};
    for (std::size_t i = 0; i < p.thresholds.size(); ++i) p.thresholds[i] = v[8 + i];
  }
  template <class Sink>
  static void run(const Params& p, const Recording& rec, Sink&& sink) {
    Params q = p;
    q.weights.assign(q.thresholds.size(), 1.0);
    GeneralizedPrandtlIshlinskii model(q);
    const std::size_t K = q.thresholds.size();
    std::vector<double> row(K + 1, 1.0);
    for (std::size_t k = 0; k < rec.n; ++k) {
      model.step(rec.x[k]);
      const auto& z = model.play_states();
      for (std::size_t i = 0; i < K; ++i) row[i] = z[i];
      sink(k, row.data());
    }
  }
};

template <class F, class = void>
struct is_nonnegative : std::false_type {};
template <class F>
struct is_nonnegative<F, std::void_t<decltype(F::nonnegative)>>
    : std::integral_constant<bool, F::nonnegative> {};

template <class F>
std::size_t features_vector_size(const typename F::Params& base) {
  if constexpr (std::is_same_v<F, PrandtlIshlinskiiFeatures>) {
    return base.thresholds.size();
  } else if constexpr (std::is_same_v<F, GeneralizedPrandtlIshlinskiiFeatures>) {
    return 8 + base.thresholds.size();
  } else {
    (void)base;
    return F::vector_size;
  }
}

namespace detail {
// Solve the symmetric positive semi-definite K x K system G theta = b by
// Cholesky with a small ridge; returns false if it fails.
inline bool solve_spd(std::vector<double> G, std::vector<double> b, int K, double* theta) {
  double trace = 0.0;
  for (int i = 0; i < K; ++i) trace += G[i * K + i];
  const double ridge = 1e-12 * (trace > 0.0 ? trace / K : 1.0);
  for (int i = 0; i < K; ++i) G[i * K + i] += ridge;
  for (int j = 0; j < K; ++j) {
    double d = G[j * K + j];
    for (int k = 0; k < j; ++k) d -= G[j * K + k] * G[j * K + k];
    if (!(d > 0.0)) return false;
    d = std::sqrt(d);
    G[j * K + j] = d;
    for (int i = j + 1; i < K; ++i) {
      double s = G[i * K + j];
      for (int k = 0; k < j; ++k) s -= G[i * K + k] * G[j * K + k];
      G[i * K + j] = s / d;
    }
  }
  for (int i = 0; i < K; ++i) {
    double s = b[i];
    for (int k = 0; k < i; ++k) s -= G[i * K + k] * b[k];
    b[i] = s / G[i * K + i];
  }
  for (int i = K - 1; i >= 0; --i) {
    double s = b[i];
    for (int k = i + 1; k < K; ++k) s -= G[k * K + i] * b[k];
    b[i] = s / G[i * K + i];
  }
  for (int i = 0; i < K; ++i) theta[i] = b[i];
  return true;
}

// min 0.5 t'Gt - b't with t_i >= 0 for i < n_bounded (the rest free): the
// Lawson-Hanson active-set method on the normal equations. Returns false if a
// sub-system cannot be solved.
inline bool solve_nonneg(const std::vector<double>& G, const std::vector<double>& b, int K,
                         int n_bounded, double* theta) {
  std::vector<char> passive(K, 0);
  std::vector<double> t(K, 0.0), s(K, 0.0);
  for (int i = n_bounded; i < K; ++i) passive[i] = 1;
  double scale = 0.0;
  for (int i = 0; i < K; ++i) scale = std::max(scale, std::abs(b[i]));
  const double tol = 1e-12 * (scale > 0.0 ? scale : 1.0);
  auto solve_passive = [&](std::vector<double>& out) {
    std::vector<int> idx;
    for (int i = 0; i < K; ++i)
      if (passive[i]) idx.push_back(i);
    const int m = static_cast<int>(idx.size());
    std::fill(out.begin(), out.end(), 0.0);
    if (m == 0) return true;
    std::vector<double> Gs(m * m), bs(m), ts(m);
    for (int i = 0; i < m; ++i) {
      bs[i] = b[idx[i]];
      for (int j = 0; j < m; ++j) Gs[i * m + j] = G[idx[i] * K + idx[j]];
    }
    if (!solve_spd(Gs, bs, m, ts.data())) return false;
    for (int i = 0; i < m; ++i) out[idx[i]] = ts[i];
    return true;
  };
  if (!solve_passive(t)) return false;
  for (int outer = 0; outer < 3 * K + 10; ++outer) {
    // gradient of the objective's negative: w = b - G t
    int best = -1;
    double wbest = tol;
    for (int i = 0; i < n_bounded; ++i) {
      if (passive[i]) continue;
      double w = b[i];
      for (int j = 0; j < K; ++j) w -= G[i * K + j] * t[j];
      if (w > wbest) {
        wbest = w;
        best = i;
      }
    }
    if (best < 0) break;
    passive[best] = 1;
    for (int inner = 0; inner < 3 * K + 10; ++inner) {
      if (!solve_passive(s)) return false;
      double alpha = 1.0;
      bool feasible = true;
      for (int i = 0; i < n_bounded; ++i) {
        if (passive[i] && s[i] <= 0.0) {
          feasible = false;
          const double d = t[i] - s[i];
          const double a = d > 0.0 ? t[i] / d : 0.0;
          if (a < alpha) alpha = a;
        }
      }
      if (feasible) {
        t = s;
        break;
      }
      for (int i = 0; i < K; ++i) t[i] += alpha * (s[i] - t[i]);
      for (int i = 0; i < n_bounded; ++i)
        if (passive[i] && t[i] <= tol * 1e-3) {
          passive[i] = 0;
          t[i] = 0.0;
        }
    }
  }
  for (int i = 0; i < K; ++i) theta[i] = t[i];
  return true;
}
}  // namespace detail

// Residual sum of squares of the least-squares linear coefficients (shared by
// all recordings) for one nonlinear vector v; theta (K values) may be nullptr.
namespace detail {
// Accumulate G (lower triangle), b and y'y; K known at compile time when KC > 0.
template <int KC, class F>
void accumulate(const typename F::Params& p, const std::vector<Recording>& recs, int K,
                double* G, double* b, double& yy) {
  for (const Recording& rec : recs) {
    F::run(p, rec, [&](std::size_t k, const double* row) {
      if (k < rec.warmup) return;
      const double y = rec.y[k];
      const int n = KC > 0 ? KC : K;
      for (int i = 0; i < n; ++i) {
        b[i] += row[i] * y;
        for (int j = 0; j <= i; ++j) G[i * n + j] += row[i] * row[j];
      }
      yy += y * y;
    });
  }
}
}  // namespace detail

// Residual sum of squares of the least-squares linear coefficients (shared by
// all recordings) for one nonlinear vector v; theta (K values) may be nullptr.
template <class F>
double separable_cost_one(const typename F::Params& base, const double* v,
                          const std::vector<Recording>& recs, double* theta) noexcept {
  try {
    typename F::Params p = base;
    F::assign(p, v);
    const int K = F::size(p);
    std::vector<double> G(K * K, 0.0), b(K, 0.0), th(K, 0.0);
    double yy = 0.0;
    if (K == 4)
      detail::accumulate<4, F>(p, recs, K, G.data(), b.data(), yy);
    else if (K == 2)
      detail::accumulate<2, F>(p, recs, K, G.data(), b.data(), yy);
    else
      detail::accumulate<0, F>(p, recs, K, G.data(), b.data(), yy);
    for (int i = 0; i < K; ++i)
      for (int j = 0; j < i; ++j) G[j * K + i] = G[i * K + j];
    if constexpr (is_nonnegative<F>::value) {
      if (!detail::solve_nonneg(G, b, K, K - 1, th.data())) return detail::kInf;
    } else {
      if (!detail::solve_spd(G, b, K, th.data())) return detail::kInf;
    }
    // SSE = y'y - 2 theta'b + theta'G theta
    double quad = 0.0, lin = 0.0;
    for (int i = 0; i < K; ++i) {
      lin += th[i] * b[i];
      for (int j = 0; j < K; ++j) quad += th[i] * G[i * K + j] * th[j];
    }
    if (theta)
      for (int i = 0; i < K; ++i) theta[i] = th[i];
    const double sse = yy - 2.0 * lin + quad;
    if (!std::isfinite(sse)) return detail::kInf;
    return sse > 0.0 ? sse : 0.0;
  } catch (...) {
    return detail::kInf;
  }
}

template <class F>
void separable_population_cost(const typename F::Params& base, const double* v, std::size_t P,
                               const std::vector<Recording>& recs, double* costs,
                               unsigned workers = 0) {
  const std::size_t nv = features_vector_size<F>(base);
  parallel_for(P, workers, [&](std::size_t p) {
    costs[p] = separable_cost_one<F>(base, v + p * nv, recs, nullptr);
  });
}

// The regressor matrix (sum n) x K, row-major, for one nonlinear vector.
template <class F>
void features_matrix(const typename F::Params& base, const double* v,
                     const std::vector<Recording>& recs, double* out) {
  typename F::Params p = base;
  F::assign(p, v);
  const int K = F::size(p);
  std::size_t offset = 0;
  for (const Recording& rec : recs) {
    F::run(p, rec, [&](std::size_t k, const double* row) {
      for (int i = 0; i < K; ++i) out[(offset + k) * K + i] = row[i];
    });
    offset += rec.n;
  }
}

}  // namespace tendonsheath::batch
