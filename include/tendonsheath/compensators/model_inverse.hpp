// The real-time inverse of every model the identification returns (Python's InverseFeedforward
// and the C++ loader build this one class from the same description, so their commands agree):
//
//   v = (y_d - output_offset) / output_gain            a Scaled model's map (identity otherwise)
//   v = pre(v)         Hammerstein lag inverse, or a static polynomial's inverse
//   u = core(v)        the model's own inverse, inside the input range
//   u = post(u)        Wiener lag inverse (then held inside the range again)
//   x = input_offset + input_scale * u, shaped to the command limits
//
// Cores: the direct inverse of spec D.2 (Backlash, BoucWenBacklash), the exact
// Prandtl-Ishlinskii inverse (thresholds[0] = 0), the root-finding inverse (RootInverse: PI of
// any thresholds, GPI, BoucWen, PlantModel, Polynomial and a model followed by a polynomial),
// the CurveAngleModel's (CurveAngleFeedforward: it follows the route), the oscillator's
// (OscillatorInverse) and the AngleDependent ones (their base's inverse with the base
// parameters re-evaluated from their laws at every route change). Every command stays in the
// input range; a cycle that could not reach its target inside it reports out_of_range.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "../models/angle_laws.hpp"
#include "../models/curve_angle.hpp"
#include "../models/forward_model.hpp"
#include "../models/hysteretic_oscillator.hpp"
#include "../models/model_list.hpp"
#include "../physics/pull_pull_statics.hpp"
#include "command_shaping.hpp"
#include "curve_angle_feedforward.hpp"
#include "input_range.hpp"
#include "inverse_feedforward.hpp"
#include "lag_inverse.hpp"
#include "oscillator_inverse.hpp"
#include "root_inverse.hpp"

namespace tendonsheath {

/// The affine map of a Python `Scaled` model around the inverted one:
/// command = input_offset + input_scale * inner((y_d - output_offset) / output_gain).
struct ScaledMap {
  double input_offset = 0.0;  ///< added to the inner command
  double input_scale = 1.0;  ///< scales the inner command, > 0
  double output_offset = 0.0;  ///< subtracted from the desired output
  double output_gain = 1.0;  ///< divides the desired output, != 0

