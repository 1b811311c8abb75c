// Inverse of a model with a measured load (python: tendonsheath.models.Loaded), one control
// cycle at a time: the load measured (or estimated from the motor's current or torque) is
// given to every step.
//
// Loaded:  y = base(play_r(L)(x)) + gain L,  r(L) = slack exp(-|L| / slack_load) + friction |L|
// Inverse: z = base^-1(y_d - gain L)                (any inverse of the base: a template part)
//          d = clip(d + (z - z_prev) / switch_travel, -1, 1)   (the play's direction, smoothed)
//          x = z + r(L) d
// A non-finite load holds the last finite one. step() is noexcept and allocates nothing.
#pragma once

#include <algorithm>
#include <cmath>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// The load terms of a Loaded model and the play inverse's switch travel.
struct LoadTerms {
  double gain = 0.0;            ///< output per unit load (the tendon's compliance), any sign
  double slack = 0.0;           ///< the play's half-width at zero load (input unit), >= 0
  double slack_load = 1.0;      ///< the load over which the slack closes (load unit), > 0
  double friction = 0.0;        ///< the play's growth per unit |load|, >= 0
  double switch_travel = 1e-3;  ///< base-input travel of the play's direction switch, > 0

  /// Throws std::invalid_argument naming the first term out of range.
  void validate(const char* where) const {
    require_finite(gain, where, "gain");
    require_non_negative(slack, where, "slack");
    require_positive(slack_load, where, "slack_load");
    require_non_negative(friction, where, "friction");
    require_positive(switch_travel, where, "switch_travel");
  }

  /// The play's half-width r(load) = slack exp(-|load| / slack_load) + friction |load|.
  double radius(double load) const noexcept {
    const double a = std::fabs(load);
    return slack * std::exp(-a / slack_load) + friction * a;
  }
};

/// The play inverse alone: x = z + r(load) d, d the smoothed direction of travel of z.
class LoadPlayInverse {
 public:
  /// @param terms the load terms; throws std::invalid_argument naming one out of range.
  explicit LoadPlayInverse(const LoadTerms& terms) : t_(terms) { t_.validate("LoadPlayInverse"); }

  /// The terms it was built with.
  const LoadTerms& terms() const noexcept { return t_; }

  /// Start afresh: direction 0 (mid-band), no previous z, load 0.
  void reset() noexcept {
    started_ = false;
    d_ = 0.0;
    z_prev_ = 0.0;
    load_ = 0.0;
  }

  /// The load to use this cycle: ``load`` when finite, else the last finite one.
  double held_load(double load) noexcept {
    if (std::isfinite(load)) load_ = load;
    return load_;
  }

  /// The command for the base input z under the load (a non-finite load holds the last).
  double step(double z, double load) noexcept {
    const double l = held_load(load);
    if (!std::isfinite(z)) z = z_prev_;
    if (started_) d_ = std::clamp(d_ + (z - z_prev_) / t_.switch_travel, -1.0, 1.0);
    started_ = true;
    z_prev_ = z;
    return z + t_.radius(l) * d_;
  }

 private:
  LoadTerms t_;
  bool started_ = false;
  double d_ = 0.0;
  double z_prev_ = 0.0;
  double load_ = 0.0;
};

/// @brief A base model's inverse fed the measured load: z = Inverse(y_d - gain L), then the
/// load's play inverted. ``Inverse`` is any compensator with ``double step(double y_d, double
/// dt) noexcept`` and ``void reset() noexcept`` (e.g. BacklashInverseFeedforward).
template <class Inverse>
class LoadCompensated {
 public:
  /// @param inverse the base's inverse (copied); @param terms the load terms (validated).
  LoadCompensated(const Inverse& inverse, const LoadTerms& terms)
      : inverse_(inverse), play_(terms) {}

  /// The base's inverse.
  const Inverse& inverse() const noexcept { return inverse_; }
  /// The load terms.
  const LoadTerms& terms() const noexcept { return play_.terms(); }

  /// Start afresh (the base inverse's state and the play's).
  void reset() noexcept {
    inverse_.reset();
    play_.reset();
  }

  /// The last step's status: the base inverse's (an Inverse with ``Status status() const
  /// noexcept``; e.g. a ModelInverse's out_of_range or saturated).
  Status status() const noexcept { return inverse_.status(); }

  /// One control cycle: the command for the desired output y_d under the load measured now.
  double step(double y_d, double dt, double load) noexcept {
    const double l = play_.held_load(load);
    const double z = inverse_.step(y_d - play_.terms().gain * l, dt);
    return play_.step(z, l);
  }

 private:
  Inverse inverse_;
  LoadPlayInverse play_;
};

}  // namespace tendonsheath
