// Loading the compensators whose real-time step takes more than (y_d, dt), saved by Python's
// `to_json` (format "tendonsheath.compensator", version 1):
//
//   LoadCompensated     the inverse of a Loaded model, fed the measured load each cycle
//                       -> LoadCompensated<ModelInverse>::step(y_d, dt, load)
//   CoupledFeedforward  the inverse of a Coupled model, every joint each cycle
//                       -> CoupledFeedforward::step(y_d[J], u[J], dt)
//
// Why not a LoadedCompensator (io/json.hpp): its step(y_d, dt) / step(y_d, reading, dt) serves
// single-input feedforwards. A load folded into it would be an input every other kind ignores,
// and its step without one would silently mean "load 0"; J joints do not fit a scalar step at
// all. So each file loads into the core's own class, whose step is the core's (noexcept, no
// allocation, as Python runs it) and whose signature makes the caller give the load or the J
// angles. LoadedCompensator refuses these files, pointing here.
//
// OPTIONAL and OUTSIDE the real-time path, like io/json.hpp (needs nlohmann/json): load once at
// start-up. Strict like Python's loader: a missing, unknown, null or mistyped key is an error
// naming the file and the key: a Result from the try_ loaders (with or without C++ exceptions),
// a std::invalid_argument from the others.
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../compensators/coupled_feedforward.hpp"
#include "../compensators/load_compensated.hpp"
#include "json.hpp"

namespace tendonsheath::io {

/// The core's inverse of a Loaded model: the base's ModelInverse and the load's play inverse.
using LoadCompensatedInverse = LoadCompensated<ModelInverse>;

namespace detail {

inline const std::set<std::string> kLoadCompensatedKeys{
    "format", "version", "compensator", "model", "switch", "smoothing", "limits",
    "input_range", "range_margin", "filter_hz"};
inline const std::set<std::string> kCoupledKeys{
    "format", "version", "compensator", "model", "smoothing", "limits", "input_range",
    "range_margin", "filter_hz"};

// the format, the version and the compensator `kind`, and only `allowed` keys (all `required`)
inline void check_compensator(const json& f, const char* kind, const std::set<std::string>& allowed,
                              const std::set<std::string>& required, const std::string& where) {
  check_format(f, "tendonsheath.compensator", where);
  if (failed()) return;
  const json& k = member(f, "compensator", where);
  if (k != kind)
    return fail(where, std::string("key 'compensator' must be \"") + kind + "\" (got " +
                           shown(k) + "; io::compensator_from_json loads the single-input "
                           "compensators)");
  check_keys(f, allowed, required, where);
}

// joint i's settings: the shared ones, with its own model's range when the file gives none
// (Python's input_range "identified", joint by joint)
inline InverseSettings joint_settings(const json& f, const InverseSettings& shared,
                                      const json& model, const std::string& where) {
  InverseSettings s = shared;
  if (f.contains("input_range")) return s;
  if (const auto r = model_input_range(model, where)) {
    if (!(r->first < r->second))
      return fail(where, "key 'input_range' needs lo < hi for the inverse"), s;
    s.range = InputRange::identified(r->first, r->second, number(f, "range_margin", where));
  }
  return s;
}

// the LoadCompensated of a file (what load_compensated_from_json returns)
inline std::optional<LoadCompensatedInverse> load_compensated(const json& f,
                                                              const std::string& where) {
  check_compensator(f, "LoadCompensated", kLoadCompensatedKeys, kLoadCompensatedKeys, where);
  if (failed()) return std::nullopt;
  const LoadedModel m = loaded_model_from_json(member(f, "model", where), where + ": model");
  if (failed()) return std::nullopt;
  LoadTerms terms = m.terms;
  terms.switch_travel = number(f, "switch", where);
  if (failed()) return std::nullopt;
  require_positive(terms.switch_travel, where.c_str(), "switch");  // Python's rule and message
  if (failed()) return std::nullopt;
  const InverseSettings s = inverse_settings(f, where);  // input_range is the file's (required)
  if (failed()) return std::nullopt;
  const ModelInverse inverse = make_model_inverse(m.base, s, where);
  if (failed()) return std::nullopt;
  return built<LoadCompensatedInverse>("", inverse, terms);
}

// the CoupledFeedforward of a file (what coupled_feedforward_from_json returns)
inline std::optional<CoupledFeedforward> coupled_feedforward(const json& f,
                                                             const std::string& where) {
  std::set<std::string> required = kCoupledKeys;
  required.erase("input_range");
  check_compensator(f, "CoupledFeedforward", kCoupledKeys, required, where);
  if (failed()) return std::nullopt;
  const std::string wm = where + ": model";
  const json& model = member(f, "model", where);
  const CoupledModel m = coupled_model_from_json(model, wm);
  if (failed()) return std::nullopt;
  const InverseSettings shared = inverse_settings(f, where);  // the coupled model has no range
  if (failed()) return std::nullopt;
  std::vector<ModelInverse> joints;
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    const std::string wi = wm + ": models[" + std::to_string(i) + "]";
    const InverseSettings s = joint_settings(f, shared, member(model, "models", wm)[i], wi);
    if (failed()) return std::nullopt;
    joints.push_back(make_model_inverse(m.joints[i], s, where + ": joint " + std::to_string(i)));
    if (failed()) return std::nullopt;
  }
  // a coupling with a diagonal, or I - C singular, is named as the file's key
  return built<CoupledFeedforward>(wm + ": key 'coupling'", std::move(joints), m.coupling);
}

}  // namespace detail

