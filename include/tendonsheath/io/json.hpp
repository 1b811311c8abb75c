// Loading compensators saved by Python's `Compensator.to_json` (format
// "tendonsheath.compensator", version 1) into the real-time core.
//
// OPTIONAL and OUTSIDE the real-time path: it needs nlohmann/json (Debian's
// nlohmann-json3-dev, CMake target nlohmann_json::nlohmann_json), reads files and allocates.
// Load once at start-up; the returned LoadedCompensator's step() is the core's: noexcept,
// no allocation. Strict, like Python's loader: a missing, unknown, null or mistyped key is a
// std::invalid_argument naming the key. null stands for an unbounded limit (JSON has no inf).
#pragma once

#include "requires_exceptions.hpp"

#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

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
/// Outside the real-time path: it reads files, allocates and throws std::invalid_argument naming a
/// missing, unknown, null or mistyped key. Load once at start-up; the LoadedCompensator's step() is
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

// The file's (Python's) names of the core's fields, for the core's messages (Python's CORE_NAMES)
inline const std::vector<std::pair<std::string, std::string>> kFileNames{
    {"v_eps", "smoothing"}, {"total_angle", "curve_angle"}, {"sheath_length", "length"}};

// build(), a core's constructor; its std::invalid_argument rethrown naming the file (`where`) and
// each field by the file's name ("CurveAngleFeedforward: smoothing must be > 0 (got 0)"), as
// Python's loader says it
template <class Build>
auto with_file_names(const std::string& where, Build build) -> decltype(build()) {
  try {
    return build();
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    for (const auto& [core, file] : kFileNames) {
      const std::string key = ": " + core + " ";
      for (auto at = m.find(key); at != std::string::npos; at = m.find(key, at + file.size()))
        m.replace(at + 2, core.size(), file);
    }
    fail(where, m);
  }
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

/// The model of a "tendonsheath.model" document (a Scaled model around an invertible one, or an
/// invertible one). Throws std::invalid_argument, message starting with `where`, naming the bad key.
inline InvertibleModel invertible_model_from_json(const json& m, const std::string& where) {
  detail::check_format(m, "tendonsheath.model", where);
  const json& name = detail::member(m, "model", where);
  InvertibleModel out;
  out.name = name.is_string() ? name.get<std::string>() : name.dump();
  if (out.name == "Scaled") {
    detail::check_keys(m, {"format", "version", "model", "inner", "map", "input_range"},
                       {"inner", "map"}, where);
    const std::string w = where + ": map";
    const json& mp = m.at("map");
    detail::check_keys(mp, {"input_offset", "input_scale", "output_offset", "output_gain"},
                       {"input_offset", "input_scale", "output_offset", "output_gain"}, w);
    const ScaledMap map{detail::number(mp, "input_offset", w), detail::number(mp, "input_scale", w),
                        detail::number(mp, "output_offset", w), detail::number(mp, "output_gain", w)};
    map.validate(w.c_str());
    out = invertible_model_from_json(m.at("inner"), where + ": inner");
    if (out.map.input_scale != 1.0 || out.map.output_gain != 1.0 || out.map.input_offset != 0.0 ||
        out.map.output_offset != 0.0)
      detail::fail(where, "a Scaled model inside a Scaled model is not supported");
    out.map = map;
    return out;
  }
  detail::check_keys(m, detail::kPlainKeys, {"params"}, where);
  const json& p = m.at("params");
  const std::string w = where + ": params";
  if (out.name == "Backlash" || out.name == "BoucWenBacklash") {
    const bool bw = out.name == "BoucWenBacklash";
    std::set<std::string> keys{"c_r", "c_l", "B_r", "B_l"};
    if (bw) keys.insert({"rho", "sigma", "n"});
    detail::check_keys(p, keys, keys, w);
    for (const auto& k : keys) detail::number(p, k, w);  // every one a number, used or not
    out.backlash.c_r = detail::number(p, "c_r", w);
    out.backlash.c_l = detail::number(p, "c_l", w);
    out.backlash.B_r = detail::number(p, "B_r", w);
    out.backlash.B_l = detail::number(p, "B_l", w);
  } else if (out.name == "PrandtlIshlinskii") {
    detail::check_keys(p, {"thresholds", "weights"}, {"thresholds", "weights"}, w);
    out.pi.thresholds = detail::numbers(p, "thresholds", w);
    out.pi.weights = detail::numbers(p, "weights", w);
  } else {
    detail::fail(where, "key 'model': the C++ loader inverts Backlash, BoucWenBacklash, "
                        "PrandtlIshlinskii and Scaled around them (got " + name.dump() + ")");
  }
  return out;
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
    p.compliance = detail::number(f, "compliance", where);
  } else {  // each checked as Python checks it, before their ratio is
    const double stiffness = detail::number(f, "stiffness", where);
    const double length = detail::number(f, "length", where);
    require_positive(stiffness, where.c_str(), "CurveAngleFeedforward: stiffness");
    require_positive(length, where.c_str(), "CurveAngleFeedforward: length");
    p.compliance = length / stiffness;
  }
  p.pretension = detail::number(f, "pretension", where);
  p.load_force = detail::number(f, "load_force", where);
  p.load_stiffness = detail::number(f, "load_stiffness", where);
  p.proximal_radius = detail::number(f, "proximal_radius", where);
  p.distal_radius = detail::number(f, "distal_radius", where);
  p.total_angle = detail::number(f, "curve_angle", where);
  if (f.contains("play")) p.play = detail::number(f, "play", where);  // absent in older files
  p.v_eps = detail::number(f, "smoothing", where);
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
  p.sheath_length = detail::number(f, detail::renamed_key(f, "length", "sheath_length"), where);
  p.stiffness = detail::number(f, "stiffness", where);
  p.pretension = detail::number(f, "pretension", where);
  p.total_angle = detail::number(f, detail::renamed_key(f, "curve_angle", "total_angle"), where);
  p.bending_stiffness = detail::number(f, "bending_stiffness", where);
  p.tendon_offset = detail::number(f, "tendon_offset", where);
  p.backbone_length = detail::number(f, "backbone_length", where);
  p.proximal_radius = detail::number(f, "proximal_radius", where);
  p.gap_factor = detail::number(f, "gap_factor", where);
  if (f.contains("play")) p.play = detail::number(f, "play", where);  // absent in older files
  p.v_eps = detail::number(f, "smoothing", where);
  const json& mode = detail::member(f, "mode", where);
  if (mode == "exact") p.mode = ContinuumMode::Exact;
  else if (mode == "published") p.mode = ContinuumMode::Published;
  else detail::fail(where, "key 'mode' must be \"exact\" or \"published\" (got " + mode.dump() + ")");
  p.limits = detail::limits(f, where);
  return p;
}

