// Loading compensators saved by Python's `Compensator.to_json` (format
// "tendonsheath.compensator", version 1) into the real-time core.
//
// OPTIONAL and OUTSIDE the real-time path: it needs nlohmann/json (Debian's
// nlohmann-json3-dev, CMake target nlohmann_json::nlohmann_json), reads files and allocates.
// Load once at start-up; the returned LoadedCompensator's step() is the core's: noexcept,
// no allocation. Strict, like Python's loader: a missing, unknown, null or mistyped key is an
// error naming the key. null stands for an unbounded limit (JSON has no inf).
//
// With or without C++ exceptions (docs/cpp-without-exceptions.md): each loader has a try_ form
// that returns a tendonsheath::Result (the compensator, or the message naming the file and the
// key), e.g. try_load_compensator_json(path); the plain form returns the object and throws
// std::invalid_argument with that message (without exceptions: the error handler, then
// std::abort(), as a constructor called directly does).
#pragma once

#include <cstdio>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

#include "../bench/erased_compensator.hpp"
#include "../compensators/compensator_list.hpp"
#include "../compensators/continuum_feedforward.hpp"
#include "../compensators/curve_angle_feedforward.hpp"
#include "../compensators/encoder_loop.hpp"
#include "../compensators/inverse_feedforward.hpp"
#include "../compensators/learned_feedforward.hpp"
#include "../compensators/make_model_inverse.hpp"
#include "../compensators/tip_loop.hpp"
#include "json_models.hpp"

