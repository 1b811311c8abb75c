// libFuzzer entry point of one driver of fuzz_drivers.hpp, chosen at compile time with
// -DTENDONSHEATH_FUZZ_TARGET=<family> (plants, motor, sensor, models, inverses, compensators,
// listed).
// Built and run by `make fuzz`; a broken rule aborts with the rule and the operation index,
// and libFuzzer writes the reproducing input (crash-*).
#include <cstdio>
#include <cstdlib>

#include "fuzz_drivers.hpp"

#ifndef TENDONSHEATH_FUZZ_TARGET
#error "define TENDONSHEATH_FUZZ_TARGET"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const tendonsheath::fuzz::Failure f = tendonsheath::fuzz::TENDONSHEATH_FUZZ_TARGET(data, size);
  if (f.rule != nullptr) {
    std::fprintf(stderr, "fuzz: %s (operation %ld)\n", f.rule, f.op);
    std::abort();
  }
  return 0;
}