  /// Throws std::invalid_argument "<where>: <name> must be ..." naming the first bad value (the
  /// rule of Python's `Scaled`, with its message).
  void validate(const char* where) const {
    require_finite(input_offset, where, "input_offset");
    require_positive(input_scale, where, "input_scale");
    require_finite(output_offset, where, "output_offset");
    require(std::isfinite(output_gain) && output_gain != 0.0, where,
            "output_gain must be finite and not 0 (got ", output_gain, ")");
  }
};

/// @brief One plain model of the library, reduced to what its inverse needs: `kind` (the Python
/// class name) says which member holds its parameters. Besides `lag`, `base` and `laws`, it has
/// one member per model class of the list (model_list.hpp, TENDONSHEATH_MODELS): `backlash`
/// (BacklashParams), `bouc_wen_backlash`, `bouc_wen`, `prandtl_ishlinskii`,
/// `generalized_prandtl_ishlinskii`, `polynomial`, `plant_model`, `hysteretic_oscillator` and
/// `curve_angle_model` (CurveAngleParams); part_params<M>() reaches model M's.
struct ModelPart {
  std::string kind;  ///< a model class of the list, FirstOrderLag, SecondOrderLag or
                     ///< AngleDependent
#define TENDONSHEATH_DETAIL_PART_MEMBER(Model, member) Model::Params member{};
  TENDONSHEATH_MODELS(TENDONSHEATH_DETAIL_PART_MEMBER)
#undef TENDONSHEATH_DETAIL_PART_MEMBER
  LagInverseParams lag{};  ///< FirstOrderLag (order 1) or SecondOrderLag (order 2)
  std::string base;  ///< AngleDependent: the base's kind (its options in the member above)
  AngleLaws laws{};  ///< AngleDependent: the laws of the base's parameters
};

/// Where ModelPart holds model M's parameters: `name` (the member's and the Python property's
/// name) and `member` (the pointer to it), for each model M of the list.
template <class M>
struct PartMember;
#define TENDONSHEATH_DETAIL_PART_POINTER(Model, name_)            \
  template <>                                                     \
  struct PartMember<Model> {                                      \
    static constexpr const char* name = #name_;                   \
    static constexpr auto member = &ModelPart::name_;             \
  };
TENDONSHEATH_MODELS(TENDONSHEATH_DETAIL_PART_POINTER)
#undef TENDONSHEATH_DETAIL_PART_POINTER

/// Model M's parameters in part p.
template <class M>
typename M::Params& part_params(ModelPart& p) noexcept {
  return p.*PartMember<M>::member;
}
/// Model M's parameters in part p.
template <class M>
const typename M::Params& part_params(const ModelPart& p) noexcept {
  return p.*PartMember<M>::member;
}

/// A model as its inverse needs it: one part, or a Chain's two (first, then second), and the map
/// of a Scaled model around it.
struct InverseModel {
  std::vector<ModelPart> parts;  ///< one part, or a Chain's first and second
  ScaledMap map{};  ///< identity unless the model was a Scaled one
};

/// The settings of a ModelInverse (Python's InverseFeedforward arguments).
struct InverseSettings {
  double smoothing = 0.05;  ///< D.2 and curve-angle direction switch speed, output units per s
  CommandLimits limits{};  ///< the command's limits (outer units)
  InputRange range{};  ///< the commands allowed (outer units); unbounded by default
  double filter_hz = 0.0;  ///< the lag and oscillator inverses' corner, Hz; 0: their default
};

/// The identity core (a lag alone: its inverse is the stage around it).
struct PassThrough {
  /// Nothing to reset.
  void reset() noexcept {}
  /// @return v itself
  double step(double v, double) noexcept { return v; }
  /// Always ok.
  Status status() const noexcept { return Status::ok; }
};

namespace detail {
inline bool set_base_params(BacklashInverseFeedforward& e, const double* v) noexcept {
  return e.set_branches(v);
}
inline bool set_base_params(RootInverse<ForwardModel>& e, const double* v) noexcept {
  return e.model().set_base_params(v);
}
inline bool set_base_params(OscillatorInverse& e, const double* v) noexcept {
  return e.set_base_params(v);
}
}  // namespace detail

/// @brief An inverse whose base parameters follow the route through AngleLaws (Python's
/// AngleDependent model): set_curve_angle() and set_shape() re-evaluate them (no allocation).
///
/// Where the laws give parameters the base cannot take (e.g. a negative slope), the last valid
/// ones are kept and status() reports input_clamped.
/// @tparam Engine BacklashInverseFeedforward, RootInverse<ForwardModel> or OscillatorInverse
template <class Engine>
class AngleDependentInverse {
 public:
  /// @param engine the base's inverse, built at curve angle theta0
  /// @param laws the laws (validated)
  /// @param theta0 the curve angle the engine was built at, rad
  AngleDependentInverse(Engine engine, const AngleLaws& laws, double theta0)
      : engine_(std::move(engine)), laws_(laws), theta_(theta0) {
    laws.validate("AngleDependentInverse");
  }
  /// Start afresh (the route kept).
  void reset() noexcept { engine_.reset(); }
  /// @param v the desired output
  /// @param dt the time since the previous cycle, s
  /// @return the base's inverse command
  double step(double v, double dt) noexcept { return engine_.step(v, dt); }
  /// The engine's status, and input_clamped when the route's parameters were not valid.
  Status status() const noexcept {
    return clamped_ ? engine_.status() | Status::input_clamped : engine_.status();
  }
  /// Uniform curvature with total angle theta, rad (the laws' tanh(mu |theta| / 2)).
  void set_curve_angle(double theta) noexcept {
    if (!std::isfinite(theta)) return;
    double v[AngleLaws::kMaxParams];
    laws_.at_angle(theta, v);
    theta_ = theta;
    clamped_ = !detail::set_base_params(engine_, v);
  }
  /// Any route: its shape integrals (with mu = the laws' angle_friction) and total angle.
  void set_shape(const ShapeIntegrals& s) noexcept {
    if (!(std::isfinite(s.g) && std::isfinite(s.G) && s.g > 0.0 && s.G > 0.0 &&
          std::isfinite(s.curve_angle)))
      return;
    double v[AngleLaws::kMaxParams];
    laws_.at_shape(s, v);
    theta_ = s.curve_angle;
    clamped_ = !detail::set_base_params(engine_, v);
  }
  /// The curve angle in use, rad.
  double curve_angle() const noexcept { return theta_; }
  /// The base's inverse.
  const Engine& engine() const noexcept { return engine_; }

