// Building the ModelInverse of a model description (InverseModel): which inverse each model
// class gets. Construction only (allocates, throws std::invalid_argument naming the problem).
//
//   Backlash, BoucWenBacklash            the direct inverse of spec D.2 (smoothing)
//   PrandtlIshlinskii, thresholds[0] = 0  the exact inverse (monotone for any signs of weights
//                                         the model accepts: every partial sum > 0)
//   PrandtlIshlinskii (r_0 > 0), GPI, BoucWen, PlantModel, Polynomial, and any of these or a
//   Backlash / BoucWenBacklash followed by a Polynomial      the root-finding inverse
//                                         (PlantModel: of its quasi-static plant, its viscous
//                                         drag inverted as a first-order lag, see
//                                         plant_viscous_lag)
//   HystereticOscillator                  OscillatorInverse (filter_hz)
//   CurveAngleModel                       CurveAngleFeedforward (it follows the route)
//   AngleDependent over Backlash / BoucWenBacklash, BoucWen, HystereticOscillator: the base's
//                                         inverse, its parameters from the laws at each route
//   Chain(model, lag)  Hammerstein: lag inverse, then the model's inverse
//   Chain(lag, model)  Wiener: the model's inverse, then the lag inverse
//   Chain(model, Polynomial) of a model without a forward root engine: the polynomial's
//                      static root inverse, then the model's inverse
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "model_inverse.hpp"

