// What both programs of this folder share (make_cases.cpp, json_cases.cpp): the check that
// the build's mode is the one CMakeLists.txt asked for, the count of failed checks, and the
// same random draws in both builds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

#include <tendonsheath/config.hpp>

#if !defined(EXPECT_EXCEPTIONS) || EXPECT_EXCEPTIONS != TENDONSHEATH_EXCEPTIONS
#error "built in the wrong mode: EXPECT_EXCEPTIONS must equal TENDONSHEATH_EXCEPTIONS"
#endif

namespace no_exceptions {

inline int failures = 0;  // checks that failed

inline void check(bool ok, const std::string& what) {
  if (ok) return;
  ++failures;
  std::fprintf(stderr, "FAILED: %s\n", what.c_str());
}

// splitmix64: the same draws in both builds
struct Rng {
  std::uint64_t s;
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  std::size_t below(std::size_t n) { return static_cast<std::size_t>(next() % n); }
};

}  // namespace no_exceptions