/// A LoadCompensated from the parsed contents of its file, or the message, starting with
/// `where`, naming the bad key (with or without exceptions); see load_compensated_from_json.
inline Result<LoadCompensatedInverse> try_load_compensated_from_json(
    const json& f, const std::string& where = "compensator") {
  return tendonsheath::detail::result_of<LoadCompensatedInverse>(
      [&] { return detail::load_compensated(f, where); });
}

/// A LoadCompensated from the parsed contents of its file: model (a Loaded model), switch (the
/// play's switch travel, > 0) and the base inverse's settings (smoothing, limits, input_range,
/// range_margin, filter_hz, as an InverseFeedforward file's). Throws std::invalid_argument,
/// message starting with `where`, naming the bad key.
inline LoadCompensatedInverse load_compensated_from_json(const json& f,
                                                         const std::string& where = "compensator") {
  return try_load_compensated_from_json(f, where).value();
}

/// A CoupledFeedforward from the parsed contents of its file, or the message, starting with
/// `where`, naming the bad key (with or without exceptions); see coupled_feedforward_from_json.
inline Result<CoupledFeedforward> try_coupled_feedforward_from_json(
    const json& f, const std::string& where = "compensator") {
  return tendonsheath::detail::result_of<CoupledFeedforward>(
      [&] { return detail::coupled_feedforward(f, where); });
}

/// A CoupledFeedforward from the parsed contents of its file: model (a Coupled model document)
/// and the settings every joint's inverse takes (as an InverseFeedforward file's; without
/// input_range, each joint is held in its own model's saved range, if any). Throws
/// std::invalid_argument, message starting with `where`, naming the bad key.
inline CoupledFeedforward coupled_feedforward_from_json(const json& f,
                                                        const std::string& where = "compensator") {
  return try_coupled_feedforward_from_json(f, where).value();
}

/// A LoadCompensated from a file written by Python's `LoadCompensated.to_json(path)`, or the
/// message naming the file and the bad key (with or without exceptions).
inline Result<LoadCompensatedInverse> try_load_load_compensated_json(const std::string& path) {
  return tendonsheath::detail::result_of<LoadCompensatedInverse>(
      [&]() -> std::optional<LoadCompensatedInverse> {
        const std::optional<json> file = detail::json_file(path);
        if (detail::failed() || !file) return std::nullopt;
        return detail::load_compensated(*file, path);
      });
}

/// A LoadCompensated from a file written by Python's `LoadCompensated.to_json(path)`.
inline LoadCompensatedInverse load_load_compensated_json(const std::string& path) {
  return try_load_load_compensated_json(path).value();
}

/// A CoupledFeedforward from a file written by Python's `CoupledFeedforward.to_json(path)`, or
/// the message naming the file and the bad key (with or without exceptions).
inline Result<CoupledFeedforward> try_load_coupled_feedforward_json(const std::string& path) {
  return tendonsheath::detail::result_of<CoupledFeedforward>(
      [&]() -> std::optional<CoupledFeedforward> {
        const std::optional<json> file = detail::json_file(path);
        if (detail::failed() || !file) return std::nullopt;
        return detail::coupled_feedforward(*file, path);
      });
}

/// A CoupledFeedforward from a file written by Python's `CoupledFeedforward.to_json(path)`.
inline CoupledFeedforward load_coupled_feedforward_json(const std::string& path) {
  return try_load_coupled_feedforward_json(path).value();
}

}  // namespace tendonsheath::io
