// Batch simulation of any streaming model: the whole loop in C++.
#pragma once

#include <cstddef>

#include "../validate.hpp"

namespace tendonsheath {

// Model concept: reset() noexcept; double step(double x, double dt) noexcept;
// The first step() after reset() initialises the state at x (dt is ignored).
// t may be nullptr for rate-independent models; then dt = 1 per sample.
template <class Model>
void simulate(Model& model, const double* t, const double* x, double* y, std::size_t n,
              const char* where) {
  check_series(t, x, n, where);
  model.reset();
  for (std::size_t k = 0; k < n; ++k) {
    const double dt = (k == 0 || t == nullptr) ? (k == 0 ? 0.0 : 1.0) : t[k] - t[k - 1];
    y[k] = model.step(x[k], dt);
  }
}

}  // namespace tendonsheath
