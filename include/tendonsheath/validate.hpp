// Parameter and input validation. Used only at construction and in batch
// (non-real-time) entry points; step() never throws.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace tendonsheath {

namespace detail {
// Shortest text that reads back as v (std::to_chars: no locale, no iostreams).
inline std::string format_value(double v) {
  char buf[64];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  return std::string(buf, end);
}
}  // namespace detail

// Throws std::invalid_argument with "<where>: <what>" when cond is false.
inline void require(bool cond, const std::string& where, const std::string& what) {
  if (!cond) throw std::invalid_argument(where + ": " + what);
}

inline void require_finite(double v, const char* where, const char* name) {
  require(std::isfinite(v), where,
          std::string(name) + " must be finite (got " + detail::format_value(v) + ")");
}

inline void require_positive(double v, const char* where, const char* name) {
  require(std::isfinite(v) && v > 0.0, where,
          std::string(name) + " must be > 0 (got " + detail::format_value(v) + ")");
}

inline void require_non_negative(double v, const char* where, const char* name) {
  require(std::isfinite(v) && v >= 0.0, where,
          std::string(name) + " must be >= 0 (got " + detail::format_value(v) + ")");
}

inline void require_at_least(double v, double lo, const char* where, const char* name) {
  require(std::isfinite(v) && v >= lo, where,
          std::string(name) + " must be >= " + detail::format_value(lo) + " (got " +
              detail::format_value(v) + ")");
}

inline void require_in_range(double v, double lo, double hi, const char* where, const char* name) {
  require(std::isfinite(v) && v >= lo && v <= hi, where,
          std::string(name) + " must be in [" + detail::format_value(lo) + ", " +
              detail::format_value(hi) + "] (got " + detail::format_value(v) + ")");
}

// A sampled signal for batch simulation: n >= 1 finite samples, and when a
// time vector is given it must be finite and strictly increasing.
inline void check_series(const double* t, const double* x, std::size_t n, const char* where) {
  require(n >= 1, where, "the input is empty");
  // Branch-free scans first (they vectorise); locate the culprit only on failure.
  bool finite = true;
  for (std::size_t k = 0; k < n; ++k) finite &= std::isfinite(x[k]);
  if (!finite) {
    for (std::size_t k = 0; k < n; ++k)
      if (!std::isfinite(x[k]))
        throw std::invalid_argument(std::string(where) + ": input sample x[" + std::to_string(k) +
                                    "] is not finite (" + detail::format_value(x[k]) + ")");
  }
  if (t == nullptr) return;
  bool ordered = std::isfinite(t[0]);
  for (std::size_t k = 1; k < n; ++k) ordered &= (t[k] > t[k - 1]) & std::isfinite(t[k]);
  if (ordered) return;
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(t[k]))
      throw std::invalid_argument(std::string(where) + ": time t[" + std::to_string(k) +
                                  "] is not finite (" + detail::format_value(t[k]) + ")");
    if (k > 0 && !(t[k] > t[k - 1]))
      throw std::invalid_argument(std::string(where) + ": time is not strictly increasing at t[" +
                                  std::to_string(k) + "] = " + detail::format_value(t[k]) +
                                  " <= t[" + std::to_string(k - 1) +
                                  "] = " + detail::format_value(t[k - 1]));
  }
}

}  // namespace tendonsheath
