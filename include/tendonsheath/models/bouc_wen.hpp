// Classic Bouc-Wen hysteresis as a rate-independent input-output model:
//
//   dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n
//   y  = alpha x + (1 - alpha) k z
//
// Bounded-input bounded-state requires beta > 0 and |gamma| <= beta, so that
// |z| <= z_u = (A / (beta + gamma))^(1/n). z is integrated in x with RK4.
#pragma once

#include <cmath>
#include <cstddef>

#include "../status.hpp"
#include "../validate.hpp"
#include "bouc_wen_backlash.hpp"
#include "power.hpp"
#include "../param_table.hpp"

namespace tendonsheath {

/// Parameters of BoucWen (validated by its constructor).
struct BoucWenParams {
  double A = 1.0;  ///< amplitude of the hysteretic state's rate, > 0
  double beta = 0.5;  ///< shape parameter, > 0
  double gamma = 0.5;  ///< shape parameter, |gamma| <= beta (bounded state)
  double n = 1.0;  ///< sharpness of the transitions, >= 1
  double alpha = 0.5;  ///< share of the linear (elastic) path, in [0, 1] (A is the amplitude)
  double k = 1.0;  ///< gain of the hysteretic path
  double max_step = 0.05;  ///< largest change of z / z_u per RK4 sub-step
  int max_substeps = 256;  ///< most RK4 sub-steps in one step(), >= 1 (bounds its work)

  /// How many identifiable parameters assign() reads: the table's Role::parameter rows
  /// (checked against it below the table).
  static constexpr std::size_t vector_size = 6;
  /// Set the identifiable parameters from `v[0..vector_size)`, in the order of the table's
  /// parameter rows (the Python param_names); the options are kept.
  void assign(const double* v) noexcept;
};

/// The parameter table of BoucWenParams (param_table.hpp): unit, range and doc of each field.
template <>
struct ParamTable<BoucWenParams> {
  static constexpr const char* owner = "BoucWen";  ///< the class its constructor takes it
  static constexpr bool checked_from_table = true;  ///< its constructor checks the single-field bounds with validate_fields()
  /// The rows, in the order of the struct and of the constructor's checks.
  static constexpr auto fields = std::make_tuple(
      param("A", &BoucWenParams::A, "", positive(),
            "amplitude of the hysteretic state's rate"),
      param("beta", &BoucWenParams::beta, "", positive(),
            "shape parameter"),
      param("gamma", &BoucWenParams::gamma, "", finite(),
            "shape parameter, |gamma| <= beta and beta + gamma > 0 (bounded state)"),
      param("n", &BoucWenParams::n, "", at_least(1.0),
            "sharpness of the transitions"),
      param("alpha", &BoucWenParams::alpha, "", in_range(0.0, 1.0),
            "share of the linear (elastic) path"),
      param("k", &BoucWenParams::k, "output/input", finite(),
            "gain of the hysteretic path"),
      option("max_step", &BoucWenParams::max_step, "", positive(),
            "largest change of z / z_u per RK4 sub-step"),
      option("max_substeps", &BoucWenParams::max_substeps, "", documented(1, true, kInf, false),
            "most RK4 sub-steps in one step() (bounds its work)"));
};

static_assert(BoucWenParams::vector_size == parameter_count<BoucWenParams>(),
              "vector_size is the number of the table's parameter rows");
inline void BoucWenParams::assign(const double* v) noexcept { assign_parameters(*this, v); }

/// @brief Classic Bouc-Wen hysteresis as a rate-independent input-output model.
///
/// dz = A dx - beta |dx| |z|^(n-1) z - gamma dx |z|^n and y = alpha x + (1 - alpha) k z, with z
/// integrated in x by RK4 (at most max_substeps sub-steps a step). With beta > 0 and
/// |gamma| <= beta the state stays within z_ultimate().
class BoucWen {
 public:
  /// The parameter struct its constructor takes.
  using Params = BoucWenParams;
  /// True when the output depends only on the input's path, not on its timing (step() ignores dt).
  static constexpr bool rate_independent = true;

