// Batch simulation of a plant (optionally behind a motor and with a sensor),
// with route changes given as a compact schedule: the whole loop in C++.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "../validate.hpp"
#include "motor.hpp"
#include "sensor.hpp"

namespace tendonsheath {

/// Route changes: before sample index[i] the plant's node angles become row i
/// of `angles` (count rows of `width` values, row-major).
struct RouteSchedule {
  const std::size_t* index = nullptr;  ///< count sample indices, strictly increasing
  const double* angles = nullptr;  ///< count x width node angles, rad, finite and >= 0
  std::size_t count = 0;  ///< the number of route changes (0: none)
  std::size_t width = 0;  ///< node angles per change: the plant's n_node_angles()
};

/// Where simulate_plant() writes each sample's record: n values per array; q_out is required, a
/// nullptr array is not written.
struct PlantTrace {
  double* q_out = nullptr;           ///< plant output per sample (required)
  double* q_in = nullptr;            ///< plant input (motor position) per sample, optional
  unsigned char* slack = nullptr;    ///< slack flag per sample, optional
  double* min_tension = nullptr;     ///< smallest tension per sample, optional
  double* measured = nullptr;        ///< sensor reading of q_out per sample, optional
  double* q_motor = nullptr;         ///< motor shaft angle (its encoder) per sample, optional
  unsigned char* status = nullptr;   ///< Status flags of plant, motor and sensor per sample, optional
};

/// Throws std::invalid_argument (message starting with `where`) unless schedule s fits the plant
/// and n samples: rows of plant.n_node_angles() finite angles >= 0 at increasing indices < n.
template <class Plant>
void check_schedule(const Plant& plant, const RouteSchedule& s, std::size_t n, const char* where) {
  if (s.count == 0) return;
  require(s.width == plant.n_node_angles(), where, "route schedule rows hold ", s.width,
          " node angles, the plant needs ", plant.n_node_angles());
  for (std::size_t i = 0; i < s.count; ++i) {
    require(s.index[i] < n, where, "route schedule index ", s.index[i], " is beyond the input");
    require(i == 0 || s.index[i] > s.index[i - 1], where,
            "route schedule indices must be strictly increasing");
    for (std::size_t j = 0; j < s.width; ++j) {
      const double a = s.angles[i * s.width + j];
      require(std::isfinite(a) && a >= 0.0, where, "route schedule angle [", i, ", ", j,
              "] must be finite and >= 0 (got ", a, ")");
    }
  }
}

/// Starts from plant.reset() (at rest, current route); t may be nullptr when
/// there is no motor and the load has no damper (dt = 0).
/// Validates its inputs first (std::invalid_argument naming the problem), then runs the loop.
/// @tparam Plant SingleTendonPlant, PullPullPlant or ContinuumPlant
/// @param plant the plant, reset first
/// @param motor the motor between the input and the plant, or nullptr (u is the plant input)
/// @param sensor the output sensor, or nullptr (read only when out.measured is given)
/// @param t the n sample times, s, finite and increasing, or nullptr (see above)
/// @param u the n inputs (motor commands, or plant inputs without a motor)
/// @param n the number of samples, >= 1
/// @param sched the route changes
/// @param out where each sample's record goes
/// @param where the name that starts an error message
template <class Plant>
void simulate_plant(Plant& plant, Motor* motor, Sensor* sensor, const double* t, const double* u,
                    std::size_t n, const RouteSchedule& sched, const PlantTrace& out,
                    const char* where) {
  check_series(t, u, n, where);
  require(motor == nullptr || t != nullptr, where, "a motor needs the time vector t");
  require(sensor == nullptr || sensor->params().delay == 0.0 || t != nullptr, where,
          "a sensor with a delay needs the time vector t");
  check_schedule(plant, sched, n, where);
  plant.reset();
  if (motor) motor->reset();
  if (sensor) sensor->reset();
  std::size_t next = 0;
  for (std::size_t k = 0; k < n; ++k) {
    while (next < sched.count && sched.index[next] == k) {
      plant.set_node_angles(sched.angles + next * sched.width);
      ++next;
    }
    const double dt = (k == 0 || t == nullptr) ? 0.0 : t[k] - t[k - 1];
    const double qin = motor ? motor->step(u[k], dt, plant.drive_reaction()) : u[k];
    const double q = plant.step(qin, dt);
    out.q_out[k] = q;
    if (out.q_in) out.q_in[k] = qin;
    if (out.q_motor) out.q_motor[k] = motor ? motor->position() : qin;
    if (out.slack) out.slack[k] = plant.slack() ? 1 : 0;
    if (out.min_tension) out.min_tension[k] = plant.min_tension();
    if (out.measured) out.measured[k] = sensor ? sensor->measure(q, dt) : q;
    if (out.status) {
      Status s = plant.status();
      if (motor) s |= motor->status();
      if (sensor && out.measured) s |= sensor->status();
      out.status[k] = static_cast<unsigned char>(s);
    }
  }
}

}  // namespace tendonsheath
