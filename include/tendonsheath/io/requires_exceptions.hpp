// The optional JSON loaders (tendonsheath/io/json*.hpp) report a bad file by throwing: they
// refuse to build without C++ exceptions, saying what to use instead.
#pragma once

#include "../config.hpp"

#if !TENDONSHEATH_EXCEPTIONS
#error "tendonsheath/io/json.hpp needs C++ exceptions: it reports a bad file by throwing \
std::invalid_argument, and nlohmann/json reports parse and type errors by throwing. Without \
exceptions, export the compensator to a header of constexpr parameters on a host \
(tendonsheath export FILE --cpp OUT.hpp) and build it with that header's make_compensator(), \
which returns a tendonsheath::Result (docs/cpp-without-exceptions.md)."
#endif
