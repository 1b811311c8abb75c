// One ModelInverse of every kind of core and stage (the model classes identify returns), for
// the allocation, behaviour and fuzz tests.
#pragma once

#include <string>
#include <tendonsheath/compensators/make_model_inverse.hpp>

namespace tendonsheath::cases {

inline ModelPart part(const char* kind) {
  ModelPart p;
  p.kind = kind;
  return p;
}

inline ModelPart plays(const char* kind, double r0) {
  ModelPart p = part(kind);
  p.prandtl_ishlinskii = PrandtlIshlinskiiParams{{r0, 0.1, 0.2, 0.3}, {0.8, 0.3, -0.2, 0.2}};
  return p;
}

inline ModelPart laws_part(const char* base, std::size_t count) {
  ModelPart p = part("AngleDependent");
  p.base = base;
  AngleLaws laws;
  laws.count = count;
  laws.angle_friction = 0.1;
  double c0[8] = {1.0, 0.9, 0.1, 0.05, 20.0, 1.0, 2.0, 0.0};  // Backlash / BoucWenBacklash
  if (std::string(base) == "BoucWen") {
    const double v[8] = {1.0, 0.5, 0.2, 1.0, 0.3, 1.0};
    for (int i = 0; i < 8; ++i) c0[i] = v[i];
  } else if (std::string(base) == "HystereticOscillator") {
    const double v[8] = {1e-3, 0.05, 1.0, 1.0, 2.0, 0.5, 0.5, 1.0};
    for (int i = 0; i < 8; ++i) c0[i] = v[i];
  }
  for (std::size_t i = 0; i < count; ++i) laws.c0[i] = c0[i];
  laws.law[0] = AngleLaw::linear, laws.c1[0] = 0.05;   // a slope that follows Theta
  laws.law[2] = AngleLaw::tanh, laws.c1[2] = 0.1;      // a dead zone that follows the shape
  p.laws = laws;
  return p;
}

inline ModelPart lag(int order) {
  ModelPart p = part(order == 1 ? "FirstOrderLag" : "SecondOrderLag");
  p.lag.order = order;
  p.lag.time_constant = 0.03;
  p.lag.frequency = 4.0;
  p.lag.damping = 0.7;
  return p;
}

inline ModelPart cubic() {
  ModelPart p = part("Polynomial");
  p.polynomial.coefficients = {0.05, 1.0, 0.1, 0.2};
  return p;
}

inline ModelPart oscillator() {
  ModelPart p = part("HystereticOscillator");
  p.hysteretic_oscillator = HystereticOscillatorParams{};
  p.hysteretic_oscillator.m = 1e-3;
  p.hysteretic_oscillator.c = 0.05;
  p.hysteretic_oscillator.beta = 2.0;
  return p;
}

/// The number of cases inverse_case() builds.
constexpr int kInverseCases = 17;

/// Case i's model description (see the switch for which class each is).
inline InverseModel inverse_model(int i) {
  InverseModel m;
  switch (i) {
    case 0: m.parts = {part("Backlash")}; break;                       // D.2
    case 1: m.parts = {plays("PrandtlIshlinskii", 0.0)}; break;        // exact PI
    case 2: m.parts = {plays("PrandtlIshlinskii", 0.02)}; break;       // root: PI, r0 > 0
    case 3: m.parts = {part("GeneralizedPrandtlIshlinskii")}; break;   // root: GPI
    case 4: m.parts = {part("BoucWen")}; break;                        // root: BoucWen
    case 5: m.parts = {cubic()}; break;                                // root: a polynomial
    case 6: {                                                          // root + lag: plant
      ModelPart p = part("PlantModel");
      p.plant_model.elements = 4;
      p.plant_model.viscous_time = 0.01;
      m.parts = {p};
      break;
    }
    case 7: m.parts = {part("BoucWenBacklash"), cubic()}; break;      // composite root
    case 8: m.parts = {part("BoucWenBacklash"), lag(2)}; break;       // Hammerstein
    case 9: m.parts = {lag(1), plays("PrandtlIshlinskii", 0.0)}; break;  // Wiener
    case 10: m.parts = {oscillator()}; break;                          // oscillator
    case 11: m.parts = {part("CurveAngleModel")}; break;               // follows the route
    case 12: m.parts = {laws_part("BoucWenBacklash", 7)}; break;       // angle D.2
    case 13: m.parts = {laws_part("BoucWen", 6)}; break;               // angle root
    case 14: m.parts = {laws_part("HystereticOscillator", 8)}; break;  // angle oscillator
    case 15: m.parts = {oscillator(), cubic()}; break;                 // polynomial stage
    default: {                                                         // Scaled GPI
      m.parts = {part("GeneralizedPrandtlIshlinskii")};
      m.map = ScaledMap{0.2, 2.0, 0.1, -0.7};
      break;
    }
  }
  return m;
}

/// Case i's inverse, with the commands held in `range`.
inline ModelInverse inverse_case(int i, const InputRange& range = {}) {
  InverseSettings s;
  s.smoothing = 0.01;
  s.range = range;
  return make_model_inverse(inverse_model(i), s, "case " + std::to_string(i));
}

}  // namespace tendonsheath::cases