/// @brief Loading compensators saved by Python's `to_json` into the real-time core (optional
/// header tendonsheath/io/json.hpp, needs nlohmann/json).
///
/// Outside the real-time path: it reads files, allocates, and names a missing, unknown, null or
/// mistyped key in its error: a Result from the try_ loaders (with or without exceptions), a
/// std::invalid_argument from the others. Load once at start-up; the LoadedCompensator's step() is
/// the core's: noexcept, no allocation.
namespace tendonsheath::io {

namespace detail {

// `now`, or `old` in a file written before the setting was renamed (docs/vocabulary.md)
inline std::string renamed_key(const json& f, const char* now, const char* old) {
  return f.is_object() && f.contains(old) ? old : now;
}

inline CommandLimits limits(const json& file, const std::string& where) {
  const json& l = member(file, "limits", where);
  const std::string w = where + ": limits";
  check_keys(l, {"min", "max", "max_rate"}, {}, w);
  const double inf = std::numeric_limits<double>::infinity();
  CommandLimits out;
  if (l.contains("min")) out.min = number(l, "min", w, -inf);
  if (l.contains("max")) out.max = number(l, "max", w, inf);
  if (l.contains("max_rate")) out.max_rate = number(l, "max_rate", w, inf);
  return out;
}

}  // namespace detail

/// The affine map of a Python `Scaled` model (tendonsheath::ScaledMap).
using ScaledMap = tendonsheath::ScaledMap;

/// A model file ("tendonsheath.model") reduced to what its inverse needs.
struct InvertibleModel {
  std::string name;                  ///< Backlash, BoucWenBacklash or PrandtlIshlinskii
  BacklashInverseParams backlash{};  ///< c_r, c_l, B_r, B_l (Backlash, BoucWenBacklash)
  PrandtlIshlinskiiParams pi{};      ///< PrandtlIshlinskii
  ScaledMap map{};                   ///< identity unless the file held a Scaled model
};

namespace detail {

// the model of a "tendonsheath.model" document (what invertible_model_from_json returns)
inline InvertibleModel invertible_model(const json& m, const std::string& where) {
  InvertibleModel out;
  check_format(m, "tendonsheath.model", where);
  if (failed()) return out;
  const json& name = member(m, "model", where);
  out.name = name.is_string() ? name.get<std::string>() : shown(name);
  if (out.name == "Scaled") {
    check_keys(m, {"format", "version", "model", "inner", "map", "input_range"}, {"inner", "map"},
               where);
    if (failed()) return out;
    const ScaledMap map = scaled_map(member(m, "map", where), where + ": map");
    if (failed()) return out;
    out = invertible_model(member(m, "inner", where), where + ": inner");
    if (failed()) return out;
    if (out.map.input_scale != 1.0 || out.map.output_gain != 1.0 || out.map.input_offset != 0.0 ||
        out.map.output_offset != 0.0)
      fail(where, "a Scaled model inside a Scaled model is not supported");
    out.map = map;
    return out;
  }
  check_keys(m, kPlainKeys, {"params"}, where);
  if (failed()) return out;
  const json& p = member(m, "params", where);
  const std::string w = where + ": params";
  if (out.name == "Backlash" || out.name == "BoucWenBacklash") {
    std::set<std::string> keys;  // the model's parameter rows (its options are not in "params")
    const auto parameter = [&](const auto& row) {
      if (row.role == Role::parameter) keys.insert(row.name);
    };
    if (out.name == "BoucWenBacklash") for_each_field<BoucWenBacklashParams>(parameter);
    else for_each_field<BacklashParams>(parameter);
    check_keys(p, keys, keys, w);
    for (const auto& k : keys) number(p, k, w);  // every one a number, used or not
    // the inverse takes the backlash rows (BacklashInverseParams derives from BacklashParams)
    for_each_field<BacklashParams>([&](const auto& row) {
      out.backlash.*row.member = number(p, row.name, w);
    });
  } else if (out.name == "PrandtlIshlinskii") {
    check_keys(p, {"thresholds", "weights"}, {"thresholds", "weights"}, w);
    out.pi.thresholds = numbers(p, "thresholds", w);
    out.pi.weights = numbers(p, "weights", w);
  } else {
    fail(where, "key 'model': the C++ loader inverts Backlash, BoucWenBacklash, "
                "PrandtlIshlinskii and Scaled around them (got " + shown(name) + ")");
  }
  return out;
}

}  // namespace detail

/// The model of a "tendonsheath.model" document (a Scaled model around an invertible one, or an
/// invertible one), or the message, starting with `where`, naming the bad key.
inline Result<InvertibleModel> try_invertible_model_from_json(const json& m,
                                                              const std::string& where) {
  return tendonsheath::detail::result_of<InvertibleModel>(
      [&] { return std::optional<InvertibleModel>(detail::invertible_model(m, where)); });
}

/// The model of a "tendonsheath.model" document (a Scaled model around an invertible one, or an
/// invertible one). Throws std::invalid_argument, message starting with `where`, naming the bad key.
inline InvertibleModel invertible_model_from_json(const json& m, const std::string& where) {
  return try_invertible_model_from_json(m, where).value();
}

/// The CurveAngleFeedforward parameters of a "tendonsheath.compensator" document (Python's names:
/// curve_angle, smoothing; a null max_correction_rate is unbounded). Throws std::invalid_argument,
/// message starting with `where`, naming a missing or mistyped key.
inline CurveAngleFeedforwardParams curve_angle_feedforward_params(const json& f,
                                                                 const std::string& where) {
  const double inf = std::numeric_limits<double>::infinity();
  CurveAngleFeedforwardParams p;
  p.friction = detail::number(f, "friction", where);
  if (f.contains("compliance")) {  // a file written before docs/vocabulary.md
    const double compliance = detail::number(f, "compliance", where);  // L / EA
    require_positive(compliance, where.c_str(), "CurveAngleFeedforward: length / stiffness");
    p.stiffness = 1.0 / compliance;  // as Python reads it: any EA, L with L / EA = compliance
    p.length = 1.0;
  } else {  // each checked as Python checks it, before their ratio is
    const double stiffness = detail::number(f, "stiffness", where);
    const double length = detail::number(f, "length", where);
    require_positive(stiffness, where.c_str(), "CurveAngleFeedforward: stiffness");
    require_positive(length, where.c_str(), "CurveAngleFeedforward: length");
    p.stiffness = stiffness;
    p.length = length;
  }
  p.pretension = detail::number(f, "pretension", where);
  p.load_force = detail::number(f, "load_force", where);
  p.load_stiffness = detail::number(f, "load_stiffness", where);
  p.proximal_radius = detail::number(f, "proximal_radius", where);
  p.distal_radius = detail::number(f, "distal_radius", where);
  p.curve_angle = detail::number(f, "curve_angle", where);
  if (f.contains("play")) p.play = detail::number(f, "play", where);  // absent in older files
  p.smoothing = detail::number(f, "smoothing", where);
  p.max_correction_rate = detail::number(f, "max_correction_rate", where, inf);
  p.limits = detail::limits(f, where);
  return p;
}

/// The ContinuumFeedforward parameters of a "tendonsheath.compensator" document (mode "exact" or
/// "published"). Throws std::invalid_argument, message starting with `where`, naming a missing or
/// mistyped key.
inline ContinuumFeedforwardParams continuum_feedforward_params(const json& f,
                                                               const std::string& where) {
  ContinuumFeedforwardParams p;
  p.friction = detail::number(f, "friction", where);
  p.length = detail::number(f, detail::renamed_key(f, "length", "sheath_length"), where);
  p.stiffness = detail::number(f, "stiffness", where);
  p.pretension = detail::number(f, "pretension", where);
  p.curve_angle = detail::number(f, detail::renamed_key(f, "curve_angle", "total_angle"), where);
  p.bending_stiffness = detail::number(f, "bending_stiffness", where);
  p.tendon_offset = detail::number(f, "tendon_offset", where);
  p.backbone_length = detail::number(f, "backbone_length", where);
  p.proximal_radius = detail::number(f, "proximal_radius", where);
  p.gap_factor = detail::number(f, "gap_factor", where);
  if (f.contains("play")) p.play = detail::number(f, "play", where);  // absent in older files
  p.smoothing = detail::number(f, "smoothing", where);
  const json& mode = detail::member(f, "mode", where);
  if (mode == "exact") p.mode = ContinuumMode::Exact;
  else if (mode == "published") p.mode = ContinuumMode::Published;
  else detail::fail(where, "key 'mode' must be \"exact\" or \"published\" (got " + detail::shown(mode) + ")");
  p.limits = detail::limits(f, where);
  return p;
}

/// The feedforwards a compensator file can hold that have a reader of their own here.
using FeedforwardsWithReader = TypeList<BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
                                        CurveAngleFeedforward, ContinuumFeedforward, ModelInverse>;

/// Whether compensator C of the list (compensator_list.hpp) is read from its table: a feedforward
/// (step(y_d, dt)) with a parameter table and no reader of its own, whose file holds one key per
/// row (its Python class's settings).
template <class C>
struct read_from_table
    : std::bool_constant<has_params_table<C>::value && compensator_step_inputs<C>() == 1 &&
                         !list_contains_v<FeedforwardsWithReader, C>> {};

/// The compensators of the list read from their tables (read_from_table).
using FeedforwardsFromTable = filter_list_t<Compensators, read_from_table>;

/// A loaded compensator: one of the core's feedforwards (validated by its constructor), with the
/// affine map of a Scaled model applied around a BacklashInverseFeedforward or
/// PrandtlIshlinskiiFeedforward built by hand (a ModelInverse holds its own map: an
/// InverseFeedforward file loads as one, with the identity map here). step() is noexcept and
/// allocates nothing.
class LoadedCompensator {
 public:
  /// The feedforwards a compensator file can hold.
  using Engine = apply_list_t<decltype(FeedforwardsWithReader{} + FeedforwardsFromTable{}),
                              std::variant>;

