// An encoder-like sensor: y = quantise(x + noise), with Gaussian noise of
// standard deviation noise_std and quantisation to multiples of resolution
// (0: none). The noise comes from a seeded splitmix64 generator and a
// Box-Muller transform, so a seed gives the same sequence on every platform.
#pragma once

#include <cmath>
#include <cstdint>

#include "../status.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// Parameters of Sensor (validated by its constructor).
struct SensorParams {
  double resolution = 0.0;  ///< quantisation step (same unit as x), 0 = none
  double noise_std = 0.0;   ///< Gaussian noise standard deviation
  std::uint64_t seed = 0;  ///< seed of the noise generator: a seed gives the same sequence on every platform
};

/// @brief An encoder-like sensor: y = quantise(x + noise), Gaussian noise of standard deviation
/// noise_std and quantisation to multiples of resolution (0: none).
///
/// The noise comes from a seeded splitmix64 generator and a Box-Muller transform. measure() is
/// noexcept and allocates nothing; reset() restarts the noise sequence from the seed.
class Sensor {
  static constexpr double kPi = 3.14159265358979323846;

 public:
  /// The parameter struct its constructor takes.
  using Params = SensorParams;

  /// @param p the parameters; throws std::invalid_argument when resolution or noise_std is not >= 0.
  explicit Sensor(const Params& p) : p_(p) {
    require_non_negative(p.resolution, "Sensor", "resolution");
    require_non_negative(p.noise_std, "Sensor", "noise_std");
    reset();
  }
  /// The parameters it was built with.
  const Params& params() const noexcept { return p_; }
  /// The last reading's status: held_nonfinite_input when x was not finite.
  Status status() const noexcept { return held_ ? Status::held_nonfinite_input : Status::ok; }

  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    state_ = p_.seed;
    have_spare_ = false;
    last_ = 0.0;
  }

  /// One reading of x; a non-finite x repeats the last reading.
  /// @param x the true value
  /// @return the reading: x plus noise, quantised (the last reading when x is not finite)
  double measure(double x) noexcept {
    held_ = !std::isfinite(x);
    if (held_) return last_;
    double y = x;
    if (p_.noise_std > 0.0) y += p_.noise_std * gaussian();
    // past 2^52 steps y / resolution is an integer already (and it may overflow): kept
    if (p_.resolution > 0.0 && std::fabs(y / p_.resolution) < 4503599627370496.0)
      y = p_.resolution * std::round(y / p_.resolution);
    last_ = y;
    return y;
  }

 private:
  std::uint64_t next() noexcept {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform01() noexcept {  // in (0, 1)
    return (static_cast<double>(next() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  }
  double gaussian() noexcept {
    if (have_spare_) {
      have_spare_ = false;
      return spare_;
    }
    const double u1 = uniform01(), u2 = uniform01();
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * kPi * u2);
    have_spare_ = true;
    return r * std::cos(2.0 * kPi * u2);
  }

  Params p_;
  std::uint64_t state_ = 0;
  double spare_ = 0.0;
  double last_ = 0.0;
  bool have_spare_ = false;
  bool held_ = false;
};

}  // namespace tendonsheath
