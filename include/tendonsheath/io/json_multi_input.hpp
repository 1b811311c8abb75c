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
// start-up. Strict like Python's loader: a missing, unknown, null or mistyped key is a
// std::invalid_argument naming the file and the key.
#pragma once

#include <cstddef>
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
  const json& k = member(f, "compensator", where);
  if (k != kind)
    fail(where, std::string("key 'compensator' must be \"") + kind + "\" (got " + k.dump() +
                    "; io::compensator_from_json loads the single-input compensators)");
  check_keys(f, allowed, required, where);
}

// joint i's settings: the shared ones, with its own model's range when the file gives none
// (Python's input_range "identified", joint by joint)
inline InverseSettings joint_settings(const json& f, const InverseSettings& shared,
                                      const json& model, const std::string& where) {
  InverseSettings s = shared;
  if (f.contains("input_range")) return s;
  if (const auto r = model_input_range(model, where)) {
    if (!(r->first < r->second)) fail(where, "key 'input_range' needs lo < hi for the inverse");
    s.range = InputRange::identified(r->first, r->second, number(f, "range_margin", where));
  }
  return s;
}

}  // namespace detail

/// A LoadCompensated from the parsed contents of its file: model (a Loaded model), switch (the
/// play's switch travel, > 0) and the base inverse's settings (smoothing, limits, input_range,
/// range_margin, filter_hz, as an InverseFeedforward file's). Throws std::invalid_argument,
/// message starting with `where`, naming the bad key.
inline LoadCompensatedInverse load_compensated_from_json(const json& f,
                                                         const std::string& where = "compensator") {
  detail::check_compensator(f, "LoadCompensated", detail::kLoadCompensatedKeys,
                            detail::kLoadCompensatedKeys, where);
  const LoadedModel m = loaded_model_from_json(f.at("model"), where + ": model");
  LoadTerms terms = m.terms;
  terms.switch_travel = detail::number(f, "switch", where);
  require_positive(terms.switch_travel, where.c_str(), "switch");  // Python's rule and message
  const InverseSettings s = inverse_settings(f, where);  // input_range is the file's (required)
  return LoadCompensatedInverse(make_model_inverse(m.base, s, where), terms);
}

/// A CoupledFeedforward from the parsed contents of its file: model (a Coupled model document)
/// and the settings every joint's inverse takes (as an InverseFeedforward file's; without
/// input_range, each joint is held in its own model's saved range, if any). Throws
/// std::invalid_argument, message starting with `where`, naming the bad key.
inline CoupledFeedforward coupled_feedforward_from_json(const json& f,
                                                        const std::string& where = "compensator") {
  std::set<std::string> required = detail::kCoupledKeys;
  required.erase("input_range");
  detail::check_compensator(f, "CoupledFeedforward", detail::kCoupledKeys, required, where);
  const std::string wm = where + ": model";
  const CoupledModel m = coupled_model_from_json(f.at("model"), wm);
  const InverseSettings shared = inverse_settings(f, where);  // the coupled model has no range
  std::vector<ModelInverse> joints;
  for (std::size_t i = 0; i < m.joints.size(); ++i) {
    const std::string wi = wm + ": models[" + std::to_string(i) + "]";
    const json& model = f.at("model").at("models")[i];
    const InverseSettings s = detail::joint_settings(f, shared, model, wi);
    joints.push_back(make_model_inverse(m.joints[i], s, where + ": joint " + std::to_string(i)));
  }
  try {
    return CoupledFeedforward(std::move(joints), m.coupling);
  } catch (const std::invalid_argument& e) {  // a coupling with a diagonal, or I - C singular
    detail::fail(wm + ": key 'coupling'", e.what());
  }
}

/// A LoadCompensated from a file written by Python's `LoadCompensated.to_json(path)`.
inline LoadCompensatedInverse load_load_compensated_json(const std::string& path) {
  return load_compensated_from_json(read_json_file(path), path);
}

/// A CoupledFeedforward from a file written by Python's `CoupledFeedforward.to_json(path)`.
inline CoupledFeedforward load_coupled_feedforward_json(const std::string& path) {
  return coupled_feedforward_from_json(read_json_file(path), path);
}

}  // namespace tendonsheath::io
