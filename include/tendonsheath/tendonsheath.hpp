// tendonsheath: real-time core (header-only, C++17).
#pragma once

#include "config.hpp"
#include "error_handler.hpp"
#include "result.hpp"
#include "validate.hpp"
#include "status.hpp"
#include "models/backlash.hpp"
#include "models/bouc_wen.hpp"
#include "models/bouc_wen_backlash.hpp"
#include "models/hysteretic_oscillator.hpp"
#include "models/oscillator_sensitivity.hpp"
#include "models/prandtl_ishlinskii.hpp"
#include "models/simulate.hpp"
#include "physics/pull_pull_statics.hpp"
#include "compensators/command_shaping.hpp"
#include "compensators/inverse_feedforward.hpp"
#include "compensators/input_range.hpp"
#include "compensators/lag_inverse.hpp"
#include "compensators/oscillator_inverse.hpp"
#include "compensators/root_inverse.hpp"
#include "compensators/model_inverse.hpp"
#include "compensators/make_model_inverse.hpp"
#include "compensators/coupled_feedforward.hpp"
#include "models/angle_laws.hpp"
#include "models/forward_model.hpp"
#include "models/model_list.hpp"
#include "models/plant_model.hpp"
#include "compensators/curve_angle_feedforward.hpp"
#include "compensators/continuum_feedforward.hpp"
#include "compensators/adaptive_controller.hpp"
#include "compensators/encoder_loop.hpp"
#include "compensators/learned_feedforward.hpp"
#include "compensators/tip_loop.hpp"
#include "compensators/load_compensated.hpp"
#include "models/polynomial.hpp"
#include "models/generalized_prandtl_ishlinskii.hpp"
#include "route.hpp"
#include "plant/friction_chain.hpp"
#include "plant/single_tendon.hpp"
#include "plant/pull_pull.hpp"
#include "plant/continuum.hpp"
#include "plant/motor.hpp"
#include "plant/sensor.hpp"
#include "plant/simulate_plant.hpp"
#include "bench/closed_loop.hpp"
#include "models/curve_angle.hpp"

/// @mainpage The real-time C++ core
/// Header-only C++17: include tendonsheath/tendonsheath.hpp and link the CMake target
/// tendonsheath::core. Start from the namespace tendonsheath or the class list; the
/// <a href="../index.html">C++ page of the documentation site</a> introduces the CMake package,
/// the real-time contract and the examples.

/// @brief The real-time core: hysteresis models and their inverses, physics plants,
/// compensators and the closed-loop bench.
///
/// Every class validates its parameters once, in its constructor (std::invalid_argument naming
/// the class and the parameter; make<T>() returns that message in a Result instead, and is the
/// way to build one when the core is compiled without exceptions: see result.hpp and
/// error_handler.hpp). After that, step() is noexcept, allocates nothing, does bounded
/// work and never returns NaN for finite input; status() tells what the last step did.
