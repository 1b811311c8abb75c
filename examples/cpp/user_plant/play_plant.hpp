// A user's own plant: a play (backlash) of half-width h between the input and the output, the
// C++ twin of the pure-Python PlayPlant in tests/test_bench_plants.py. It includes nothing from
// nanobind: the same class can run in a robot's real-time simulation.
//
// At rest the output is 0; a step moves it only as far as the input pulls it out of the band
// [input - h, input + h].
#pragma once

#include <cmath>
#include <stdexcept>

class PlayPlant {
 public:
  explicit PlayPlant(double half_width = 0.05) : h_(half_width) {
    if (!(std::isfinite(h_) && h_ >= 0.0))
      throw std::invalid_argument("PlayPlant: half_width must be finite and >= 0");
  }

  // the contract of tendonsheath/bench/erased_plant.hpp: reset, step(input, dt), output
  void reset() noexcept { x_ = y_ = 0.0; }
  double step(double input, double /*dt*/) noexcept {
    if (!std::isfinite(input)) return y_;  // a non-finite input holds the output
    x_ = input;
    if (x_ - y_ > h_) y_ = x_ - h_;
    if (y_ - x_ > h_) y_ = x_ + h_;
    return y_;
  }
  double output() const noexcept { return y_; }
  double input() const noexcept { return x_; }
  double half_width() const noexcept { return h_; }

 private:
  double h_;
  double x_ = 0.0;
  double y_ = 0.0;
};