  /// @param kind the Python class name of the compensator
  /// @param engine the feedforward, built (and validated) from the file
  /// @param map the affine map of a Scaled model around the inverse (identity by default)
  LoadedCompensator(std::string kind, Engine engine, ScaledMap map = {})
      : kind_(std::move(kind)), engine_(std::move(engine)), map_(map) {}

  /// @param y_d the desired output, in the file's (outer) units
  /// @param dt the time since the previous cycle, s
  /// @return the motor command: input_offset + input_scale * engine.step((y_d - output_offset) /
  /// output_gain, dt), plus the learned correction table when the file holds one (a
  /// LearnedFeedforward); with a loop (an EncoderLoop or TipLoop file) and no reading given, the
  /// loop falls back (status fallback): use step(y_d, reading, dt)
  double step(double y_d, double dt) noexcept { return step(y_d, NAN, dt); }
  /// @brief One cycle with the loop's sensor: the feedforward's command (plus the learned
  /// correction of a LearnedFeedforward), corrected by the loop when the file holds one, else the
  /// reading is not used.
  /// @param y_d the desired output, in the file's (outer) units
  /// @param reading the loop's sensor now (NaN: no reading this cycle): the motor encoder, rad,
  /// for an EncoderLoop; the tip angle, in y_d's units, for a TipLoop
  /// @param dt the time since the previous cycle, s
  /// @return the servo command
  double step(double y_d, double reading, double dt) noexcept {
    const double inner_y = (y_d - map_.output_offset) / map_.output_gain;
    const double x = std::visit([&](auto& e) noexcept { return e.step(inner_y, dt); }, engine_);
    double target = map_.input_offset + map_.input_scale * x;
    if (learned_) target = learned_->correct(target, dt);
    if (loop_) return loop_->correct(target, reading, dt);
    if (tip_) return tip_->correct(target, y_d, reading, dt);
    return target;
  }
  /// Start afresh from the initial state, as after construction; the parameters (and any route,
  /// shape or curve angle set since) are kept.
  void reset() noexcept {
    std::visit([](auto& e) noexcept { e.reset(); }, engine_);
    if (learned_) learned_->reset();
    if (loop_) loop_->reset();
    if (tip_) tip_->reset();
  }
  /// The last step's status flags (see Status).
  Status status() const noexcept {
    Status s = std::visit([](const auto& e) noexcept { return e.status(); }, engine_);
    if (learned_) s |= learned_->status();
    if (loop_) return s | loop_->status();
    return tip_ ? s | tip_->status() : s;
  }
  /// Put an encoder loop around the feedforward (what an EncoderLoop file holds); kind() is then
  /// "EncoderLoop".
  void set_encoder_loop(const EncoderLoop& loop) {
    loop_ = loop;
    tip_.reset();
    kind_ = "EncoderLoop";
  }
  /// The encoder loop, when the file holds one (nullptr otherwise).
  const EncoderLoop* encoder_loop() const noexcept { return loop_ ? &*loop_ : nullptr; }
  /// Add a learned correction table to the feedforward's command (what a LearnedFeedforward file
  /// holds; inside the encoder or tip loop, if any); kind() is then "LearnedFeedforward".
  void set_learned_correction(const LearnedCorrection& learned) {
    learned_ = learned;
    kind_ = "LearnedFeedforward";
  }
  /// The learned correction table, when the file holds one (nullptr otherwise).
  const LearnedCorrection* learned_correction() const noexcept {
    return learned_ ? &*learned_ : nullptr;
  }
  /// Put a tip loop around the feedforward (what a TipLoop file holds); kind() is then "TipLoop".
  void set_tip_loop(const TipLoop& loop) {
    tip_ = loop;
    loop_.reset();
    kind_ = "TipLoop";
  }
  /// The tip loop, when the file holds one (nullptr otherwise).
  const TipLoop* tip_loop() const noexcept { return tip_ ? &*tip_ : nullptr; }
  /// The route's shape for a feedforward that follows it (CurveAngleFeedforward, a ModelInverse
  /// of a CurveAngleModel or AngleDependent model; ignored by the others), and its curve angle for
  /// a tip loop's gain schedule.
  void set_shape(const ShapeIntegrals& s) noexcept {
    if (auto* c = std::get_if<CurveAngleFeedforward>(&engine_)) c->set_shape(s);
    if (auto* m = std::get_if<ModelInverse>(&engine_)) m->set_shape(s);
    if (tip_) tip_->set_shape(s);
  }
  /// Uniform curvature of total angle theta (rad) for a feedforward that follows the route, and
  /// the curve angle of a tip loop's gain schedule.
  void set_curve_angle(double theta) noexcept {
    if (auto* c = std::get_if<CurveAngleFeedforward>(&engine_)) c->set_curve_angle(theta);
    if (auto* m = std::get_if<ModelInverse>(&engine_)) m->set_curve_angle(theta);
    if (tip_) tip_->set_curve_angle(theta);
  }
  const std::string& kind() const noexcept { return kind_; }  ///< the Python class name
  Engine& engine() noexcept { return engine_; }  ///< the feedforward itself, e.g.\ for CurveAngleFeedforward::set_curve_angle
  /// The affine map around the inverse.
  const ScaledMap& map() const noexcept { return map_; }

