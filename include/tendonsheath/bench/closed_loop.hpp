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
#include "../compensators/compensator_list.hpp"
#include "../compensators/continuum_feedforward.hpp"
#include "../compensators/inverse_feedforward.hpp"
#include "../compensators/curve_angle_feedforward.hpp"
#include "../compensators/encoder_loop.hpp"
#include "../compensators/learned_feedforward.hpp"
#include "../compensators/model_inverse.hpp"
#include "../compensators/tip_loop.hpp"
#include "../physics/pull_pull_statics.hpp"
#include "../plant/motor.hpp"
#include "../plant/sensor.hpp"
#include "../plant/simulate_plant.hpp"
#include "../type_list.hpp"
#include "../validate.hpp"
#include "erased_compensator.hpp"

namespace tendonsheath {

/// Route shapes seen by a controller, at the same indices as the plant's RouteSchedule.
struct ShapeSchedule {
  const ShapeIntegrals* shapes = nullptr;  ///< one per route change, or nullptr
};

/// Where run_closed_loop() writes each sample's record: n values per array; output is required, a
/// nullptr array is not written.
struct ClosedLoopTrace {
  double* output = nullptr;         ///< true distal output per sample (required)
  double* measured = nullptr;       ///< what the sensor reported (NaN in dropouts)
  double* command = nullptr;        ///< controller output (motor angle or torque)
  double* motor = nullptr;          ///< motor shaft position (its encoder; the pulley lags it by
                                    ///< the gear play when the motor has gear backlash)
  unsigned char* slack = nullptr;   ///< slack flag
  unsigned char* fallback = nullptr;  ///< controller in its fallback mode
  unsigned char* status = nullptr;  ///< Status flags of controller, motor, plant and sensor
};

/// @brief Uncompensated: the kinematic motor angle gain * y_d for the desired output.
///
/// OpenLoop, FeedforwardLoop, CurveAngleLoop and AdaptiveLoop are the controllers as
/// run_closed_loop() sees them: reset(), on_shape(), in_fallback(), status() and command().
struct OpenLoop {  // uncompensated: the kinematic motor angle for the desired output
  /// motor angle per unit of desired output (the kinematic ratio)
  double gain = 1.0;
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {}
  /// Ignores the route: this controller does not follow it.
  void on_shape(const ShapeIntegrals&) noexcept {}
  /// Always false: there is no fallback.
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return Status::ok; }
  /// @return the motor command gain * y_d for desired output y_d (measurement, motor and dt unused)
  double command(double y_d, double, double, double) noexcept { return gain * y_d; }
};

/// @brief Any feedforward compensator (step(y_d, dt)) in the loop: the measurement is not used.
/// @tparam Feedforward BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
/// ContinuumFeedforward, CurveAngleFeedforward or io::LoadedCompensator
template <class Feedforward>
struct FeedforwardLoop {  // any feedforward compensator: no use of the measurement
  /// the compensator
  Feedforward ff;
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { ff.reset(); }
  /// Ignores the route: this controller does not follow it.
  void on_shape(const ShapeIntegrals&) noexcept {}
  /// Always false: there is no fallback.
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ff.status(); }
  /// @return ff.step(y_d, dt), the motor command
  double command(double y_d, double, double, double dt) noexcept { return ff.step(y_d, dt); }
};

/// A curve-angle feedforward that follows the route's shape every cycle (shape sensing).
struct CurveAngleLoop {  // follows the route's shape every cycle (shape sensing)
  /// the compensator
  CurveAngleFeedforward ff;
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { ff.reset(); }
  /// Passes the new route shape to the feedforward (set_shape).
  void on_shape(const ShapeIntegrals& s) noexcept { ff.set_shape(s); }
  /// Always false: there is no fallback.
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ff.status(); }
  /// @return ff.step(y_d, dt), the motor angle command
  double command(double y_d, double, double, double dt) noexcept { return ff.step(y_d, dt); }
};

/// The inverse of an identified model (ModelInverse) in the loop; one that follows the route
/// (CurveAngleModel, AngleDependent) is given every route shape (set_shape), as from shape sensing.
struct ModelInverseLoop {
  /// the compensator
  ModelInverse ff;
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { ff.reset(); }
  /// Passes the new route shape to the inverse (set_shape; ignored when it does not follow it).
  void on_shape(const ShapeIntegrals& s) noexcept { ff.set_shape(s); }
  /// Always false: there is no fallback.
  bool in_fallback() const noexcept { return false; }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ff.status(); }
  /// @return ff.step(y_d, dt), the motor command
  double command(double y_d, double, double, double dt) noexcept { return ff.step(y_d, dt); }
};

