// Build configuration of the core, detected from the compiler.
//
// TENDONSHEATH_EXCEPTIONS is 1 when C++ exceptions are enabled (the default of every compiler)
// and 0 when the code is built without them (g++/clang++ -fno-exceptions, as embedded and many
// real-time targets build). With 1 a failed parameter check throws std::invalid_argument; with 0
// it is reported through tendonsheath::make() (result.hpp) or the error handler
// (error_handler.hpp). Define it to 0 yourself to take the exception-free path with exceptions
// on; every translation unit of a program must then see the same value.
//
// TENDONSHEATH_THREAD_LOCAL is the storage of the slot in which make() collects a failed check:
// thread_local by default; define it empty for a single-threaded target whose toolchain has no
// thread-local storage.
#pragma once

#ifndef TENDONSHEATH_EXCEPTIONS
#if defined(__cpp_exceptions) || defined(__EXCEPTIONS) || defined(_CPPUNWIND)
#define TENDONSHEATH_EXCEPTIONS 1
#else
#define TENDONSHEATH_EXCEPTIONS 0
#endif
#endif

#ifndef TENDONSHEATH_THREAD_LOCAL
#define TENDONSHEATH_THREAD_LOCAL thread_local
#endif
