// Shared helpers of the nanobind extension: every bind_*.cpp file registers
// one concept on the module.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <utility>

namespace tsbind {

namespace nb = nanobind;

using InArray = nb::ndarray<const double, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using OutArray = nb::ndarray<nb::numpy, double, nb::ndim<1>>;
using OutMatrix = nb::ndarray<nb::numpy, double, nb::ndim<2>>;

// A fresh NumPy array of n doubles that owns its buffer.
inline std::pair<OutArray, double*> new_array(std::size_t n) {
  double* data = new double[n > 0 ? n : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return {OutArray(data, {n}, owner), data};
}

inline std::pair<OutMatrix, double*> new_matrix(std::size_t rows, std::size_t cols) {
  double* data = new double[rows * cols > 0 ? rows * cols : 1];
  nb::capsule owner(data, [](void* p) noexcept { delete[] static_cast<double*>(p); });
  return {OutMatrix(data, {rows, cols}, owner), data};
}

void bind_models(nb::module_& m);
void bind_curve_angle(nb::module_& m);
void bind_batch(nb::module_& m);

}  // namespace tsbind
