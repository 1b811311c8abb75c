// tendonsheath: real-time core (header-only, C++17).
#pragma once

#include "validate.hpp"
#include "models/backlash.hpp"
#include "models/bouc_wen.hpp"
#include "models/bouc_wen_backlash.hpp"
#include "models/hysteretic_oscillator.hpp"
#include "models/prandtl_ishlinskii.hpp"
#include "models/simulate.hpp"
#include "physics/pull_pull_statics.hpp"
#include "compensators/command_shaping.hpp"
#include "compensators/inverse_feedforward.hpp"
#include "compensators/curve_angle_feedforward.hpp"
#include "compensators/continuum_feedforward.hpp"
#include "compensators/adaptive_controller.hpp"
#include "models/polynomial.hpp"
#include "models/generalized_prandtl_ishlinskii.hpp"
