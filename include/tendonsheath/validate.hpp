// Parameter and input validation. Used only at construction and in batch
// (non-real-time) entry points; step() never throws.
//
// A failed check throws std::invalid_argument "<where>: <what>" when exceptions are on; built
// without them (-fno-exceptions) it goes where error_handler.hpp says: collected by make()
// (result.hpp) or handed to the error handler, then std::abort().
//
// A check costs a comparison when it passes: its message is given as parts (text, numbers)
// that are formatted only when the check fails (std::to_chars: no locale, no iostreams), so
// a passing check allocates nothing, e.g. require(n >= 2, where, "n must be >= 2 (got ", n, ")").
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <string>
#include <string_view>
#include <type_traits>

#include "error_handler.hpp"

namespace tendonsheath {

namespace detail {
// Shortest text that reads back as v (std::to_chars: no locale, no iostreams).
inline std::string format_value(double v) {
  char buf[64];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  return std::string(buf, end);
}

inline void append_part(std::string& s, std::string_view part) { s.append(part); }
inline void append_part(std::string& s, char c) { s.push_back(c); }
inline void append_part(std::string& s, double v) { s.append(format_value(v)); }
template <class I, std::enable_if_t<std::is_integral_v<I> && !std::is_same_v<I, char>, int> = 0>
void append_part(std::string& s, I v) {
  char buf[24];
  const auto end = std::to_chars(buf, buf + sizeof buf, v).ptr;
  s.append(buf, end);
}

// "<where>: <parts...>", built only on failure.
template <class... Parts>
std::string message(std::string_view where, const Parts&... parts) {
  std::string msg(where);
  msg.append(": ");
  (append_part(msg, parts), ...);
  return msg;
}

// A failure no caller goes on from: thrown, or (without exceptions) handed to the error handler.
template <class... Parts>
[[noreturn]] void fail(std::string_view where, const Parts&... parts) {
  raise_error(message(where, parts...));
}

// A failed check: thrown, or (without exceptions) collected by make() when one is running on
// this thread (then it returns: the constructor goes on to its detail::failed() guard).
template <class... Parts>
void check_failed(std::string_view where, const Parts&... parts) {
  report_error(message(where, parts...));
}
}  // namespace detail

/// Throws std::invalid_argument with "<where>: <parts...>" when cond is false; the parts
/// (text, floating-point and integer values) are formatted only then. Built without exceptions,
/// the message goes to make() or to the error handler instead (error_handler.hpp).
template <class... Parts>
inline void require(bool cond, std::string_view where, const Parts&... parts) {
  if (!cond) detail::check_failed(where, parts...);
}

/// Throws std::invalid_argument "<where>: <name> must be finite (got v)" unless v is finite.
inline void require_finite(double v, const char* where, const char* name) {
  require(std::isfinite(v), where, name, " must be finite (got ", v, ")");
}

/// Throws std::invalid_argument "<where>: <name> must be > 0 (got v)" unless v is finite and > 0.
inline void require_positive(double v, const char* where, const char* name) {
  require(std::isfinite(v) && v > 0.0, where, name, " must be > 0 (got ", v, ")");
}

/// Throws std::invalid_argument "<where>: <name> must be >= 0 (got v)" unless v is finite and >= 0.
inline void require_non_negative(double v, const char* where, const char* name) {
  require(std::isfinite(v) && v >= 0.0, where, name, " must be >= 0 (got ", v, ")");
}

/// Throws std::invalid_argument "<where>: <name> must be >= lo (got v)" unless v is finite and >= lo.
inline void require_at_least(double v, double lo, const char* where, const char* name) {
  require(std::isfinite(v) && v >= lo, where, name, " must be >= ", lo, " (got ", v, ")");
}

/// Throws std::invalid_argument "<where>: <name> must be in [lo, hi] (got v)" unless v is finite and
/// in [lo, hi].
inline void require_in_range(double v, double lo, double hi, const char* where, const char* name) {
  require(std::isfinite(v) && v >= lo && v <= hi, where, name, " must be in [", lo, ", ", hi,
          "] (got ", v, ")");
}

/// A sampled signal for batch simulation: n >= 1 finite samples, and when a
/// time vector is given it must be finite and strictly increasing.
inline void check_series(const double* t, const double* x, std::size_t n, const char* where) {
  require(n >= 1, where, "the input is empty");
  // Branch-free scans first (they vectorise); locate the culprit only on failure.
  bool finite = true;
  for (std::size_t k = 0; k < n; ++k) finite &= std::isfinite(x[k]);
  if (!finite) {
    for (std::size_t k = 0; k < n; ++k)
      require(std::isfinite(x[k]), where, "input sample x[", k, "] is not finite (", x[k], ")");
  }
  if (t == nullptr) return;
  bool ordered = std::isfinite(t[0]);
  for (std::size_t k = 1; k < n; ++k) ordered &= (t[k] > t[k - 1]) & std::isfinite(t[k]);
  if (ordered) return;
  for (std::size_t k = 0; k < n; ++k) {
    require(std::isfinite(t[k]), where, "time t[", k, "] is not finite (", t[k], ")");
    require(k == 0 || t[k] > t[k - 1], where, "time is not strictly increasing at t[", k,
            "] = ", t[k], " <= t[", k - 1, "] = ", k > 0 ? t[k - 1] : 0.0);
  }
}

}  // namespace tendonsheath
