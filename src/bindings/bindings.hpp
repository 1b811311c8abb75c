// Shared helpers of the nanobind extension: every bind_*.cpp file registers
// one concept on the module.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <tendonsheath/plant/simulate_plant.hpp>

namespace tsbind {

namespace nb = nanobind;

using InArray = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using OutArray = nb::ndarray<nb::numpy, double, nb::ndim<1>>;
using OutMatrix = nb::ndarray<nb::numpy, double, nb::ndim<2>>;
using InMatrix = nb::ndarray<const double, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
using InIndex = nb::ndarray<const std::uint64_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;

// Two series of one trajectory must have the same number of samples.
inline void check_lengths(std::size_t a, std::size_t b, const char* what, const char* where) {
  if (a != b)
    throw std::invalid_argument(std::string(where) + ": " + what + " has " + std::to_string(b) +
                                " samples, the trajectory has " + std::to_string(a));
}

// A fresh NumPy array of n doubles that owns its buffer.
inline std::pair<OutArray, double*> new_array(std::size_t n) {
  double* data = new double[n > 0 ? n : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return {OutArray(data, {n}, owner), data};
}

// A fresh NumPy array of n bytes (per-sample Status flags) that owns its buffer.
using OutBytes = nb::ndarray<nb::numpy, std::uint8_t, nb::ndim<1>>;
inline std::pair<OutBytes, std::uint8_t*> new_bytes(std::size_t n) {
  auto* data = new std::uint8_t[n > 0 ? n : 1]();
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<std::uint8_t*>(p); });
  return {OutBytes(data, {n}, owner), data};
}

inline std::pair<OutMatrix, double*> new_matrix(std::size_t rows, std::size_t cols) {
  double* data = new double[rows * cols > 0 ? rows * cols : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return {OutMatrix(data, {rows, cols}, owner), data};
}

// A route-change schedule from (sample indices, node-angle rows); `storage` keeps the indices.
inline tendonsheath::RouteSchedule to_schedule(const std::optional<InIndex>& sidx,
                                               const std::optional<InMatrix>& sang,
                                               std::vector<std::size_t>& storage, const char* name) {
  tendonsheath::RouteSchedule sched;
  if (!sidx || !sang) return sched;
  if (sang->shape(0) != sidx->shape(0))
    throw std::invalid_argument(std::string(name) + ": route schedule sizes differ");
  storage.resize(sidx->shape(0));
  for (std::size_t i = 0; i < storage.size(); ++i)
    storage[i] = static_cast<std::size_t>(sidx->data()[i]);
  sched.index = storage.data();
  sched.angles = sang->data();
  sched.count = storage.size();
  sched.width = sang->shape(1);
  return sched;
}

// The T(other) constructors bind_copy queued, defined by finish_copy_constructors() once every
// class has its own constructors (so that a class's signature shows those first).
inline std::vector<std::function<void()>>& pending_copy_constructors() {
  static std::vector<std::function<void()>> pending;
  return pending;
}

inline void finish_copy_constructors() {
  for (auto& define : pending_copy_constructors()) define();
  pending_copy_constructors().clear();
}

// copy.copy and copy.deepcopy of a streaming engine, and T(other): a snapshot of its whole state
// (the python-control systems of tendonsheath.control step from saved snapshots; a Python class
// built on T copies itself with T(other), as its __init__ runs once).
template <class Cls>
std::decay_t<Cls> bind_copy(Cls&& cls) {
  using T = typename std::decay_t<Cls>::Type;
  if constexpr (!std::is_aggregate_v<T>)
    pending_copy_constructors().push_back([cls]() mutable {
      cls.def(nb::init<const T&>(), nb::arg("other"),
              "A copy of ``other``: its parameters and its exact streaming state.");
    });
  cls.def("__copy__", [](const T& self) { return T(self); });
  cls.def("__deepcopy__", [](const T& self, nb::handle) { return T(self); }, nb::arg("memo"));
  return std::forward<Cls>(cls);
}

void bind_statics(nb::module_& m);
void bind_models(nb::module_& m);
void bind_compensators(nb::module_& m);
void bind_plant(nb::module_& m);
void bind_profile(nb::module_& m);
void bind_bench(nb::module_& m);
// CurveAngleModel (two inputs), bound where bind_models binds the model list
void bind_curve_angle_model(nb::module_& m);
void bind_batch(nb::module_& m);
void bind_model_inverse(nb::module_& m);
void bind_coupled(nb::module_& m);
// after every hand binding: the compensators of the list that have none (bind_compensators.cpp)
void bind_compensator_list(nb::module_& m);

}  // namespace tsbind