 private:
  Engine engine_;
  AngleLaws laws_;
  double theta_ = 0.0;
  bool clamped_ = false;
};

namespace detail {
template <class C, class = void>
struct follows_shape : std::false_type {};
template <class C>
struct follows_shape<C, std::void_t<decltype(std::declval<C&>().set_shape(ShapeIntegrals{}))>>
    : std::true_type {};
}  // namespace detail

/// @brief The real-time inverse of any identified model (see the file's comment): map, pre-stage,
/// core, post-stage, input range and command limits. step() is noexcept, allocates nothing and
/// does bounded work. Build one with make_model_inverse().
class ModelInverse {
 public:
  /// The model's own inverses.
  using Core = std::variant<PassThrough, BacklashInverseFeedforward, PrandtlIshlinskiiInverse,
                            RootInverse<ForwardModel>, CurveAngleFeedforward, OscillatorInverse,
                            AngleDependentInverse<BacklashInverseFeedforward>,
                            AngleDependentInverse<RootInverse<ForwardModel>>,
                            AngleDependentInverse<OscillatorInverse>>;
  /// What runs before the core: nothing, a Hammerstein lag's inverse, or a static polynomial's.
  using Stage = std::variant<std::monostate, LagInverse, RootInverse<Polynomial>>;

  /// @param core the model's inverse (inner units)
  /// @param pre the stage before it
  /// @param post a Wiener lag's inverse after it, or none
  /// @param map the Scaled map (identity by default)
  /// @param range the commands allowed, outer units (validated)
  /// @param limits the command limits, outer units (validated)
  /// @param friction the friction of the route's shape integrals (route-following cores)
  ModelInverse(Core core, Stage pre, std::optional<LagInverse> post, const ScaledMap& map,
               const InputRange& range, const CommandLimits& limits, double friction = 0.0)
      : core_(std::move(core)), pre_(std::move(pre)), post_(std::move(post)), map_(map),
        range_(range.unmapped(map.input_offset, map.input_scale)), shaper_(limits),
        friction_(friction) {
    range.validate("ModelInverse");
    limits.validate("ModelInverse");
    require(map.input_scale > 0.0 && std::isfinite(map.input_scale), "ModelInverse",
            "input_scale must be > 0 (got ", map.input_scale, ")");
    require(map.output_gain != 0.0 && std::isfinite(map.output_gain), "ModelInverse",
            "output_gain must be finite and not 0 (got ", map.output_gain, ")");
  }

  /// Start afresh from the initial state; the route (shape or curve angle) is kept.
  void reset() noexcept {
    std::visit([](auto& c) noexcept { c.reset(); }, core_);
    std::visit([](auto& s) noexcept { reset_stage(s); }, pre_);
    if (post_) post_->reset();
    guard_.reset();
    shaper_.reset();
    held_ = false;
  }

