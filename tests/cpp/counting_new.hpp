// A replacement global operator new that counts the allocations made while `armed` is set,
// for the tests that check a step() allocates nothing. It defines operator new and delete:
// include it in exactly one source file of a test program (each tests/cpp/test_*.cpp is its
// own program).
#pragma once

#include <atomic>
#include <cstdlib>
#include <new>

namespace {
std::atomic<bool> armed{false};
std::atomic<long> allocations{0};
}  // namespace

// The replacement pair is new -> malloc, delete -> free; GCC's -Wmismatched-new-delete
// cannot see that they match once inlined.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif

void* operator new(std::size_t n) {
  if (armed.load(std::memory_order_relaxed)) allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