 private:
  std::string kind_;
  Engine engine_;
  ScaledMap map_;
  std::optional<LearnedCorrection> learned_;
  std::optional<EncoderLoop> loop_;
  std::optional<TipLoop> tip_;
};

/// The InverseSettings of an InverseFeedforward file: smoothing, limits, and the optional
/// input_range ([lo, hi] or null; absent: the model's own "input_range", if any), range_margin
/// (default 0.1) and filter_hz (null or absent: the default). Throws std::invalid_argument naming
/// a bad key (without exceptions, inside a try_ loader: that loader's Result holds the message).
inline InverseSettings inverse_settings(const json& f, const std::string& where) {
  InverseSettings s;
  s.smoothing = detail::number(f, "smoothing", where);
  s.limits = detail::limits(f, where);
  const double margin = f.contains("range_margin") ? detail::number(f, "range_margin", where) : 0.1;
  require_non_negative(margin, where.c_str(), "range_margin");  // Python's rule and message
  if (detail::failed()) return s;
  const auto range = f.contains("input_range")
                         ? model_input_range(f, where)
                         : model_input_range(detail::member(f, "model", where), where + ": model");
  if (detail::failed()) return s;
  if (range) {
    require(std::isfinite(range->first) && std::isfinite(range->second) &&
                range->first < range->second,
            where, "input_range needs finite lo < hi (got lo=", range->first, ", hi=", range->second,
            ")");  // Python's message
    if (detail::failed()) return s;
    s.range = InputRange::identified(range->first, range->second, margin);
  }
  if (f.contains("filter_hz") && !detail::member(f, "filter_hz", where).is_null()) {
    s.filter_hz = detail::number(f, "filter_hz", where);
    require(std::isfinite(s.filter_hz) && s.filter_hz > 0.0, where,
            "filter_hz must be > 0 or None/null (got ", s.filter_hz, ")");  // Python's message
  }
  return s;
}

namespace detail {

// T built by make<T>(args...): its failed check reported as "<prefix>: <message>" (the message
// alone when prefix is empty), as the constructor's exception would have been (std::nullopt then)
template <class T, class... Args>
std::optional<T> built(const std::string& prefix, Args&&... args) {
  Result<T> r = tendonsheath::make<T>(std::forward<Args>(args)...);
  if (r.ok()) return std::optional<T>(std::move(r).value());
  tendonsheath::detail::report_error(prefix.empty() ? r.error() : prefix + ": " + r.error());
  return std::nullopt;
}

// Python's InverseFeedforward: a ModelInverse (its Scaled map inside it).
inline std::optional<LoadedCompensator> inverse_from_json(const json& f, const std::string& where) {
  check_keys(f, {"format", "version", "compensator", "model", "smoothing", "limits", "input_range",
                 "range_margin", "filter_hz"},
             {"model", "smoothing", "limits"}, where);
  if (failed()) return std::nullopt;
  const InverseModel m = inverse_model_from_json(member(f, "model", where), where + ": model");
  if (failed()) return std::nullopt;
  const InverseSettings s = inverse_settings(f, where);
  if (failed()) return std::nullopt;
  ModelInverse inverse = make_model_inverse(m, s, where);
  if (failed()) return std::nullopt;
  return LoadedCompensator("InverseFeedforward", std::move(inverse));
}

inline const std::set<std::string> kCurveAngleKeys{
    "format", "version", "compensator", "friction", "stiffness", "length", "pretension",
    "load_force", "load_stiffness", "proximal_radius", "distal_radius", "curve_angle",
    "smoothing", "max_correction_rate", "limits"};
inline const std::set<std::string> kContinuumKeys{
    "format", "version", "compensator", "friction", "length", "stiffness", "pretension",
    "curve_angle", "bending_stiffness", "tendon_offset", "backbone_length", "proximal_radius",
    "gap_factor", "smoothing", "mode", "limits"};

// Settings renamed in docs/vocabulary.md: a file written before holds `old` instead of `now`.
struct RenamedKeys {
  std::vector<std::string> now;
  std::string old;
};
inline const std::vector<RenamedKeys> kCurveAngleRenamed{{{"stiffness", "length"}, "compliance"}};
inline const std::vector<RenamedKeys> kContinuumRenamed{{{"length"}, "sheath_length"},
                                                        {{"curve_angle"}, "total_angle"}};

// The keys a file must hold: `keys`, with the old name of each renamed setting it uses.
inline std::set<std::string> keys_of_file(const json& f, std::set<std::string> keys,
                                          const std::vector<RenamedKeys>& renames) {
  for (const auto& r : renames) {
    if (!f.is_object() || !f.contains(r.old)) continue;
    for (const auto& k : r.now) keys.erase(k);
    keys.insert(r.old);
  }
  return keys;
}

// the keys of a feedforward's file (those `keys_of_file` gives, and the optional play) checked
inline void check_feedforward_keys(const json& f, const std::set<std::string>& all,
                                   const std::vector<RenamedKeys>& renames,
                                   const std::string& where) {
  const auto keys = keys_of_file(f, all, renames);
  std::set<std::string> allowed = keys;
  allowed.insert("play");  // optional: files written before it was a setting lack it
  check_keys(f, allowed, keys, where);
}

inline std::optional<LoadedCompensator> compensator(const json& f, const std::string& where);

inline const std::set<std::string> kEncoderLoopKeys{
    "format", "version", "compensator", "feedforward", "kp", "ki", "kd",
    "derivative_cutoff_hz", "max_correction", "limits"};

// Python's EncoderLoop: its feedforward (a compensator file of its own) and the loop's gains.
inline std::optional<LoadedCompensator> encoder_loop_from_json(const json& f,
                                                               const std::string& where) {
  check_keys(f, kEncoderLoopKeys, kEncoderLoopKeys, where);
  if (failed()) return std::nullopt;
  const json& inner = member(f, "feedforward", where);
  if (inner.is_object() && inner.contains("compensator") && inner["compensator"] == "EncoderLoop")
    return fail(where, "key 'feedforward' must be a feedforward, not another EncoderLoop"),
           std::nullopt;
  std::optional<LoadedCompensator> out = compensator(inner, where + ": feedforward");
  if (failed() || !out) return std::nullopt;
  EncoderLoopParams p;
  p.kp = number(f, "kp", where);
  p.ki = number(f, "ki", where);
  p.kd = number(f, "kd", where);
  p.derivative_cutoff_hz = number(f, "derivative_cutoff_hz", where);
  p.max_correction = number(f, "max_correction", where, std::numeric_limits<double>::infinity());
  p.limits = limits(f, where);
  if (failed()) return std::nullopt;
  const auto loop = built<EncoderLoop>(where, p);
  if (!loop) return std::nullopt;
  out->set_encoder_loop(*loop);
  return out;
}

inline const std::set<std::string> kLearnedKeys{
    "format", "version", "compensator", "feedforward", "table", "table_dt", "hold_last", "limits"};

// Python's LearnedFeedforward: its feedforward (a compensator file of its own) and the table.
inline std::optional<LoadedCompensator> learned_from_json(const json& f, const std::string& where) {
  check_keys(f, kLearnedKeys, kLearnedKeys, where);
  if (failed()) return std::nullopt;
  const json& inner = member(f, "feedforward", where);
  if (inner.is_object() && inner.contains("compensator")) {
    const json& k = inner["compensator"];
    if (k == "EncoderLoop" || k == "TipLoop" || k == "LearnedFeedforward")
      return fail(where, "key 'feedforward' must be a feedforward, not an " +
                             k.get<std::string>() + " (put the loop around the LearnedFeedforward)"),
             std::nullopt;
  }
  std::optional<LoadedCompensator> out = compensator(inner, where + ": feedforward");
  if (failed() || !out) return std::nullopt;
  LearnedFeedforwardParams p;
  p.table_dt = number(f, "table_dt", where);
  const json& hold = member(f, "hold_last", where);
  if (failed()) return std::nullopt;
  if (!hold.is_boolean())
    return fail(where, "key 'hold_last' must be true or false (got " + shown(hold) + ")"),
           std::nullopt;
  p.hold_last = hold.get<bool>();
  p.limits = limits(f, where);
  std::vector<double> table = numbers(f, "table", where);
  if (failed()) return std::nullopt;
  const auto learned = built<LearnedCorrection>(where, std::move(table), p);
  if (!learned) return std::nullopt;
  out->set_learned_correction(*learned);
  return out;
}

inline const std::set<std::string> kTipLoopKeys{
    "format", "version", "compensator", "feedforward", "kp", "ki", "kd",
    "derivative_cutoff_hz", "max_correction", "schedule", "limits"};

// the tip loop's gain schedule, [[curve_angle, gain], ...] (up to 8 points), into p
inline void tip_schedule(const json& f, TipLoopParams& p, const std::string& where) {
  const json& schedule = member(f, "schedule", where);
  if (!schedule.is_array() || schedule.size() > TipLoopParams::kMaxSchedule)
    return fail(where, "key 'schedule' must be a list of at most 8 [curve_angle, gain] pairs");
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const json& row = schedule[i];
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number())
      return fail(where, "key 'schedule': entry " + std::to_string(i) +
                             " must be a [curve_angle, gain] pair of numbers (got " + shown(row) +
                             ")");
    p.schedule_angles[i] = row[0].get<double>();
    p.schedule_gains[i] = row[1].get<double>();
  }
  p.schedule_size = schedule.size();
}

