// Where the message of a failed parameter check goes.
//
// With C++ exceptions (TENDONSHEATH_EXCEPTIONS == 1, config.hpp) a failed check throws
// std::invalid_argument("<where>: <what>"), as it always has. Built without them
// (-fno-exceptions) a failed check never continues into the code after it unchecked:
//
//   - inside tendonsheath::make<T>(...) (result.hpp) the first failed check's message is
//     collected in a thread-local slot; the constructor stops at its next guard
//     (detail::failed()) without using the bad values, and make() returns an error Result
//     holding the same message the exception would have carried;
//   - anywhere else (a constructor called directly, a static factory such as Route::uniform,
//     a set_*() method, a batch function such as simulate()) the error handler is called with
//     the message, then std::abort(). The default handler writes the message and a newline to
//     stderr; set_error_handler() replaces it (an embedded target may log and reset, or
//     longjmp to its own recovery point). A handler must not return: if it does, std::abort()
//     is called.
//
// step() never fails a check: it is noexcept with or without exceptions.
#pragma once

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include "config.hpp"

#if TENDONSHEATH_EXCEPTIONS
#include <stdexcept>
#endif

namespace tendonsheath {

/// What a failed check calls, with its message, when the core is built without exceptions and
/// no make() is collecting the error; it must not return (std::abort() follows if it does).
/// Not called when exceptions are on: the check throws std::invalid_argument instead.
using ErrorHandler = void (*)(const char* message);

namespace detail {

// the default handler: the message and a newline on stderr (no iostreams)
inline void write_to_stderr(const char* message) {
  std::fputs(message, stderr);
  std::fputc('\n', stderr);
  std::fflush(stderr);
}

inline std::atomic<ErrorHandler>& handler_slot() noexcept {
  static std::atomic<ErrorHandler> handler{nullptr};
  return handler;
}

// the error of one make(): the first failed check's message
struct Capture {
  bool failed = false;
  std::string message;
};

// the make() collecting on this thread (nullptr: none)
inline Capture*& capture_slot() noexcept {
  static TENDONSHEATH_THREAD_LOCAL Capture* capture = nullptr;
  return capture;
}

// Collects the failed checks of one construction on this thread while it lives (make() only).
class CaptureScope {
 public:
  CaptureScope() noexcept : previous_(capture_slot()) { capture_slot() = &capture_; }
  ~CaptureScope() { capture_slot() = previous_; }
  CaptureScope(const CaptureScope&) = delete;
  CaptureScope& operator=(const CaptureScope&) = delete;
  Capture& capture() noexcept { return capture_; }

 private:
  Capture capture_;
  Capture* previous_;
};

// An error no caller can recover from here: thrown, or handed to the handler, then abort.
[[noreturn]] inline void raise_error(const std::string& message) {
#if TENDONSHEATH_EXCEPTIONS
  throw std::invalid_argument(message);
#else
  const ErrorHandler handler = handler_slot().load();
  (handler != nullptr ? handler : write_to_stderr)(message.c_str());
  std::abort();
#endif
}

// A failed check: thrown with exceptions; without them, collected by the make() running on
// this thread (only its first message is kept; the caller goes on to its next guard) or, when
// none is, raised.
inline void report_error(std::string message) {
#if TENDONSHEATH_EXCEPTIONS
  throw std::invalid_argument(message);
#else
  Capture* capture = capture_slot();
  if (capture == nullptr) raise_error(message);
  if (!capture->failed) {
    capture->failed = true;
    capture->message = std::move(message);
  }
#endif
}

// True when a check of the construction make() is running has failed: a constructor returns
// at this guard before it uses its parameters (sizes, indices, allocations). Always false with
// exceptions (the check has thrown), so the guard compiles to nothing there.
#if TENDONSHEATH_EXCEPTIONS
constexpr bool failed() noexcept { return false; }
#else
inline bool failed() noexcept {
  const Capture* capture = capture_slot();
  return capture != nullptr && capture->failed;
}
#endif

}  // namespace detail

/// Replace the error handler (nullptr restores the default, which writes the message to stderr).
/// Only used when the core is built without exceptions; see error_handler.hpp.
/// @param handler called with the message of a failed check made outside make(); must not return
/// @return the handler it replaces (nullptr for the default)
inline ErrorHandler set_error_handler(ErrorHandler handler) noexcept {
  return detail::handler_slot().exchange(handler);
}

}  // namespace tendonsheath
