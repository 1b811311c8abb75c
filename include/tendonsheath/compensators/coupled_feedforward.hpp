// The inverse of a coupled-joints model (Python's models.Coupled and
// compensate.CoupledFeedforward): joint i's angle is H_i(x_i) + sum_j C[i][j] y_j, so with every
// joint on its desired angle joint i's own model must give h_i = y_d,i - sum_j C[i][j] y_d,j,
// and each cycle x_i = H_i^-1(h_i) (each H_i^-1 a ModelInverse). The coupling acts through the
// other joints' angles (the idlers of their cables turn with them), so it is taken from the
// desired angles, not from the other joints' commands.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "../status.hpp"
#include "../validate.hpp"
#include "model_inverse.hpp"

namespace tendonsheath {

/// @brief Feedforward of J coupled joints: one ModelInverse per joint and the coupling matrix C
/// (row-major, J x J, zero diagonal, I - C invertible). Construction validates and allocates;
/// step() is noexcept, allocates nothing and does O(J^2) work plus each joint's inverse.
class CoupledFeedforward {
 public:
  /// @param joints each joint's inverse (of its own model H_i)
  /// @param coupling C, row-major J x J: joint i's angle per radian of joint j
  /// @throws std::invalid_argument no joints, C of the wrong size, not finite, with a non-zero
  ///         diagonal, or with I - C singular
  CoupledFeedforward(std::vector<ModelInverse> joints, std::vector<double> coupling)
      : joints_(std::move(joints)), coupling_(std::move(coupling)) {
    const std::size_t n = joints_.size();
    require(n > 0, "CoupledFeedforward", "give at least one joint");
    require(coupling_.size() == n * n, "CoupledFeedforward", "the coupling must hold ", n * n,
            " values (", n, " x ", n, ", row-major; got ", coupling_.size(), ")");
    if (detail::failed()) return;  // without exceptions, in make(): the coupling is not indexed
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        const double c = coupling_[i * n + j];
        require(std::isfinite(c), "CoupledFeedforward", "coupling[", i, "][", j,
                "] must be finite (got ", c, ")");
        require(i != j || c == 0.0, "CoupledFeedforward", "the coupling's diagonal must be zero",
                " (a joint's own gain is its model's; got coupling[", i, "][", i, "] = ", c, ")");
      }
    }
    if (detail::failed()) return;  // without exceptions, in make(): no solve with bad values
    require(!singular(coupling_, n), "CoupledFeedforward",
            "I - coupling is singular (the joints' angles are undefined)");
    targets_.assign(n, 0.0);
    last_.assign(n, 0.0);
  }

  /// The number of joints J.
  std::size_t joints() const noexcept { return joints_.size(); }
  /// C[i][j].
  double coupling(std::size_t i, std::size_t j) const noexcept {
    return coupling_[i * joints_.size() + j];
  }
  /// Joint i's inverse.
  const ModelInverse& joint(std::size_t i) const noexcept { return joints_[i]; }

  /// Every joint's inverse back to its initial state; the last desired angles back to 0.
  void reset() noexcept {
    for (auto& j : joints_) j.reset();
    for (auto& v : last_) v = 0.0;
  }

  /// One control cycle.
  /// @param y_d J desired angles; a non-finite one holds that joint's command, and the other
  ///        joints' coupling terms use its last finite value
  /// @param u J commands (written)
  /// @param dt the time since the previous cycle, s
  void step(const double* y_d, double* u, double dt) noexcept {
    const std::size_t n = joints_.size();
    for (std::size_t j = 0; j < n; ++j) {
      if (std::isfinite(y_d[j])) last_[j] = y_d[j];
    }
    for (std::size_t i = 0; i < n; ++i) {
      double h = y_d[i];
      for (std::size_t j = 0; j < n; ++j) h -= coupling_[i * n + j] * last_[j];
      targets_[i] = h;  // NaN where y_d[i] is: joint i's inverse then holds
    }
    for (std::size_t i = 0; i < n; ++i) u[i] = joints_[i].step(targets_[i], dt);
  }

  /// The last cycle's status: every joint's flags together.
  Status status() const noexcept {
    Status s = Status::ok;
    for (const auto& j : joints_) s = s | j.status();
    return s;
  }

  /// The last cycle's targets of the joints' own models, h = y_d - C y_d.
  const std::vector<double>& targets() const noexcept { return targets_; }

 private:
  // |det(I - C)| < 1e-9 by Gaussian elimination with partial pivoting (construction only)
  static bool singular(const std::vector<double>& c, std::size_t n) {
    std::vector<double> a(n * n);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) a[i * n + j] = (i == j ? 1.0 : 0.0) - c[i * n + j];
    double det = 1.0;
    for (std::size_t k = 0; k < n; ++k) {
      std::size_t p = k;
      for (std::size_t i = k + 1; i < n; ++i)
        if (std::fabs(a[i * n + k]) > std::fabs(a[p * n + k])) p = i;
      if (a[p * n + k] == 0.0) return true;
      if (p != k) {
        for (std::size_t j = 0; j < n; ++j) std::swap(a[k * n + j], a[p * n + j]);
        det = -det;
      }
      det *= a[k * n + k];
      for (std::size_t i = k + 1; i < n; ++i) {
        const double f = a[i * n + k] / a[k * n + k];
        for (std::size_t j = k; j < n; ++j) a[i * n + j] -= f * a[k * n + j];
      }
    }
    return std::fabs(det) < 1e-9;
  }

  std::vector<ModelInverse> joints_;
  std::vector<double> coupling_;
  std::vector<double> targets_;
  std::vector<double> last_;
};

}  // namespace tendonsheath
