// The one list of the core's compensators that the closed loop runs at C++ speed. Everything
// that dispatches on a compensator's class follows from it: the closed loop's controller variant
// (bind_bench.cpp) and its loop (bench/closed_loop.hpp: LoopOf), the binding of a compensator
// without one of its own (src/bindings/bind_compensators.cpp: from its ParamTable and its step's
// signature), the C++ JSON loader's dispatch (io/json.hpp: a feedforward with no reader of its
// own is read row by row from its table) and the names Python reads (_core.compensator_kinds()).
//
// Adding a compensator: its header (the class, `using Params`, a ParamTable<Params> whose
// `owner` is the class name, reset(), a noexcept step(y_d, dt) or step(y_d, measured, dt) or
// step(y_d, measured, motor, dt), status()), its #include and one entry below, and its Python
// class (docs/contributing.md, "Adding a compensator").
#pragma once

#include <type_traits>

#include "../param_table.hpp"
#include "../type_list.hpp"
#include "adaptive_controller.hpp"
#include "continuum_feedforward.hpp"
#include "curve_angle_feedforward.hpp"
#include "dead_band_inverse.hpp"
#include "inverse_feedforward.hpp"
#include "model_inverse.hpp"

namespace tendonsheath {

/// The one list of the core's compensators that the closed loop runs at C++ speed: Python's
/// bench.run hands a bound one (or a Python compensator built on one) to the loop of its class
/// (LoopOf in bench/closed_loop.hpp), tried in this order. Adding a compensator: its header and
/// one entry here (see the file's comment).
using Compensators = TypeList<ModelInverse, CurveAngleFeedforward, AdaptiveController,
                              ContinuumFeedforward, BacklashInverseFeedforward,
                              PrandtlIshlinskiiFeedforward, DeadBandInverse>;

/// Whether compensator C has a parameter table (C::Params with a ParamTable): what its binding,
/// its name and its C++ JSON reader follow from when it has none of its own.
template <class C, class = void>
struct has_params_table : std::false_type {};
/// (see has_params_table)
template <class C>
struct has_params_table<C, std::void_t<decltype(ParamTable<typename C::Params>::owner)>>
    : std::true_type {};

/// The name Python, a saved file and _core.compensator_kinds() give a compensator class C that
/// has a parameter table: its table's owner.
template <class C>
constexpr const char* compensator_kind() noexcept {
  return ParamTable<typename C::Params>::owner;
}

}  // namespace tendonsheath
