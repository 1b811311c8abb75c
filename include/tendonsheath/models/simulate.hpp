// Batch simulation of any streaming model: the whole loop in C++.
#pragma once

#include <cmath>
#include <cstddef>

#include "../validate.hpp"

namespace tendonsheath {

// Model concept: reset() noexcept; double step(double x, double dt) noexcept;
// The first step() after reset() initialises the state at x (dt is ignored).
// t may be nullptr for rate-independent models; then dt = 1 per sample.
// The input is validated in the same pass (a bad sample throws, naming it, and the
// partial output is discarded by the caller).
template <class Model>
void simulate(Model& model, const double* t, const double* x, double* y, std::size_t n,
              const char* where) {
  require(n >= 1, where, "the input is empty");
  model.reset();
  bool ok = true;
  for (std::size_t k = 0; k < n; ++k) {
    double dt = 0.0;
    if (t != nullptr) {
      if (k > 0) dt = t[k] - t[k - 1];
      ok &= std::isfinite(t[k]) & (k == 0 || dt > 0.0);
    } else if (k > 0) {
      dt = 1.0;
    }
    ok &= std::isfinite(x[k]);
    if (!ok) check_series(t, x, k + 1, where);  // throws, naming the sample
    y[k] = model.step(x[k], dt);
  }
}

}  // namespace tendonsheath
