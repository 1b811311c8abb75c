// Construction that reports a bad parameter as a value: tendonsheath::make<T>(args...) returns a
// Result<T> holding either the object or the message of its first failed check, with C++
// exceptions or without them (-fno-exceptions, TENDONSHEATH_EXCEPTIONS == 0):
//
//   auto built = tendonsheath::make<tendonsheath::Backlash>(params);
//   if (!built.ok()) { log(built.error().c_str()); return; }   // "Backlash: c_r must be > 0 ..."
//   tendonsheath::Backlash& model = built.value();
//
// The message is the one the constructor's std::invalid_argument carries. With exceptions make()
// catches that exception; without them every check of the construction reports to make()
// instead of to the error handler (error_handler.hpp), and each constructor returns at its
// guard (detail::failed()) before it sizes a buffer, indexes a vector or derives a constant from
// a bad value; make() then destroys the half-built object and returns the message.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "config.hpp"
#include "error_handler.hpp"

#if TENDONSHEATH_EXCEPTIONS
#include <stdexcept>
#endif

namespace tendonsheath {

template <class T>
class Result;

template <class T, class... Args>
Result<T> make(Args&&... args);

namespace detail {
template <class T, class Build>
Result<T> result_of(Build&& build);
}  // namespace detail

/// @brief An object of the core, or why it could not be built: what make<T>() returns.
/// @tparam T the class built
template <class T>
class Result {
 public:
  /// True when it holds the object.
  bool ok() const noexcept { return value_.has_value(); }
  /// ok()
  explicit operator bool() const noexcept { return ok(); }
  /// The object. Called on an error, it is an error itself: std::invalid_argument carrying
  /// error() with exceptions, the error handler (then std::abort()) without them.
  T& value() & {
    if (!ok()) detail::raise_error(error_);
    return *value_;
  }
  /// The object (const); as value().
  const T& value() const& {
    if (!ok()) detail::raise_error(error_);
    return *value_;
  }
  /// The object, moved out; as value().
  T&& value() && {
    if (!ok()) detail::raise_error(error_);
    return std::move(*value_);
  }
  /// The message of the first failed check, "<Class>: <what>" (empty when ok()).
  const std::string& error() const noexcept { return error_; }

 private:
  template <class U, class... Args>
  friend Result<U> make(Args&&... args);
  template <class U, class Build>
  friend Result<U> detail::result_of(Build&& build);

  std::optional<T> value_;
  std::string error_;
};

/// Build a T from args, reporting a bad parameter as a value (works with or without
/// exceptions).
/// @tparam T the class to build (any class of the core whose constructor validates)
/// @param args the constructor's arguments
/// @return the object, or the message the constructor's std::invalid_argument carries
template <class T, class... Args>
Result<T> make(Args&&... args) {
  Result<T> out;
#if TENDONSHEATH_EXCEPTIONS
  try {
    out.value_.emplace(std::forward<Args>(args)...);
  } catch (const std::invalid_argument& e) {
    out.value_.reset();
    out.error_ = e.what();
  }
#else
  detail::CaptureScope scope;
  out.value_.emplace(std::forward<Args>(args)...);
  if (scope.capture().failed) {
    out.value_.reset();  // built no further than its guard: never used, only destroyed
    out.error_ = std::move(scope.capture().message);
  }
#endif
  return out;
}

namespace detail {

// What make() does for a constructor, for a function that builds a T in steps (the JSON loaders,
// io/json.hpp): build() returns std::optional<T> and reports a failed check through
// report_error() (a throw with exceptions; without them the first message is collected here,
// and build() returns at its next guard, failed(), with std::nullopt or an object never used).
// The Result holds what build() returned, or the first failed check's message.
template <class T, class Build>
Result<T> result_of(Build&& build) {
  Result<T> out;
#if TENDONSHEATH_EXCEPTIONS
  try {
    std::optional<T> built = build();
    if (built) out.value_.emplace(std::move(*built));
  } catch (const std::invalid_argument& e) {
    out.value_.reset();
    out.error_ = e.what();
  }
#else
  CaptureScope scope;
  std::optional<T> built = build();
  if (scope.capture().failed) out.error_ = std::move(scope.capture().message);
  else if (built) out.value_.emplace(std::move(*built));
#endif
  if (!out.ok() && out.error_.empty()) out.error_ = "nothing was built and no check failed";
  return out;
}

}  // namespace detail

}  // namespace tendonsheath
