// What a real-time step did besides returning its value: flags, read with
// status() right after step() (the plain double-returning step() stays).
#pragma once

namespace tendonsheath {

enum class Status : unsigned {
  ok = 0u,
  held_nonfinite_input = 1u << 0,  // a non-finite input was ignored: the last output is held
  input_clamped = 1u << 1,         // an input (or dt, or a curve angle) beyond its bound was clamped
  not_converged = 1u << 2,         // the solver kept its best bounded iterate
  slack = 1u << 3,                 // a tendon tension is <= 0: the model is not valid there
  fallback = 1u << 4,              // a controller ran its fallback (no measurement)
  saturated = 1u << 5,             // the command hit its limit
};

constexpr Status operator|(Status a, Status b) noexcept {
  return static_cast<Status>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
constexpr Status& operator|=(Status& a, Status b) noexcept { return a = a | b; }
// True when every flag of `flag` is set in `s` (has(s, Status::ok) is always true).
constexpr bool has(Status s, Status flag) noexcept {
  return (static_cast<unsigned>(s) & static_cast<unsigned>(flag)) == static_cast<unsigned>(flag);
}

}  // namespace tendonsheath
