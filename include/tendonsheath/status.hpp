// What a real-time step did besides returning its value: flags, read with
// status() right after step() (the plain double-returning step() stays). Every real-time
// class has status(): plants, Motor, Sensor (after measure()), every model and inverse,
// every feedforward and controller. step_with_status() does both in one call.
#pragma once

namespace tendonsheath {

/// @brief What a real-time step did besides returning its value: a set of flags, read with
/// status() right after step() (Sensor: after measure()).
///
/// Every real-time class has status(); several flags can be set at once (combine with |, test with
/// has()). The status guide of the site says what each flag means for each class.
enum class Status : unsigned {
  ok = 0u,                         ///< nothing to report
  held_nonfinite_input = 1u << 0,  ///< a non-finite input was ignored: the last output is held
  input_clamped = 1u << 1,         ///< an input (or dt, or a curve angle) beyond its bound was clamped
  not_converged = 1u << 2,         ///< the solver kept its best bounded iterate
  slack = 1u << 3,                 ///< a tendon tension is <= 0: the model is not valid there
  fallback = 1u << 4,              ///< a controller ran its fallback (no measurement)
  saturated = 1u << 5,             ///< the command hit its limit
  out_of_range = 1u << 6,          ///< an inverse's command would have left the input range its
                                   ///< model was identified on (plus the stated margin): it was
                                   ///< held at the range's edge (the target is unreachable there)
};

/// The union of two flag sets.
constexpr Status operator|(Status a, Status b) noexcept {
  return static_cast<Status>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
/// Adds the flags of b to a; returns a.
constexpr Status& operator|=(Status& a, Status b) noexcept { return a = a | b; }
/// True when every flag of `flag` is set in `s` (has(s, Status::ok) is always true).
constexpr bool has(Status s, Status flag) noexcept {
  return (static_cast<unsigned>(s) & static_cast<unsigned>(flag)) == static_cast<unsigned>(flag);
}

/// One step that also reports its status (ruckig-style): y = step_with_status(obj, s, x, dt).
/// @tparam RealTime any class of the core with step(args...) and status()
/// @param obj the model, plant, compensator or controller to step
/// @param status receives obj.status() after the step
/// @param args the arguments of obj.step (the input, then dt where it takes one)
/// @return what obj.step(args...) returned
template <class RealTime, class... Args>
double step_with_status(RealTime& obj, Status& status, Args... args) noexcept {
  const double y = obj.step(args...);
  status = obj.status();
  return y;
}

}  // namespace tendonsheath
