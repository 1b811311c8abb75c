// The virtual bench: controller -> motor -> plant -> sensor -> controller at a
// fixed rate, the whole loop in C++.
//
// At sample k (dt = t_k - t_{k-1}): route changes due at k are applied (to the
// plant, and as shape integrals to a controller that follows the route), the
// controller computes u_k from y_d[k], the last measurement and the motor
// position, the motor advances under u_k, the plant under the motor position,
// and the sensor reads the new output (NaN where a dropout mask is set).
#pragma once

#include <cmath>
#include <cstddef>

#include "../compensators/adaptive_controller.hpp"
#include "../compensators/curve_angle_feedforward.hpp"
#include "../physics/pull_pull_statics.hpp"
#include "../plant/motor.hpp"
#include "../plant/sensor.hpp"
#include "../plant/simulate_plant.hpp"
#include "../validate.hpp"

namespace tendonsheath {

/// Route shapes seen by a controller, at the same indices as the plant's RouteSchedule.
struct ShapeSchedule {
  const ShapeIntegrals* shapes = nullptr;  ///< one per route change, or nullptr
};

struct ClosedLoopTrace {
  double* output = nullptr;         ///< true distal output per sample (required)
  double* measured = nullptr;       ///< what the sensor reported (NaN in dropouts)
  double* command = nullptr;        ///< controller output (motor angle or torque)
  double* motor = nullptr;          ///< motor shaft position (its encoder; the pulley lags it by
                                    /// the gear play when the motor has gear backlash)
  unsigned char* slack = nullptr;   ///< slack flag
  unsigned char* fallback = nullptr;  ///< controller in its fallback mode
  unsigned char* status = nullptr;  ///< Status flags of controller, motor, plant and sensor
};

/// Controllers as the loop sees them.
struct OpenLoop {  // uncompensated: the kinematic motor angle for the desired output
  double gain = 1.0;
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept {}
  void on_shape(const ShapeIntegrals&) noexcept {}
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return Status::ok; }
  double command(double y_d, double, double, double) noexcept { return gain * y_d; }
};

template <class Feedforward>
struct FeedforwardLoop {  // any feedforward compensator: no use of the measurement
  Feedforward ff;
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept { ff.reset(); }
  void on_shape(const ShapeIntegrals&) noexcept {}
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ff.status(); }
  double command(double y_d, double, double, double dt) noexcept { return ff.step(y_d, dt); }
};

struct CurveAngleLoop {  // follows the route's shape every cycle (shape sensing)
  CurveAngleFeedforward ff;
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept { ff.reset(); }
  void on_shape(const ShapeIntegrals& s) noexcept { ff.set_shape(s); }
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ff.status(); }
  double command(double y_d, double, double, double dt) noexcept { return ff.step(y_d, dt); }
};

struct AdaptiveLoop {
  AdaptiveController ctrl;
  /// Back to the state right after construction; the parameters are kept.
  void reset() noexcept { ctrl.reset(); }
  void on_shape(const ShapeIntegrals&) noexcept {}
  bool in_fallback() const noexcept { return ctrl.in_fallback(); }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ctrl.status(); }
  double command(double y_d, double measured, double motor, double dt) noexcept {
    return ctrl.step(y_d, measured, motor, dt);
  }
};

template <class Plant, class Controller>
void run_closed_loop(Plant& plant, Motor* motor, Sensor* sensor, Controller& controller,
                     const double* t, const double* y_d, std::size_t n, const RouteSchedule& sched,
                     const ShapeSchedule& shapes, const unsigned char* dropout,
                     const ClosedLoopTrace& out, const char* where) {
  require(t != nullptr, where, "the bench needs the time vector t");
  check_series(t, y_d, n, where);
  check_schedule(plant, sched, n, where);
  plant.reset();
  if (motor) motor->reset();
  if (sensor) sensor->reset();
  controller.reset();
  std::size_t next = 0;
  double measured = sensor ? sensor->measure(plant.output()) : plant.output();
  double motor_position = plant.input();
  for (std::size_t k = 0; k < n; ++k) {
    while (next < sched.count && sched.index[next] == k) {
      plant.set_node_angles(sched.angles + next * sched.width);
      if (shapes.shapes) controller.on_shape(shapes.shapes[next]);
      ++next;
    }
    const double dt = k == 0 ? 0.0 : t[k] - t[k - 1];
    const double u = controller.command(y_d[k], measured, motor_position, dt);
    const double pulley = motor ? motor->step(u, dt, plant.drive_reaction()) : u;
    motor_position = motor ? motor->position() : u;  // what the controller's encoder reads
    const double y = plant.step(pulley, dt);
    const bool lost = dropout && dropout[k];
    const double reading = sensor ? sensor->measure(y) : y;
    measured = lost ? NAN : reading;
    out.output[k] = y;
    if (out.measured) out.measured[k] = measured;
    if (out.command) out.command[k] = u;
    if (out.motor) out.motor[k] = motor_position;
    if (out.slack) out.slack[k] = plant.slack() ? 1 : 0;
    if (out.fallback) out.fallback[k] = controller.in_fallback() ? 1 : 0;
    if (out.status) {
      Status s = controller.status() | plant.status();
      if (motor) s |= motor->status();
      if (sensor) s |= sensor->status();
      out.status[k] = static_cast<unsigned char>(s);
    }
  }
}

}  // namespace tendonsheath