// Python's TipLoop: its feedforward (a compensator file of its own), the loop's gains and its gain
// schedule ([[curve_angle, gain], ...], up to 8 points).
inline std::optional<LoadedCompensator> tip_loop_from_json(const json& f, const std::string& where) {
  check_keys(f, kTipLoopKeys, kTipLoopKeys, where);
  if (failed()) return std::nullopt;
  const json& inner = member(f, "feedforward", where);
  if (inner.is_object() && inner.contains("compensator") &&
      (inner["compensator"] == "TipLoop" || inner["compensator"] == "EncoderLoop"))
    return fail(where, "key 'feedforward' must be a feedforward, not a " +
                           shown(inner["compensator"])),
           std::nullopt;
  std::optional<LoadedCompensator> out = compensator(inner, where + ": feedforward");
  if (failed() || !out) return std::nullopt;
  TipLoopParams p;
  p.kp = number(f, "kp", where);
  p.ki = number(f, "ki", where);
  p.kd = number(f, "kd", where);
  p.derivative_cutoff_hz = number(f, "derivative_cutoff_hz", where);
  p.max_correction = number(f, "max_correction", where, std::numeric_limits<double>::infinity());
  if (failed()) return std::nullopt;
  tip_schedule(f, p, where);
  p.limits = limits(f, where);
  if (failed()) return std::nullopt;
  const auto loop = built<TipLoop>(where, p);
  if (!loop) return std::nullopt;
  out->set_tip_loop(*loop);
  return out;
}