/// A loaded compensator: one of the core's feedforwards (validated by its constructor), with the
/// affine map of a Scaled model applied around a BacklashInverseFeedforward or
/// PrandtlIshlinskiiFeedforward built by hand (a ModelInverse holds its own map: an
/// InverseFeedforward file loads as one, with the identity map here). step() is noexcept and
/// allocates nothing.
class LoadedCompensator {
 public:
  /// The feedforwards a compensator file can hold.
  using Engine = std::variant<BacklashInverseFeedforward, PrandtlIshlinskiiFeedforward,
                              CurveAngleFeedforward, ContinuumFeedforward, ModelInverse>;

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
/// a bad key.
inline InverseSettings inverse_settings(const json& f, const std::string& where) {
  InverseSettings s;
  s.smoothing = detail::number(f, "smoothing", where);
  s.limits = detail::limits(f, where);
  const double margin = f.contains("range_margin") ? detail::number(f, "range_margin", where) : 0.1;
  require_non_negative(margin, where.c_str(), "range_margin");  // Python's rule and message
  const auto range = f.contains("input_range")
                         ? model_input_range(f, where)
                         : model_input_range(detail::member(f, "model", where), where + ": model");
  if (range) {
    require(std::isfinite(range->first) && std::isfinite(range->second) &&
                range->first < range->second,
            where, "input_range needs finite lo < hi (got lo=", range->first, ", hi=", range->second,
            ")");  // Python's message
    s.range = InputRange::identified(range->first, range->second, margin);
  }
  if (f.contains("filter_hz") && !f.at("filter_hz").is_null()) {
    s.filter_hz = detail::number(f, "filter_hz", where);
    require(std::isfinite(s.filter_hz) && s.filter_hz > 0.0, where,
            "filter_hz must be > 0 or None/null (got ", s.filter_hz, ")");  // Python's message
  }
  return s;
}

namespace detail {

// Python's InverseFeedforward: a ModelInverse (its Scaled map inside it).
inline LoadedCompensator inverse_from_json(const json& f, const std::string& where) {
  check_keys(f, {"format", "version", "compensator", "model", "smoothing", "limits", "input_range",
                 "range_margin", "filter_hz"},
             {"model", "smoothing", "limits"}, where);
  const InverseModel m = inverse_model_from_json(f.at("model"), where + ": model");
  return {"InverseFeedforward", make_model_inverse(m, inverse_settings(f, where), where)};
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

}  // namespace detail

inline LoadedCompensator compensator_from_json(const json& f, const std::string& where);

namespace detail {

inline const std::set<std::string> kEncoderLoopKeys{
    "format", "version", "compensator", "feedforward", "kp", "ki", "kd",
    "derivative_cutoff_hz", "max_correction", "limits"};

// Python's EncoderLoop: its feedforward (a compensator file of its own) and the loop's gains.
inline LoadedCompensator encoder_loop_from_json(const json& f, const std::string& where) {
  check_keys(f, kEncoderLoopKeys, kEncoderLoopKeys, where);
  const json& inner = f.at("feedforward");
  if (inner.is_object() && inner.contains("compensator") && inner.at("compensator") == "EncoderLoop")
    fail(where, "key 'feedforward' must be a feedforward, not another EncoderLoop");
  LoadedCompensator out = compensator_from_json(inner, where + ": feedforward");
  EncoderLoopParams p;
  p.kp = number(f, "kp", where);
  p.ki = number(f, "ki", where);
  p.kd = number(f, "kd", where);
  p.derivative_cutoff_hz = number(f, "derivative_cutoff_hz", where);
  p.max_correction = number(f, "max_correction", where, std::numeric_limits<double>::infinity());
  p.limits = limits(f, where);
  try {
    out.set_encoder_loop(EncoderLoop(p));
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
  return out;
}

inline const std::set<std::string> kLearnedKeys{
    "format", "version", "compensator", "feedforward", "table", "table_dt", "hold_last", "limits"};

// Python's LearnedFeedforward: its feedforward (a compensator file of its own) and the table.
inline LoadedCompensator learned_from_json(const json& f, const std::string& where) {
  check_keys(f, kLearnedKeys, kLearnedKeys, where);
  const json& inner = f.at("feedforward");
  if (inner.is_object() && inner.contains("compensator") &&
      (inner.at("compensator") == "EncoderLoop" || inner.at("compensator") == "TipLoop" ||
       inner.at("compensator") == "LearnedFeedforward"))
    fail(where, "key 'feedforward' must be a feedforward, not an " +
                    inner.at("compensator").get<std::string>() +
                    " (put the loop around the LearnedFeedforward)");
  LoadedCompensator out = compensator_from_json(inner, where + ": feedforward");
  LearnedFeedforwardParams p;
  p.table_dt = number(f, "table_dt", where);
  const json& hold = member(f, "hold_last", where);
  if (!hold.is_boolean()) fail(where, "key 'hold_last' must be true or false (got " + hold.dump() + ")");
  p.hold_last = hold.get<bool>();
  p.limits = limits(f, where);
  try {
    out.set_learned_correction(LearnedCorrection(numbers(f, "table", where), p));
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
  return out;
}

inline const std::set<std::string> kTipLoopKeys{
    "format", "version", "compensator", "feedforward", "kp", "ki", "kd",
    "derivative_cutoff_hz", "max_correction", "schedule", "limits"};

// Python's TipLoop: its feedforward (a compensator file of its own), the loop's gains and its gain
// schedule ([[curve_angle, gain], ...], up to 8 points).
inline LoadedCompensator tip_loop_from_json(const json& f, const std::string& where) {
  check_keys(f, kTipLoopKeys, kTipLoopKeys, where);
  const json& inner = f.at("feedforward");
  if (inner.is_object() && inner.contains("compensator") &&
      (inner.at("compensator") == "TipLoop" || inner.at("compensator") == "EncoderLoop"))
    fail(where, "key 'feedforward' must be a feedforward, not a " + inner.at("compensator").dump());
  LoadedCompensator out = compensator_from_json(inner, where + ": feedforward");
  TipLoopParams p;
  p.kp = number(f, "kp", where);
  p.ki = number(f, "ki", where);
  p.kd = number(f, "kd", where);
  p.derivative_cutoff_hz = number(f, "derivative_cutoff_hz", where);
  p.max_correction = number(f, "max_correction", where, std::numeric_limits<double>::infinity());
  const json& schedule = f.at("schedule");
  if (!schedule.is_array() || schedule.size() > TipLoopParams::kMaxSchedule)
    fail(where, "key 'schedule' must be a list of at most 8 [curve_angle, gain] pairs");
  for (std::size_t i = 0; i < schedule.size(); ++i) {
    const json& row = schedule[i];
    if (!row.is_array() || row.size() != 2 || !row[0].is_number() || !row[1].is_number())
      fail(where, "key 'schedule': entry " + std::to_string(i) +
                      " must be a [curve_angle, gain] pair of numbers (got " + row.dump() + ")");
    p.schedule_angles[i] = row[0].get<double>();
    p.schedule_gains[i] = row[1].get<double>();
  }
  p.schedule_size = schedule.size();
  p.limits = limits(f, where);
  try {
    out.set_tip_loop(TipLoop(p));
  } catch (const std::invalid_argument& e) {
    fail(where, e.what());
  }
  return out;
}

}  // namespace detail

/// A compensator from the parsed contents of a "tendonsheath.compensator" file.
inline LoadedCompensator compensator_from_json(const json& f, const std::string& where = "compensator") {
  detail::check_format(f, "tendonsheath.compensator", where);
  const json& kind = detail::member(f, "compensator", where);
  if (kind == "InverseFeedforward") return detail::inverse_from_json(f, where);
  if (kind == "EncoderLoop") return detail::encoder_loop_from_json(f, where);
  if (kind == "LearnedFeedforward") return detail::learned_from_json(f, where);
  if (kind == "TipLoop") return detail::tip_loop_from_json(f, where);
  if (kind == "CurveAngleFeedforward") {
    const auto keys = detail::keys_of_file(f, detail::kCurveAngleKeys, detail::kCurveAngleRenamed);
    std::set<std::string> allowed = keys;
    allowed.insert("play");  // optional: files written before it was a setting lack it
    detail::check_keys(f, allowed, keys, where);
    const CurveAngleFeedforwardParams p = curve_angle_feedforward_params(f, where);
    return {"CurveAngleFeedforward",
            detail::with_file_names(where, [&] { return CurveAngleFeedforward(p); })};
  }
  if (kind == "ContinuumFeedforward") {
    const auto keys = detail::keys_of_file(f, detail::kContinuumKeys, detail::kContinuumRenamed);
    std::set<std::string> allowed = keys;
    allowed.insert("play");  // optional: files written before it was a setting lack it
    detail::check_keys(f, allowed, keys, where);
    const ContinuumFeedforwardParams p = continuum_feedforward_params(f, where);
    return {"ContinuumFeedforward",
            detail::with_file_names(where, [&] { return ContinuumFeedforward(p); })};
  }
  if (kind == "LoadCompensated" || kind == "CoupledFeedforward")  // their step takes more inputs
    detail::fail(where, "key 'compensator': a " + kind.get<std::string>() + " steps with " +
                            (kind == "LoadCompensated" ? "the measured load each cycle: load it "
                                                         "with io::load_compensated_from_json"
                                                       : "every joint each cycle: load it with "
                                                         "io::coupled_feedforward_from_json") +
                            " (tendonsheath/io/json_multi_input.hpp)");
  detail::fail(where, "key 'compensator': unknown compensator " + kind.dump() +
                          " (known: ContinuumFeedforward, CurveAngleFeedforward, EncoderLoop, "
                          "InverseFeedforward, LearnedFeedforward, TipLoop)");
}

namespace detail {

// The keys leading to the value being parsed ("limits.max"), kept by a parser callback: a
// number too large for a double is an error nlohmann raises with no key to name.
class KeyPath {
 public:
  bool operator()(int /*depth*/, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) keys_.emplace_back();
    if (event == json::parse_event_t::object_end && !keys_.empty()) keys_.pop_back();
    if (event == json::parse_event_t::key && !keys_.empty()) keys_.back() = parsed.get<std::string>();
    return true;
  }
  std::string str() const {
    std::string out;
    for (const auto& k : keys_) out += (out.empty() ? "" : ".") + k;
    return out;
  }

 private:
  std::vector<std::string> keys_;
};

}  // namespace detail

/// The parsed contents of a JSON file (read with stdio: the library uses no iostreams). An
/// unreadable file, invalid JSON or a number beyond a double's range is a
/// std::invalid_argument naming the file (and the key of the number).
inline json read_json_file(const std::string& path) {
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (!in) throw std::invalid_argument(path + ": cannot open the file");
  std::string text;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, in)) > 0;) text.append(buffer, n);
  std::fclose(in);
  detail::KeyPath keys;
  try {
    return json::parse(text, std::ref(keys));
  } catch (const json::parse_error& e) {
    throw std::invalid_argument(path + ": not valid JSON (" + e.what() + ")");
  } catch (const json::exception& e) {  // out_of_range.406: a number overflows a double
    const std::string key = keys.str();
    throw std::invalid_argument(path + ": " + (key.empty() ? "a value" : "key '" + key + "'") +
                                " is out of range (" + e.what() + ")");
  }
}

/// A compensator from a file written by Python's `to_json(path)`.
inline LoadedCompensator load_compensator_json(const std::string& path) {
  return compensator_from_json(read_json_file(path), path);
}

}  // namespace tendonsheath::io
