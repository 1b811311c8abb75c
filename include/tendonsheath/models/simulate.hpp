// Batch simulation of any streaming model: the whole loop in C++.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

namespace detail {
// Optional parts of the model concept: int delay() (samples by which step()'s output lags
// its input, 0 if absent) and bool diverged() / long diverged_at() (the state overflowed).
template <class M, class = void>
struct has_delay : std::false_type {};
template <class M>
struct has_delay<M, std::void_t<decltype(std::declval<const M&>().delay())>> : std::true_type {};
template <class M, class = void>
struct has_divergence : std::false_type {};
template <class M>
struct has_divergence<M, std::void_t<decltype(std::declval<const M&>().diverged())>>
    : std::true_type {};

template <class M, class = void>
struct has_status : std::false_type {};
template <class M>
struct has_status<M, std::void_t<decltype(std::declval<const M&>().status())>> : std::true_type {};

// The model's status after a step as one byte (Status fits in 8 bits), ok when it has none.
template <class M>
unsigned char status_byte(const M& m) noexcept {
  if constexpr (has_status<M>::value) {
    return static_cast<unsigned char>(m.status());
  } else {
    (void)m;
    return 0;
  }
}

template <class M>
int delay_of(const M& m) noexcept {
  if constexpr (has_delay<M>::value) {
    return m.delay();
  } else {
    (void)m;
    return 0;
  }
}
template <class M>
bool diverged(const M& m) noexcept {
  if constexpr (has_divergence<M>::value) {
    return m.diverged();
  } else {
    (void)m;
    return false;
  }
}
}  // namespace detail

/// Model concept: reset() noexcept; double step(double x, double dt) noexcept;
/// The first step() after reset() initialises the state at x (dt is ignored).
/// t may be nullptr for rate-independent models; then dt = 1 per sample.
/// The input is validated in the same pass (a bad sample throws, naming it, and the
/// partial output is discarded by the caller). A model whose step() lags by delay()
/// samples is fed delay() more samples (the last one held) and y is realigned. A model
/// whose state diverged (diverged()) throws std::invalid_argument, naming the sample.
/// status, when given, receives each sample's Status flags (n bytes, written in the loop).
template <class Model>
void simulate(Model& model, const double* t, const double* x, double* y, std::size_t n,
              const char* where, unsigned char* status = nullptr) {
  require(n >= 1, where, "the input is empty");
  model.reset();
  const std::size_t D = static_cast<std::size_t>(detail::delay_of(model));
  bool ok = true;
  double dt = 0.0;
  for (std::size_t k = 0; k < n + D; ++k) {
    if (k < n) {
      dt = 0.0;
      if (t != nullptr) {
        if (k > 0) dt = t[k] - t[k - 1];
        ok &= std::isfinite(t[k]) & (k == 0 || dt > 0.0);
      } else if (k > 0) {
        dt = 1.0;
      }
      ok &= std::isfinite(x[k]);
      if (!ok) check_series(t, x, k + 1, where);  // throws, naming the sample
    }
    const double yk = model.step(x[k < n ? k : n - 1], dt);
    if (k >= D) y[k - D] = yk;
    if (status != nullptr && k >= D) status[k - D] = detail::status_byte(model);
  }
  if constexpr (detail::has_divergence<Model>::value) {
    if (model.diverged()) {
      const long at = model.diverged_at() - static_cast<long>(D);
      detail::fail(where, "the state diverged (overflowed) at sample ", at > 0 ? at : 0, " of ", n);
    }
  }
}

}  // namespace tendonsheath