// row `row` of a compensator's table from key row.name of its file: a number (an int one an
// integer), true or false, or a CommandLimits object
template <class P, class T>
void table_row(const json& f, P& p, const ParamField<P, T>& row, const std::string& where) {
  if constexpr (std::is_same_v<T, bool>) {
    const json& v = member(f, row.name, where);
    if (failed()) return;
    if (!v.is_boolean())
      return fail(where, std::string("key '") + row.name + "' must be true or false (got " +
                             shown(v) + ")");
    p.*row.member = v.get<bool>();
  } else if constexpr (std::is_integral_v<T>) {
    p.*row.member = static_cast<T>(integer(f, row.name, where));
  } else if constexpr (std::is_floating_point_v<T>) {
    p.*row.member = number(f, row.name, where);
  } else {
    static_assert(std::is_same_v<T, CommandLimits>,
                  "a compensator read from its table has number, bool and CommandLimits rows");
    p.*row.member = limits(f, where);
  }
}

// compensator C (read_from_table) from its file: one key per row of its table, all required
template <class C>
std::optional<LoadedCompensator> from_table(const json& f, const std::string& where) {
  using P = typename C::Params;
  std::set<std::string> rows;
  for_each_field<P>([&](const auto& row) { rows.insert(row.name); });
  std::set<std::string> allowed = rows;
  allowed.insert({"format", "version", "compensator"});
  check_keys(f, allowed, rows, where);
  if (failed()) return std::nullopt;
  P p{};
  for_each_field<P>([&](const auto& row) {
    if (!failed()) table_row(f, p, row, where);
  });
  if (failed()) return std::nullopt;
  auto engine = built<C>(where, p);
  if (!engine) return std::nullopt;
  return LoadedCompensator(compensator_kind<C>(), std::move(*engine));
}