namespace tendonsheath {

namespace detail {

// the pieces of a ModelInverse before assembly
struct InversePlan {
  ModelInverse::Core core{PassThrough{}};
  ModelInverse::Stage pre{};
  std::optional<LagInverse> post{};
  double friction = 0.0;
};

struct InverseContext {
  InputRange range;       // inner units
  double smoothing;       // inner units
  double filter_hz;       // 0: the default of each block
  std::string where;
};

inline bool is_lag(const ModelPart& p) {
  return p.kind == "FirstOrderLag" || p.kind == "SecondOrderLag";
}

// the model M a root engine runs, from its parameters (a PlantModel's: quasi-static, its viscous
// drag inverted by a lag inverse, see plant_lag)
template <class M>
M forward_of(const typename M::Params& p) {
  return M(p);
}
template <>
inline PlantModel forward_of<PlantModel>(const PlantModelParams& p) {
  PlantModelParams q = p;
  q.viscous_time = 0.0;
  return PlantModel(q);
}

// the forward model a root engine runs for part p, if it has one (a model of ForwardModel's)
inline std::optional<ForwardModel::First> forward_first(const ModelPart& p) {
  std::optional<ForwardModel::First> out;
  any_type(ForwardModel::Models{}, [&](auto tag) {
    using M = typename decltype(tag)::type;
    if (p.kind != model_kind<M>()) return false;
    out.emplace(forward_of<M>(part_params<M>(p)));
    return true;
  });
  return out;
}

// The first-order lag equivalent to a PlantModel's viscous drag: the delay of its output behind
// the quasi-static plant's on a steady ramp (the sheath's viscous diffusion seen from the distal
// pulley), measured once on copies of the two plants: about 0.44 viscous_time at friction angle
// 0.5, 0.22 at 4 (10 elements). A deadbeat root of the viscous plant itself is not stable: its
// sampled response from the proximal to the distal pulley has zeros outside the unit circle.
inline double plant_viscous_lag(const PlantModelParams& p) {
  PlantModelParams q = p;
  q.viscous_time = 0.0;
  PlantModel quasi_static(q), viscous(p);
  if (detail::failed()) return 0.0;  // without exceptions: the plants are not stepped
  const double tau = p.viscous_time, v = p.backlash / tau, dt = tau / 50.0;
  const int n = static_cast<int>(std::ceil((2.0 * p.backlash / v + 12.0 * tau) / dt));
  double ys = quasi_static.step(0.0, 0.0), yv = viscous.step(0.0, 0.0);
  for (int k = 1; k <= n; ++k) {
    ys = quasi_static.step(v * k * dt, dt);
    yv = viscous.step(v * k * dt, dt);
  }
  return (ys - yv) / (p.gain * v);
}

// the lag inverse of a PlantModel's viscous drag (none when it has none)
inline ModelInverse::Stage plant_lag(const ModelPart& p, const InverseContext& c) {
  if (p.kind != "PlantModel" || !(p.plant_model.viscous_time > 0.0)) return std::monostate{};
  LagInverseParams q;
  q.order = 1;
  q.time_constant = plant_viscous_lag(p.plant_model);
  q.filter_hz = c.filter_hz;
  return LagInverse(q);
}

// the root search's first step: 1e-4 of the range's span (or of 1 input unit when unbounded)
inline RootSearchSettings root_settings(const InputRange& r) {
  RootSearchSettings s;
  const double span = r.hi - r.lo;
  s.initial_step = (std::isfinite(span) && span > 0.0) ? 1e-4 * span : 1e-4;
  return s;
}

inline RootInverse<ForwardModel> root_engine(ForwardModel model, const InverseContext& c) {
  return RootInverse<ForwardModel>(model, c.range, root_settings(c.range));
}

inline BacklashInverseFeedforward direct_inverse(const double* v, const InverseContext& c) {
  BacklashInverseParams p;
  p.c_r = v[0];
  p.c_l = v[1];
  p.B_r = v[2];
  p.B_l = v[3];
  p.smoothing = c.smoothing;
  return BacklashInverseFeedforward(p);
}

// the direct inverse's four values (c_r, c_l, B_r, B_l) of a Backlash's or BoucWenBacklash's
// parameters
template <class P>
void backlash_values(const P& p, double* v) {
  v[0] = p.c_r;
  v[1] = p.c_l;
  v[2] = p.B_r;
  v[3] = p.B_l;
}

inline CurveAngleFeedforward curve_angle_inverse(const CurveAngleParams& m, const InverseContext& c) {
  CurveAngleFeedforwardParams p;
  p.friction = m.friction;
  p.stiffness = m.stiffness;
  p.length = m.length;
  p.pretension = m.pretension;
  p.load_force = m.load_force;
  p.load_stiffness = m.load_stiffness;
  p.proximal_radius = m.proximal_radius;
  p.distal_radius = m.distal_radius;
  p.play = m.play;
  p.curve_angle = 0.0;
  p.smoothing = c.smoothing;
  (void)CurveAngleModel(m);  // the model's own validation
  return CurveAngleFeedforward(p);
}

// the curve angle an AngleDependent's engine is built at: pi with a tanh law, else 0 (as Python
// validates the model)
inline double initial_angle(const AngleLaws& laws) {
  for (std::size_t i = 0; i < laws.count; ++i)
    if (laws.law[i] == AngleLaw::tanh) return 3.14159265358979323846;
  return 0.0;
}

// The engine of an AngleDependent over base M, built from the base parameters v at curve angle
// theta: the overloads below (a model without one is no AngleDependent base: has_angle_engine).
template <class M>
std::optional<ModelInverse::Core> angle_engine(TypeTag<M>, const ModelPart&, const double*, double,
                                               const InverseContext&) = delete;
// Backlash, BoucWenBacklash: the direct inverse of their first four parameters
template <class M>
std::optional<ModelInverse::Core> direct_angle_engine(const ModelPart& p, const double* v,
                                                      double theta, const InverseContext& c) {
  require(p.laws.count == M::Params::vector_size, c.where, "AngleDependent ", p.base,
          " needs one law per base parameter (got ", p.laws.count, ")");
  return AngleDependentInverse<BacklashInverseFeedforward>(direct_inverse(v, c), p.laws, theta);
}
inline std::optional<ModelInverse::Core> angle_engine(TypeTag<Backlash>, const ModelPart& p,
                                                      const double* v, double theta,
                                                      const InverseContext& c) {
  return direct_angle_engine<Backlash>(p, v, theta, c);
}
inline std::optional<ModelInverse::Core> angle_engine(TypeTag<BoucWenBacklash>, const ModelPart& p,
                                                      const double* v, double theta,
                                                      const InverseContext& c) {
  return direct_angle_engine<BoucWenBacklash>(p, v, theta, c);
}
inline std::optional<ModelInverse::Core> angle_engine(TypeTag<BoucWen>, const ModelPart& p,
                                                      const double* v, double theta,
                                                      const InverseContext& c) {
  require(p.laws.count == BoucWenParams::vector_size, c.where,
          "AngleDependent BoucWen needs 6 laws (got ", p.laws.count, ")");
  BoucWenParams b = p.bouc_wen;
  b.assign(v);
  auto root = root_engine(ForwardModel(ForwardModel::First{BoucWen(b)}), c);
  return AngleDependentInverse<RootInverse<ForwardModel>>(root, p.laws, theta);
}
inline std::optional<ModelInverse::Core> angle_engine(TypeTag<HystereticOscillator>,
                                                      const ModelPart& p, const double* v,
                                                      double theta, const InverseContext& c) {
  require(p.laws.count == HystereticOscillatorParams::vector_size, c.where,
          "AngleDependent HystereticOscillator needs 8 laws (got ", p.laws.count, ")");
  HystereticOscillatorParams o = p.hysteretic_oscillator;
  o.assign(v);
  return AngleDependentInverse<OscillatorInverse>(OscillatorInverse(o, c.filter_hz), p.laws, theta);
}

template <class M, class = void>
struct has_angle_engine : std::false_type {};
template <class M>
struct has_angle_engine<M, std::void_t<decltype(angle_engine(
                               TypeTag<M>{}, std::declval<const ModelPart&>(),
                               std::declval<const double*>(), 0.0,
                               std::declval<const InverseContext&>()))>> : std::true_type {};

inline ModelInverse::Core angle_dependent(const ModelPart& p, const InverseContext& c) {
  p.laws.validate(c.where.c_str());
  if (detail::failed()) return PassThrough{};  // without exceptions: no law read past the arrays
  const double theta = initial_angle(p.laws);
  double v[AngleLaws::kMaxParams];
  p.laws.at_angle(theta, v);
  std::optional<ModelInverse::Core> engine;
  visit_model_kind(p.base, [&](auto tag) {
    if constexpr (has_angle_engine<typename decltype(tag)::type>::value)
      engine = angle_engine(tag, p, v, theta, c);
  });
  if (engine) return std::move(*engine);
  detail::check_failed(c.where, "the inverse of an AngleDependent model takes a Backlash, "
                       "BoucWenBacklash, BoucWen or HystereticOscillator base (got '", p.base, "')");
  return PassThrough{};  // (without exceptions: never used, the check has failed)
}

inline LagInverse lag_inverse(const ModelPart& p, const InverseContext& c) {
  LagInverseParams q = p.lag;
  q.order = p.kind == "FirstOrderLag" ? 1 : 2;
  q.filter_hz = c.filter_hz;
  return LagInverse(q);
}

// The inverse of one model M of the list (model_list.hpp): the root search on the model (and a
// PlantModel's viscous lag) unless M has an inverse of its own (an overload below).
template <class M>
InversePlan inverse_plan(TypeTag<M>, const ModelPart& p, const InverseContext& c) {
  static_assert(root_invertible<M>::value,
                "a model that is not root_invertible needs its own inverse_plan() overload");
  InversePlan plan;
  auto first = forward_first(p);
  if (detail::failed()) return plan;  // without exceptions: a half-built model is not used
  plan.core = root_engine(ForwardModel(std::move(*first)), c);
  plan.pre = plant_lag(p, c);
  return plan;
}

// Backlash, BoucWenBacklash: the direct inverse of spec D.2
template <class M>
InversePlan direct_plan(const ModelPart& p, const InverseContext& c) {
  InversePlan plan;
  (void)M(part_params<M>(p));  // the model's own validation
  double v[AngleLaws::kMaxParams];
  backlash_values(part_params<M>(p), v);
  plan.core = direct_inverse(v, c);
  return plan;
}
inline InversePlan inverse_plan(TypeTag<Backlash>, const ModelPart& p, const InverseContext& c) {
  return direct_plan<Backlash>(p, c);
}
inline InversePlan inverse_plan(TypeTag<BoucWenBacklash>, const ModelPart& p,
                                const InverseContext& c) {
  return direct_plan<BoucWenBacklash>(p, c);
}

// PrandtlIshlinskii: the exact inverse when thresholds[0] = 0, else the root search
inline InversePlan inverse_plan(TypeTag<PrandtlIshlinskii> tag, const ModelPart& p,
                                const InverseContext& c) {
  if (p.prandtl_ishlinskii.thresholds.empty() || p.prandtl_ishlinskii.thresholds.front() != 0.0)
    return inverse_plan<PrandtlIshlinskii>(tag, p, c);
  InversePlan plan;
  PrandtlIshlinskiiInverse inverse(p.prandtl_ishlinskii);
  if (detail::failed()) return plan;  // without exceptions: a half-built inverse is not used
  inverse.set_range(c.range);
  plan.core = std::move(inverse);
  return plan;
}

inline InversePlan inverse_plan(TypeTag<HystereticOscillator>, const ModelPart& p,
                                const InverseContext& c) {
  InversePlan plan;
  plan.core = OscillatorInverse(p.hysteretic_oscillator, c.filter_hz);
  return plan;
}

inline InversePlan inverse_plan(TypeTag<CurveAngleModel>, const ModelPart& p,
                                const InverseContext& c) {
  InversePlan plan;
  plan.core = curve_angle_inverse(p.curve_angle_model, c);
  plan.friction = p.curve_angle_model.friction;
  return plan;
}

// the inverse of one plain model
inline InversePlan single(const ModelPart& p, const InverseContext& c) {
  InversePlan plan;
  if (visit_model_kind(p.kind, [&](auto tag) { plan = inverse_plan(tag, p, c); })) {
  } else if (p.kind == "AngleDependent") {
    plan.core = angle_dependent(p, c);
    plan.friction = p.laws.angle_friction;
  } else if (is_lag(p)) {
    plan.post = lag_inverse(p, c);
  } else {
    detail::check_failed(c.where, "no inverse for a model of kind '", p.kind, "'");
  }
  return plan;
}

// the inverse of Chain(a, b)
inline InversePlan chain(const ModelPart& a, const ModelPart& b, const InverseContext& c) {
  if (b.kind == "Polynomial") {
    if (auto first = forward_first(a)) {
      InversePlan plan;
      if (detail::failed()) return plan;  // without exceptions: a half-built model is not used
      plan.core = root_engine(ForwardModel(std::move(*first), Polynomial(b.polynomial)), c);
      plan.pre = plant_lag(a, c);  // (its lag taken after the polynomial: an approximation)
      return plan;
    }
    InversePlan plan = single(a, c);
    plan.pre = RootInverse<Polynomial>(Polynomial(b.polynomial), InputRange{},
                                       root_settings(InputRange{}));
    return plan;
  }
  if (is_lag(b)) {  // Hammerstein
    InversePlan plan = single(a, c);
    require(plan.pre.index() == 0, c.where, "a PlantModel with viscous_time > 0 followed by a "
            "lag has no inverse here (two lags in a row: give the chain one lag)");
    plan.pre = lag_inverse(b, c);
    return plan;
  }
  if (is_lag(a)) {  // Wiener
    InversePlan plan = single(b, c);
    plan.post = lag_inverse(a, c);
    return plan;
  }
  detail::check_failed(c.where, "a Chain is inverted when its second part is a Polynomial or a "
                       "lag, or its first a lag (got ", a.kind, " then ", b.kind, ")");
  return {};  // (without exceptions: never used, the check has failed)
}

// what make_model_inverse returns without exceptions once a check has failed: never stepped
inline ModelInverse unused_inverse() {
  return ModelInverse(PassThrough{}, std::monostate{}, std::nullopt, ScaledMap{}, InputRange{},
                      CommandLimits{});
}

}  // namespace detail

/// Whether model M of the list (model_list.hpp) can be the base of an AngleDependent model in
/// make_model_inverse (Backlash, BoucWenBacklash, BoucWen, HystereticOscillator): it has an
/// engine whose parameters follow the laws.
template <class M>
inline constexpr bool angle_dependent_base = detail::has_angle_engine<M>::value;

/// The real-time inverse of model `m` with settings `s` (see the file's comment for which inverse
/// each class gets). Throws std::invalid_argument, message starting with `where`, naming the
/// first bad part or setting. Without exceptions, inside a Result being built (the io loaders'
/// try_ forms), the message goes to that Result and the inverse returned is never to be used;
/// outside one, the error handler is called, then std::abort().
inline ModelInverse make_model_inverse(const InverseModel& m, const InverseSettings& s,
                                       const std::string& where = "InverseFeedforward") {
  require(m.parts.size() == 1 || m.parts.size() == 2, where,
          "a model has one part, or two for a Chain (got ", m.parts.size(), ")");
  require_positive(s.smoothing, where.c_str(), "smoothing");
  require(std::isfinite(s.filter_hz) && s.filter_hz >= 0.0, where,
          "filter_hz must be > 0, or 0 for the default (got ", s.filter_hz, ")");
  s.range.validate(where.c_str());
  const ScaledMap& mp = m.map;
  mp.validate(where.c_str());
  if (detail::failed()) return detail::unused_inverse();  // without exceptions, in a Result
  const detail::InverseContext c{s.range.unmapped(mp.input_offset, mp.input_scale),
                                 s.smoothing / std::fabs(mp.output_gain), s.filter_hz, where};
  detail::InversePlan plan = m.parts.size() == 1 ? detail::single(m.parts[0], c)
                                                 : detail::chain(m.parts[0], m.parts[1], c);
  if (detail::failed()) return detail::unused_inverse();  // its parts are not used
  return ModelInverse(std::move(plan.core), std::move(plan.pre), std::move(plan.post), mp,
                      s.range, s.limits, plan.friction);
}

}  // namespace tendonsheath
