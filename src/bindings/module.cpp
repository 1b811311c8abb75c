#include "bindings.hpp"

NB_MODULE(_core, m) {
  m.doc() = "tendonsheath real-time core (C++17), exposed through nanobind";
  tsbind::bind_statics(m);
  tsbind::bind_models(m);
  tsbind::bind_compensators(m);
  tsbind::bind_models_extended(m);
  tsbind::bind_plant(m);
  tsbind::bind_profile(m);
  tsbind::bind_bench(m);
  tsbind::bind_curve_angle(m);
  tsbind::bind_batch(m);
  tsbind::bind_model_inverse(m);
  tsbind::bind_coupled(m);
}