  /// @param p the parameters; throws std::invalid_argument naming the first one out of range.
  explicit BoucWen(const Params& p) : p_(p) {
    const char* w = "BoucWen";
    validate_fields(p, w, "A", "gamma");  // from ParamTable<BoucWenParams>
    require(std::fabs(p.gamma) <= p.beta, w,
            "|gamma| must be <= beta for a bounded hysteretic state (got beta=", p.beta,
            ", gamma=", p.gamma, ")");
    require(p.beta + p.gamma > 0.0, w, "beta + gamma must be > 0");
    validate_fields(p, w, "n", "max_step");
    require(p.max_substeps >= 1, w, "max_substeps must be >= 1");
    if (detail::failed()) return;  // without exceptions, in make(): nothing derived from bad values
    derive();
  }

  /// True when p passes the constructor's checks (no exception, no allocation).
  static bool valid(const Params& p) noexcept {
    return std::isfinite(p.A) && p.A > 0.0 && std::isfinite(p.beta) && p.beta > 0.0 &&
           std::isfinite(p.gamma) && std::fabs(p.gamma) <= p.beta && p.beta + p.gamma > 0.0 &&
           std::isfinite(p.n) && p.n >= 1.0 && p.alpha >= 0.0 && p.alpha <= 1.0 &&
           std::isfinite(p.k) && std::isfinite(p.max_step) && p.max_step > 0.0 &&
           p.max_substeps >= 1;
  }
  /// New parameters, the state (input, z) kept: for parameters that follow the route.
  /// @param p the new parameters
  /// @return false (and nothing changed) when p is not valid()
  bool set_params(const Params& p) noexcept {
    if (!valid(p)) return false;
    p_ = p;
    derive();
    z_ = clamp_z(z_);
    return true;
  }

  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The bound of the hysteretic state: z_u = (A / (beta + gamma))^(1/n).
  double z_ultimate() const noexcept { return z_u_; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    initialised_ = false;
    z_ = 0.0;
  }

  /// @brief One sample: move the input to x and return the output y.
  /// @param x the input; a non-finite x is ignored and the last output held (0 before the first step)
  /// @return y = alpha x + (1 - alpha) k z; the first call after reset() starts with z = 0 at x
  double step(double x, double /*dt*/ = 0.0) noexcept {
    held_ = !std::isfinite(x);
    kept_ = false;
    if (held_) return initialised_ ? y_ : 0.0;
    if (!initialised_) {
      x_ = x;
      initialised_ = true;
    } else {
      const double dx = x - x_;
      if (dx != 0.0) integrate(std::fabs(dx), dx > 0.0 ? 1.0 : -1.0);
      x_ = x;
    }
    y_ = p_.alpha * x_ + (1.0 - p_.alpha) * p_.k * z_;
    return y_;
  }

  /// The output of the last step().
  double output() const noexcept { return y_; }
  /// The last step's status: held_nonfinite_input (input not finite), not_converged (the
  /// integration overflowed and the state was kept).
  Status status() const noexcept {
    Status s = held_ ? Status::held_nonfinite_input : Status::ok;
    return kept_ ? s | Status::not_converged : s;
  }
  /// The hysteretic state z.
  double state() const noexcept { return z_; }

 private:
  double rate(double z, double s) const noexcept {
    const double az = std::fabs(z);
    const double q = pow_nm1_(az);
    return p_.A * s - p_.beta * q * z - p_.gamma * s * q * az;
  }
  double clamp_z(double z) const noexcept { return z > z_u_ ? z_u_ : (z < -z_u_ ? -z_u_ : z); }
  void derive() noexcept {
    pow_nm1_ = detail::AbsPower(p_.n - 1.0);
    z_u_ = std::pow(p_.A / (p_.beta + p_.gamma), 1.0 / p_.n);
  }

  void integrate(double travel, double s) noexcept {
    const int m = detail::substeps_for(p_.A * travel / z_u_, p_.max_step, p_.max_substeps);
    const double h = travel / m;
    double z = z_;
    for (int i = 0; i < m; ++i) {
      const double k1 = rate(z, s);
      const double k2 = rate(clamp_z(z + 0.5 * h * k1), s);
      const double k3 = rate(clamp_z(z + 0.5 * h * k2), s);
      const double k4 = rate(clamp_z(z + h * k3), s);
      z = clamp_z(z + h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0);
    }
    kept_ = !std::isfinite(z);
    if (!kept_) z_ = z;  // an overflowing jump keeps the old state
  }

  Params p_;
  detail::AbsPower pow_nm1_{};
  double z_u_ = 1.0;
  double x_ = 0.0, z_ = 0.0, y_ = 0.0;
  bool initialised_ = false;
  bool held_ = false, kept_ = false;
};

}  // namespace tendonsheath