/// The adaptive output-feedback controller in the loop: it uses the measurement and the motor
/// position, and returns a torque (so the loop needs a Motor).
struct AdaptiveLoop {
  /// the controller
  AdaptiveController ctrl;
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept { ctrl.reset(); }
  /// Ignores the route: this controller does not follow it.
  void on_shape(const ShapeIntegrals&) noexcept {}
  /// True when the last command ran the controller's fallback (measurement lost).
  bool in_fallback() const noexcept { return ctrl.in_fallback(); }
  /// The last step's status flags (see Status).
  Status status() const noexcept { return ctrl.status(); }
  /// @return the torque command ctrl.step(y_d, measured, motor, dt)
  double command(double y_d, double measured, double motor, double dt) noexcept {
    return ctrl.step(y_d, measured, motor, dt);
  }
};

/// @brief Any compensator C in the loop, by what it has (see erased_compensator.hpp): its step
/// takes the reference, the measurement and the motor position as its signature says; it is
/// given the route's shapes when it has set_shape(ShapeIntegrals), and reports its status() and
/// in_fallback() when it has them. The loop of a compensator added to Compensators without a
/// LoopOf of its own.
template <class C>
struct CompensatorLoop {
  /// the compensator
  C compensator;
  /// Start afresh from the initial state (the compensator's reset()).
  void reset() noexcept { compensator.reset(); }
  /// Passes the route shape to the compensator when it follows the route (set_shape).
  void on_shape(const ShapeIntegrals& s) noexcept {
    if constexpr (detail::follows_shape<C>::value) compensator.set_shape(s);
  }
  /// The compensator's in_fallback(), or false when it has none.
  bool in_fallback() const noexcept { return erased_in_fallback<C>(&compensator); }
  /// The compensator's status(), or Status::ok when it has none.
  Status status() const noexcept { return static_cast<Status>(erased_status<C>(&compensator)); }
  /// @return the compensator's step over the signals it takes, the command
  double command(double y_d, double measured, double motor, double dt) noexcept {
    return erased_command<C>(&compensator, y_d, measured, motor, dt);
  }
};

