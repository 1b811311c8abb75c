// The short fuzz run of `make test`: every driver of fuzz_drivers.hpp (the ones `make fuzz`
// runs under libFuzzer) on seeded random byte strings, so a failure reproduces exactly.
// Half of the cases are plain random bytes; the other half favour the extreme and
// non-finite values (their selector bytes are drawn below 32).
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "fuzz_drivers.hpp"

namespace {
namespace fz = tendonsheath::fuzz;

// Cases per driver: the seven together take about 8 s of CPU time (2.2 s of it "listed"; the
// six before it took 12 s at 3000 cases on a machine loaded by other jobs), within make test's
// 30 s for the short run.
constexpr int kCases = 1500;

std::vector<std::uint8_t> random_case(std::mt19937_64& gen, int i) {
  std::uniform_int_distribution<int> len(16, 1200), byte(0, 255), low(0, 31);
  std::vector<std::uint8_t> v(static_cast<std::size_t>(len(gen)));
  const bool extreme = i % 2 == 1;
  for (auto& c : v) c = static_cast<std::uint8_t>(extreme && byte(gen) < 96 ? low(gen) : byte(gen));
  return v;
}

std::string hex(const std::vector<std::uint8_t>& v) {
  static const char* d = "0123456789abcdef";
  std::string s;
  for (std::uint8_t c : v) s += {d[c >> 4], d[c & 15]};
  return s;
}

class SeededFuzz : public ::testing::TestWithParam<int> {};

TEST_P(SeededFuzz, KeepsTheRealTimeContract) {
  const fz::Target& t = fz::targets()[GetParam()];
  std::mt19937_64 gen(20261123u + static_cast<unsigned>(GetParam()));
  for (int i = 0; i < kCases; ++i) {
    const std::vector<std::uint8_t> bytes = random_case(gen, i);
    const fz::Failure f = t.run(bytes.data(), bytes.size());
    ASSERT_EQ(f.rule, nullptr) << t.name << ": " << f.rule << " at operation " << f.op
                               << " of case " << i << "; bytes " << hex(bytes);
  }
}

INSTANTIATE_TEST_SUITE_P(Drivers, SeededFuzz, ::testing::Range(0, 7),
                         [](const ::testing::TestParamInfo<int>& info) {
                           return std::string(fz::targets()[info.param].name);
                         });

// The harness can fail: a driver that breaks its rule is reported (here a stand-in whose
// "output" is NaN for every finite input).
fz::Failure always_nan(const std::uint8_t*, std::size_t) {
  return {"stand-in: non-finite output for a finite input", 0};
}

TEST(SeededFuzzHarness, ReportsABrokenRule) {
  const std::uint8_t bytes[] = {1, 2, 3};
  EXPECT_NE(always_nan(bytes, sizeof bytes).rule, nullptr);
  // and a plant driver on bytes that only step with finite inputs passes
  std::vector<std::uint8_t> calm(600, 200);
  EXPECT_EQ(fz::plants(calm.data(), calm.size()).rule, nullptr);
}
}  // namespace
