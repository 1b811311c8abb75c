#include <cstdlib>

#include "bindings.hpp"

NB_MODULE(_core, m) {
  m.doc() = "tendonsheath real-time core (C++17), exposed through nanobind";
  // nanobind lists every bound object still alive when the interpreter exits as a leak; a
  // host that keeps objects to its end (pytest's collected items, a user's session) is not
  // one, and its users would read a bug into the list. TENDONSHEATH_LEAK_WARNINGS=1 turns the
  // check on: tests/test_no_leaks.py runs it over a whole workflow.
  nanobind::set_leak_warnings(std::getenv("TENDONSHEATH_LEAK_WARNINGS") != nullptr);
  tsbind::bind_statics(m);
  tsbind::bind_models(m);
  tsbind::bind_compensators(m);
  tsbind::bind_plant(m);
  tsbind::bind_profile(m);
  tsbind::bind_bench(m);
  tsbind::bind_batch(m);
  tsbind::bind_model_inverse(m);
  tsbind::bind_coupled(m);
  tsbind::bind_compensator_list(m);
  tsbind::finish_copy_constructors();
}