/// The loop run_closed_loop() runs compensator C in: CompensatorLoop<C> unless specialised (the
/// compensators below keep the named loops above).
template <class C>
struct LoopOf {
  using type = CompensatorLoop<C>;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<ModelInverse> {
  using type = ModelInverseLoop;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<CurveAngleFeedforward> {
  using type = CurveAngleLoop;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<AdaptiveController> {
  using type = AdaptiveLoop;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<ContinuumFeedforward> {
  using type = FeedforwardLoop<ContinuumFeedforward>;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<BacklashInverseFeedforward> {
  using type = FeedforwardLoop<BacklashInverseFeedforward>;  ///< the loop
};
/// (see LoopOf)
template <>
struct LoopOf<PrandtlIshlinskiiFeedforward> {
  using type = FeedforwardLoop<PrandtlIshlinskiiFeedforward>;  ///< the loop
};
/// The loop of compensator C.
template <class C>
using loop_of_t = typename LoopOf<C>::type;

/// @brief Any of the controllers above with an EncoderLoop around its command: the loop makes the
/// motor encoder follow the controller's command (a motor angle), no tip sensor involved.
/// @tparam Inner OpenLoop, FeedforwardLoop, CurveAngleLoop or one with the same members
template <class Inner>
struct WithEncoderLoop {
  /// the controller whose command is the encoder's target
  Inner inner;
  /// the loop around the servo
  EncoderLoop loop;
  /// Start afresh: the controller and the loop.
  void reset() noexcept {
    inner.reset();
    loop.reset();
  }
  /// Passes the route shape to the controller.
  void on_shape(const ShapeIntegrals& s) noexcept { inner.on_shape(s); }
  /// The controller's fallback.
  bool in_fallback() const noexcept { return inner.in_fallback(); }
  /// The controller's and the loop's flags.
  Status status() const noexcept { return inner.status() | loop.status(); }
  /// @return loop.correct(inner.command(...), motor, dt), the servo command
  double command(double y_d, double measured, double motor,
                 double dt) noexcept(noexcept(inner.command(y_d, measured, motor, dt))) {
    return loop.correct(inner.command(y_d, measured, motor, dt), motor, dt);
  }
};

/// @brief Any of the controllers above with a learned correction table added to its command
/// (LearnedCorrection, played from the run's start); put a WithEncoderLoop (or WithTipLoop) around
/// it to have the encoder (or the tip loop) follow the corrected command.
/// @tparam Inner OpenLoop, FeedforwardLoop, CurveAngleLoop, ModelInverseLoop or one with the same
/// members
template <class Inner>
struct WithLearnedCorrection {
  /// the controller whose command is corrected
  Inner inner;
  /// the correction table's player
  LearnedCorrection learned;
  /// Start afresh: the controller, and the table's time back to 0.
  void reset() noexcept {
    inner.reset();
    learned.reset();
  }
  /// Passes the route shape to the controller.
  void on_shape(const ShapeIntegrals& s) noexcept { inner.on_shape(s); }
  /// The controller's fallback.
  bool in_fallback() const noexcept { return inner.in_fallback(); }
  /// The controller's and the table's flags.
  Status status() const noexcept { return inner.status() | learned.status(); }
  /// @return learned.correct(inner.command(...), dt), the corrected command
  double command(double y_d, double measured, double motor,
                 double dt) noexcept(noexcept(inner.command(y_d, measured, motor, dt))) {
    return learned.correct(inner.command(y_d, measured, motor, dt), dt);
  }
};

/// @brief Any of the controllers above with a TipLoop around its command: the loop corrects the
/// controller's command (a motor angle) from the measured tip angle, its gains scheduled over the
/// route's curve angle (given by on_shape, as from shape sensing).
/// @tparam Inner OpenLoop, FeedforwardLoop, CurveAngleLoop, ModelInverseLoop or one with the same
/// members
template <class Inner>
struct WithTipLoop {
  /// the controller whose command the loop corrects
  Inner inner;
  /// the loop on the tip reading
  TipLoop loop;
  /// Start afresh: the controller and the loop (the loop keeps its curve angle).
  void reset() noexcept {
    inner.reset();
    loop.reset();
  }
  /// Passes the route shape to the controller and its curve angle to the loop's gain schedule.
  void on_shape(const ShapeIntegrals& s) noexcept {
    inner.on_shape(s);
    loop.set_shape(s);
  }
  /// The controller's fallback, or the loop's (no tip reading this cycle).
  bool in_fallback() const noexcept { return inner.in_fallback() || loop.in_fallback(); }
  /// The controller's and the loop's flags.
  Status status() const noexcept { return inner.status() | loop.status(); }
  /// @return loop.correct(inner.command(...), y_d, measured, dt), the servo command
  double command(double y_d, double measured, double motor,
                 double dt) noexcept(noexcept(inner.command(y_d, measured, motor, dt))) {
    return loop.correct(inner.command(y_d, measured, motor, dt), y_d, measured, dt);
  }
};

/// @brief The virtual bench: controller -> motor -> plant -> sensor -> controller at the sample
/// times t, the whole loop in C++.
///
/// At sample k (dt = t_k - t_{k-1}): the route changes due at k are applied (to the plant, and as
/// shape integrals to the controller), the controller computes u_k from y_d[k], the last
/// measurement and the motor position, the motor advances under u_k, the plant under the motor
/// position, and the sensor reads the new output (as it was its delay before, when it has one;
/// NaN where dropout is set). Not real-time as a
/// whole: it validates its inputs first and throws std::invalid_argument naming the problem.
/// @tparam Plant SingleTendonPlant, PullPullPlant or ContinuumPlant
/// @tparam Controller OpenLoop, FeedforwardLoop, CurveAngleLoop, ModelInverseLoop, AdaptiveLoop, a
/// WithEncoderLoop, WithTipLoop or WithLearnedCorrection of one of those (or a WithEncoderLoop or
/// WithTipLoop of a WithLearnedCorrection), or one with the same members
/// @param plant the plant, reset first
/// @param motor the motor between command and plant, or nullptr (the command is the pulley angle)
/// @param sensor the output sensor, or nullptr (exact measurement)
/// @param controller the controller, reset first
/// @param t the n sample times, s, finite and increasing
/// @param y_d the n desired outputs
/// @param n the number of samples, >= 1
/// @param sched the plant's route changes
/// @param shapes the same changes as shape integrals for the controller (shapes may be nullptr)
/// @param dropout n flags, nonzero where the measurement is lost, or nullptr
/// @param out where each sample's record goes
/// @param where the name that starts an error message
/// @param encoder the motor encoder's reading (resolution, noise, latency) of the motor shaft,
/// what the controller and the record get as the motor position, or nullptr (exact)
template <class Plant, class Controller>
void run_closed_loop(Plant& plant, Motor* motor, Sensor* sensor, Controller& controller,
                     const double* t, const double* y_d, std::size_t n, const RouteSchedule& sched,
                     const ShapeSchedule& shapes, const unsigned char* dropout,
                     const ClosedLoopTrace& out, const char* where, Sensor* encoder = nullptr) {
  require(t != nullptr, where, "the bench needs the time vector t");
  check_series(t, y_d, n, where);
  check_schedule(plant, sched, n, where);
  plant.reset();
  if (motor) motor->reset();
  if (sensor) sensor->reset();
  if (encoder) encoder->reset();
  controller.reset();
  std::size_t next = 0;
  double measured = sensor ? sensor->measure(plant.output()) : plant.output();
  double motor_position = encoder ? encoder->measure(plant.input()) : plant.input();
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
    if (encoder) motor_position = encoder->measure(motor_position, dt);
    const double y = plant.step(pulley, dt);
    const bool lost = dropout && dropout[k];
    const double reading = sensor ? sensor->measure(y, dt) : y;  // dt: its latency
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
      if (encoder) s |= encoder->status();
      out.status[k] = static_cast<unsigned char>(s);
    }
  }
}

}  // namespace tendonsheath