// a compensator read from its table whose kind is `kind` (std::nullopt when none is)
inline std::optional<LoadedCompensator> from_a_table(const json& kind, const json& f,
                                                     const std::string& where, bool& found) {
  std::optional<LoadedCompensator> out;
  found = any_type(FeedforwardsFromTable{}, [&](auto tag) {
    using C = typename decltype(tag)::type;
    if (kind != compensator_kind<C>()) return false;
    out = from_table<C>(f, where);
    return true;
  });
  return out;
}

// the kinds of file compensator() reads, for its message
inline std::string known_compensators() {
  std::set<std::string> known{"ContinuumFeedforward", "CurveAngleFeedforward", "EncoderLoop",
                              "InverseFeedforward",   "LearnedFeedforward",    "TipLoop"};
  for_each_type(FeedforwardsFromTable{},
                [&](auto tag) { known.insert(compensator_kind<typename decltype(tag)::type>()); });
  std::string out;
  for (const auto& k : known) out += (out.empty() ? "" : ", ") + k;
  return out;
}

// a compensator file (what compensator_from_json loads); std::nullopt once a check has failed
inline std::optional<LoadedCompensator> compensator(const json& f, const std::string& where) {
  check_format(f, "tendonsheath.compensator", where);
  if (failed()) return std::nullopt;
  const json& kind = member(f, "compensator", where);
  if (kind == "InverseFeedforward") return inverse_from_json(f, where);
  if (kind == "EncoderLoop") return encoder_loop_from_json(f, where);
  if (kind == "LearnedFeedforward") return learned_from_json(f, where);
  if (kind == "TipLoop") return tip_loop_from_json(f, where);
  if (kind == "CurveAngleFeedforward") {
    check_feedforward_keys(f, kCurveAngleKeys, kCurveAngleRenamed, where);
    if (failed()) return std::nullopt;
    const CurveAngleFeedforwardParams p = curve_angle_feedforward_params(f, where);
    if (failed()) return std::nullopt;
    auto engine = built<CurveAngleFeedforward>(where, p);
    if (!engine) return std::nullopt;
    return LoadedCompensator("CurveAngleFeedforward", std::move(*engine));
  }
  if (kind == "ContinuumFeedforward") {
    check_feedforward_keys(f, kContinuumKeys, kContinuumRenamed, where);
    if (failed()) return std::nullopt;
    const ContinuumFeedforwardParams p = continuum_feedforward_params(f, where);
    if (failed()) return std::nullopt;
    auto engine = built<ContinuumFeedforward>(where, p);
    if (!engine) return std::nullopt;
    return LoadedCompensator("ContinuumFeedforward", std::move(*engine));
  }
  if (kind == "LoadCompensated" || kind == "CoupledFeedforward") {  // their step takes more inputs
    fail(where, "key 'compensator': a " + kind.get<std::string>() + " steps with " +
                    (kind == "LoadCompensated" ? "the measured load each cycle: load it "
                                                 "with io::load_compensated_from_json"
                                               : "every joint each cycle: load it with "
                                                 "io::coupled_feedforward_from_json") +
                    " (tendonsheath/io/json_multi_input.hpp)");
    return std::nullopt;
  }
  bool found = false;
  std::optional<LoadedCompensator> from_its_table = from_a_table(kind, f, where, found);
  if (found) return from_its_table;
  fail(where, "key 'compensator': unknown compensator " + shown(kind) + " (known: " +
                  known_compensators() + ")");
  return std::nullopt;
}

}  // namespace detail

/// A compensator from the parsed contents of a "tendonsheath.compensator" file, or the message,
/// starting with `where`, naming the bad key (with or without exceptions).
inline Result<LoadedCompensator> try_compensator_from_json(const json& f,
                                                           const std::string& where = "compensator") {
  return tendonsheath::detail::result_of<LoadedCompensator>(
      [&] { return detail::compensator(f, where); });
}

