// tendonsheath: real-time core (header-only, C++17).
#pragma once

#include "validate.hpp"
#include "models/backlash.hpp"
#include "models/bouc_wen.hpp"
#include "models/bouc_wen_backlash.hpp"
#include "models/hysteretic_oscillator.hpp"
#include "models/prandtl_ishlinskii.hpp"
#include "models/simulate.hpp"
#include "models/curve_angle.hpp"