  /// @param y_d the desired output (outer units); a non-finite one holds the last command
  /// @param dt the time since the previous cycle, s
  /// @return the command (outer units), inside the range and the limits
  double step(double y_d, double dt) noexcept {
    held_ = !std::isfinite(y_d);
    if (held_) return shaper_.apply(NAN, dt);
    double v = (y_d - map_.output_offset) / map_.output_gain;
    v = std::visit([&](auto& s) noexcept { return step_stage(s, v, dt); }, pre_);
    double u = std::visit([&](auto& c) noexcept { return c.step(v, dt); }, core_);
    u = guard_.apply(u);
    status_ = guard_.status();
    if (post_) {
      u = guard_.apply(post_->step(u, dt));
      status_ = status_ | guard_.status() | post_->status();
    }
    return shaper_.apply(map_.input_offset + map_.input_scale * u, dt);
  }

  /// The last step's status: held (y_d not finite), out_of_range (the command was held inside
  /// the input range: its target unreachable there), not_converged (the root search ran out of
  /// evaluations), input_clamped (route parameters not valid), saturated (command limits), and
  /// the flags of the model steps behind them (e.g.\ slack).
  Status status() const noexcept {
    if (held_) return Status::held_nonfinite_input | shaper_.status();
    const Status core = std::visit([](const auto& c) noexcept { return c.status(); }, core_);
    const Status pre = std::visit([](const auto& s) noexcept { return stage_status(s); }, pre_);
    return core | pre | status_ | shaper_.status();
  }

  /// True when the core follows the route (CurveAngleModel, AngleDependent): set_shape() and
  /// set_curve_angle() change its parameters.
  bool follows_route() const noexcept {
    return std::visit(
        [](const auto& c) noexcept {
          return detail::follows_shape<std::decay_t<decltype(c)>>::value;
        },
        core_);
  }
  /// The friction coefficient of the route's shape integrals (route-following cores; else 0).
  double friction() const noexcept { return friction_; }
  /// Any route: its shape integrals (computed with friction()) and total angle; ignored by a
  /// core that does not follow the route.
  void set_shape(const ShapeIntegrals& s) noexcept {
    std::visit(
        [&](auto& c) noexcept {
          if constexpr (detail::follows_shape<std::decay_t<decltype(c)>>::value) c.set_shape(s);
        },
        core_);
  }
  /// Uniform curvature of total angle theta, rad; ignored by a core that does not follow it.
  void set_curve_angle(double theta) noexcept {
    std::visit(
        [&](auto& c) noexcept {
          if constexpr (detail::follows_shape<std::decay_t<decltype(c)>>::value)
            c.set_curve_angle(theta);
        },
        core_);
  }
  /// The core (e.g.\ to read the root search's evaluations).
  const Core& core() const noexcept { return core_; }
  /// The Scaled map.
  const ScaledMap& map() const noexcept { return map_; }
  /// The input range in the inner (model's) units.
  const InputRange& inner_range() const noexcept { return range_; }

 private:
  static void reset_stage(std::monostate&) noexcept {}
  template <class S>
  static void reset_stage(S& s) noexcept {
    s.reset();
  }
  static double step_stage(std::monostate&, double v, double) noexcept { return v; }
  template <class S>
  static double step_stage(S& s, double v, double dt) noexcept {
    return s.step(v, dt);
  }
  static Status stage_status(const std::monostate&) noexcept { return Status::ok; }
  template <class S>
  static Status stage_status(const S& s) noexcept {
    // a polynomial stage's out_of_range would only say that its own (unbounded) search failed
    return s.status();
  }

  Core core_;
  Stage pre_;
  std::optional<LagInverse> post_;
  ScaledMap map_;
  InputRange range_;
  RangeGuard guard_{range_};
  CommandShaper shaper_;
  double friction_ = 0.0;
  Status status_ = Status::ok;
  bool held_ = false;
};

}  // namespace tendonsheath