/// A compensator from the parsed contents of a "tendonsheath.compensator" file. Throws
/// std::invalid_argument, message starting with `where`, naming the bad key.
inline LoadedCompensator compensator_from_json(const json& f, const std::string& where = "compensator") {
  return try_compensator_from_json(f, where).value();
}

namespace detail {

// nlohmann/json's SAX events into a document, keeping the keys leading to the value being read
// ("limits.max"): a number too large for a double is an error nlohmann reports with no key to
// name. Its parse_error() keeps the message instead of throwing, so reading a file throws
// nothing (with or without exceptions) and says the same either way.
class JsonReader {
 public:
  bool null() { return put(json(nullptr)); }
  bool boolean(bool v) { return put(json(v)); }
  bool number_integer(json::number_integer_t v) { return put(json(v)); }
  bool number_unsigned(json::number_unsigned_t v) { return put(json(v)); }
  bool number_float(json::number_float_t v, const json::string_t& /*text*/) { return put(json(v)); }
  bool string(json::string_t& v) { return put(json(std::move(v))); }
  bool binary(json::binary_t& v) { return put(json::binary(std::move(v))); }
  bool start_object(std::size_t /*elements*/) {
    open_.push_back(place(json::object()));
    keys_.emplace_back();
    return true;
  }
  bool key(json::string_t& k) {
    keys_.back() = k;
    slot_ = &(*open_.back())[k];  // (an object: operator[] inserts, never throws)
    return true;
  }
  bool end_object() {
    open_.pop_back();
    keys_.pop_back();
    return true;
  }
  bool start_array(std::size_t /*elements*/) {
    open_.push_back(place(json::array()));
    return true;
  }
  bool end_array() {
    open_.pop_back();
    return true;
  }
  // a syntax error (json::parse_error), or a number beyond a double (json::out_of_range)
  template <class Error>
  bool parse_error(std::size_t /*position*/, const std::string& /*token*/, const Error& e) {
    if (std::is_same<Error, json::parse_error>::value) {
      error_ = std::string("not valid JSON (") + e.what() + ")";
    } else {
      std::string key;
      for (const auto& k : keys_) key += (key.empty() ? "" : ".") + k;
      error_ = (key.empty() ? std::string("a value") : "key '" + key + "'") + " is out of range (" +
               e.what() + ")";
    }
    return false;
  }
  /// What was wrong with the text (empty: it parsed).
  const std::string& error() const noexcept { return error_; }
  /// The document read.
  json& document() noexcept { return root_; }

 private:
  // v put where the next value goes: the root, the end of the open array, or the key just read
  json* place(json v) {
    if (open_.empty()) {
      root_ = std::move(v);
      return &root_;
    }
    json& parent = *open_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(v));  // (an open array's element is its last: never moved)
      return &parent.back();
    }
    *slot_ = std::move(v);
    return slot_;
  }
  bool put(json v) {
    place(std::move(v));
    return true;
  }

  json root_;
  std::vector<json*> open_;
  json* slot_ = nullptr;
  std::vector<std::string> keys_;
  std::string error_;
};

// the parsed contents of the file at path (what read_json_file returns)
inline std::optional<json> json_file(const std::string& path) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) return fail(path, "cannot open the file"), std::nullopt;
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, in)) > 0;) text.append(buffer, n);
  std::fclose(in);
  JsonReader reader;
  if (!json::sax_parse(text, &reader)) return fail(path, reader.error()), std::nullopt;
  return std::move(reader.document());
}

}  // namespace detail

/// The parsed contents of a JSON file (read with stdio: the library uses no iostreams), or the
/// message naming the file (and the key of a number beyond a double's range) when it is
/// unreadable, not valid JSON, or holds such a number. With or without exceptions.
inline Result<json> try_read_json_file(const std::string& path) {
  return tendonsheath::detail::result_of<json>([&] { return detail::json_file(path); });
}

/// The parsed contents of a JSON file (read with stdio: the library uses no iostreams). An
/// unreadable file, invalid JSON or a number beyond a double's range is a
/// std::invalid_argument naming the file (and the key of the number).
inline json read_json_file(const std::string& path) { return try_read_json_file(path).value(); }

/// A compensator from a file written by Python's `to_json(path)`, or the message naming the file
/// and the bad key (with or without exceptions).
inline Result<LoadedCompensator> try_load_compensator_json(const std::string& path) {
  return tendonsheath::detail::result_of<LoadedCompensator>([&]() -> std::optional<LoadedCompensator> {
    const std::optional<json> file = detail::json_file(path);
    if (detail::failed() || !file) return std::nullopt;
    return detail::compensator(*file, path);
  });
}

/// A compensator from a file written by Python's `to_json(path)`. Throws std::invalid_argument
/// naming the file and the bad key.
inline LoadedCompensator load_compensator_json(const std::string& path) {
  return try_load_compensator_json(path).value();
}

}  // namespace tendonsheath::io
