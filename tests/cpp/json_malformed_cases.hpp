// Malformed compensator files, each with the words its loader's message must hold: the cases of
// the JSON loaders' tests (test_io_json_multi_input.cpp) and of the program that runs them with
// and without C++ exceptions (no_exceptions/json_cases.cpp), so that both check the same files;
// and the good files and models they are made from (test_io_json.cpp loads those too).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <tendonsheath/io/json.hpp>

namespace malformed_json {

using json = tendonsheath::io::json;

// a Backlash of slope c and half-width B on both sides (c = 1, B = 0: the identity)
inline json backlash_model(double c = 1.0, double B = 0.0) {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "Backlash"},
          {"params", {{"c_r", c}, {"c_l", c}, {"B_r", B}, {"B_l", B}}},
          {"options", json::object()}};
}

inline json unbounded() { return {{"min", nullptr}, {"max", nullptr}, {"max_rate", nullptr}}; }

inline json load_compensated_file(double gain, double slack, double slack_load, double friction,
                                  double switch_travel = 1e-3) {
  const json model = {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "Loaded"},
                      {"base", backlash_model()},
                      {"terms", {{"gain", gain}, {"slack", slack}, {"slack_load", slack_load},
                                 {"friction", friction}}}};
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "LoadCompensated"}, {"model", model}, {"switch", switch_travel},
          {"smoothing", 0.05}, {"limits", unbounded()}, {"input_range", nullptr},
          {"range_margin", 0.1}, {"filter_hz", nullptr}};
}

inline json coupled_file(const std::vector<json>& models,
                         const std::vector<std::vector<double>>& c) {
  const json model = {{"format", "tendonsheath.coupled_model"}, {"version", 1},
                      {"models", models}, {"coupling", c}};
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "CoupledFeedforward"}, {"model", model}, {"smoothing", 0.05},
          {"limits", unbounded()}, {"range_margin", 0.1}, {"filter_hz", nullptr}};
}

inline json three_joints() {
  return coupled_file({backlash_model(), backlash_model(), backlash_model()},
                      {{0.0, 0.2, -0.1}, {0.05, 0.0, 0.3}, {-0.25, 0.15, 0.0}});
}

// one change to a good file, and what the message must say (besides the file's name)
struct BadCase {
  std::function<void(json&)> change;
  std::string words;
};

// 18 malformed LoadCompensated files (from load_compensated_file(0.3, 0.02, 0.1, 0.05))
inline std::vector<BadCase> load_compensated_cases() {
  return {
      {[](json& f) { f.erase("switch"); }, "key 'switch' is missing"},
      {[](json& f) { f["extra"] = 1; }, "unknown key 'extra'"},
      {[](json& f) { f["switch"] = "0.1"; }, "key 'switch' must be a number"},
      {[](json& f) { f["switch"] = 0.0; }, "switch must be > 0"},
      {[](json& f) { f["smoothing"] = nullptr; }, "key 'smoothing' must be a number"},
      {[](json& f) { f.erase("input_range"); }, "key 'input_range' is missing"},
      {[](json& f) { f["limits"]["max"] = true; }, "key 'max' must be a number"},
      {[](json& f) { f["version"] = 2; }, "unsupported 'version' 2"},
      {[](json& f) { f["version"] = 1.0; }, "unsupported 'version' 1.0"},
      {[](json& f) { f["version"] = true; }, "unsupported 'version' true"},
      {[](json& f) { f["compensator"] = "InverseFeedforward"; }, "key 'compensator' must be"},
      {[](json& f) { f["model"]["model"] = "Backlash"; }, "model: key 'model' must be \"Loaded\""},
      {[](json& f) { f["model"]["terms"].erase("gain"); }, "model: terms: key 'gain' is missing"},
      {[](json& f) { f["model"]["terms"]["stiction"] = 0.1; }, "terms: unknown key 'stiction'"},
      {[](json& f) { f["model"]["terms"]["slack_load"] = 0.0; }, "terms: slack_load must be > 0"},
      {[](json& f) { f["model"]["terms"]["friction"] = "x"; }, "key 'friction' must be a number"},
      {[](json& f) { f["model"]["base"]["params"].erase("B_l"); }, "base: params: key 'B_l'"},
      {[](json& f) { f["model"]["input_range"] = {1.0, 0.0}; }, "key 'input_range'"},
  };
}

// 14 malformed CoupledFeedforward files (from three_joints())
inline std::vector<BadCase> coupled_feedforward_cases() {
  return {
      {[](json& f) { f.erase("smoothing"); }, "key 'smoothing' is missing"},
      {[](json& f) { f["gains"] = 1; }, "unknown key 'gains'"},
      {[](json& f) { f["range_margin"] = "0.1"; }, "key 'range_margin' must be a number"},
      {[](json& f) { f["version"] = 1.0; }, "unsupported 'version' 1.0"},
      {[](json& f) { f["model"]["version"] = 2; }, "model: unsupported 'version' 2"},
      {[](json& f) { f["model"]["format"] = "tendonsheath.model"; }, "model: key 'format'"},
      {[](json& f) { f["model"]["extra"] = 0; }, "model: unknown key 'extra'"},
      {[](json& f) { f["model"]["models"] = json::array(); }, "model: key 'models'"},
      {[](json& f) { f["model"]["models"][1]["params"].erase("c_r"); }, "models[1]: params: key 'c_r'"},
      {[](json& f) { f["model"]["models"][2]["input_range"] = {1.0, 0.0}; }, "models[2]: key 'input_range'"},
      {[](json& f) { f["model"]["coupling"][1] = {0.0, 0.0}; }, "model: key 'coupling' must be 3 rows"},
      {[](json& f) { f["model"]["coupling"][0][1] = "x"; }, "key 'coupling' must hold only numbers"},
      {[](json& f) { f["model"]["coupling"][0][0] = 0.1; }, "key 'coupling'"},
      {[](json& f) { f["model"].erase("coupling"); }, "model: key 'coupling' is missing"},
  };
}

// a Backlash model with its own slopes and half-widths
inline json backlash_model4(double c_r, double c_l, double B_r, double B_l) {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "Backlash"},
          {"params", {{"c_r", c_r}, {"c_l", c_l}, {"B_r", B_r}, {"B_l", B_l}}},
          {"options", json::object()}};
}

inline json inverse_file(json model, double smoothing = 0.05) {
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "InverseFeedforward"}, {"model", std::move(model)},
          {"smoothing", smoothing}, {"limits", unbounded()}};
}

inline json curve_angle_file() {
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "CurveAngleFeedforward"}, {"friction", 0.12}, {"stiffness", 5000.0},
          {"length", 1.0}, {"pretension", 15.0}, {"load_force", 1.0}, {"load_stiffness", 50.0},
          {"proximal_radius", 6e-3}, {"distal_radius", 4e-3}, {"curve_angle", 2.0},
          {"smoothing", 0.03}, {"max_correction_rate", nullptr},
          {"limits", {{"min", -3.0}, {"max", 3.0}, {"max_rate", 20.0}}}};
}

inline json continuum_file() {
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "ContinuumFeedforward"}, {"friction", 0.1}, {"length", 0.9},
          {"stiffness", 2e4}, {"pretension", 10.0}, {"curve_angle", 2.5},
          {"bending_stiffness", 4e-4}, {"tendon_offset", 2e-3}, {"backbone_length", 0.03},
          {"proximal_radius", 5e-3}, {"gap_factor", 1.0}, {"smoothing", 0.1}, {"mode", "exact"},
          {"limits", unbounded()}};
}

inline json bouc_wen_backlash_model() {
  json bw = backlash_model4(1.0, 1.1, 0.1, 0.2);
  bw["model"] = "BoucWenBacklash";
  bw["params"].update({{"rho", 5.0}, {"sigma", 0.5}, {"n", 1.0}});
  bw["options"] = {{"max_step", 0.01}, {"max_substeps", 100}};
  return bw;
}

inline json lag_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "SecondOrderLag"},
          {"params", {{"frequency", 4.0}, {"damping", 0.7}}}, {"options", json::object()}};
}

inline json chain_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "Chain"},
          {"first", backlash_model4(1.0, 1.0, 0.1, 0.1)}, {"second", lag_model()}};
}

inline json plant_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "PlantModel"},
          {"params", {{"friction_angle", 1.0}, {"backlash", 0.1}, {"viscous_time", 0.0},
                      {"gain", 1.0}, {"offset", 0.0}}},
          {"options", {{"elements", 10}}}};
}

inline json angle_dependent_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "AngleDependent"},
          {"params", {{"base", "Backlash"},
                      {"laws", {{"c_r", "constant"}, {"c_l", "constant"}, {"B_r", "tanh"},
                                {"B_l", "linear"}}},
                      {"coefficients", {{"c_r", {1.0}}, {"c_l", {1.0}}, {"B_r", {0.05, 0.1}},
                                        {"B_l", {0.05, 0.01}}}},
                      {"angle_friction", 0.1}}},
          {"options", {{"base_options", json::object()}}}};
}

inline json generalized_pi_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1},
          {"model", "GeneralizedPrandtlIshlinskii"},
          {"params", {{"rising_a", 1.0}, {"rising_b", 2.0}, {"rising_c", 0.1}, {"rising_d", 0.0},
                      {"falling_a", 1.2}, {"falling_b", 1.5}, {"falling_c", -0.1},
                      {"falling_d", 0.05}, {"thresholds", {0.0, 0.1}}, {"weights", {1.0, 0.5}}}},
          {"options", {{"envelope_range", {-0.5, 0.7}}}}};
}

inline json scaled_model() {
  return {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "Scaled"},
          {"inner", backlash_model4(1.2, 0.8, 0.1, 0.05)},
          {"map", {{"input_offset", 0.3}, {"input_scale", 2.0}, {"output_offset", -0.1},
                   {"output_gain", -1.5}}}};
}

inline json learned_file() {
  return {{"format", "tendonsheath.compensator"}, {"version", 1},
          {"compensator", "LearnedFeedforward"},
          {"feedforward", inverse_file(backlash_model4(1, 1, 0.05, 0.05))},
          {"table", {0.0, 0.01, 0.03}}, {"table_dt", 2e-3}, {"hold_last", true},
          {"limits", unbounded()}};
}

inline json encoder_loop_file(json feedforward) {
  return {{"format", "tendonsheath.compensator"}, {"version", 1}, {"compensator", "EncoderLoop"},
          {"feedforward", std::move(feedforward)}, {"kp", 0.0}, {"ki", 10.0}, {"kd", 0.0},
          {"derivative_cutoff_hz", 50.0}, {"max_correction", nullptr}, {"limits", unbounded()}};
}

inline json tip_loop_file() {
  return {{"format", "tendonsheath.compensator"}, {"version", 1}, {"compensator", "TipLoop"},
          {"feedforward", inverse_file(backlash_model4(1, 1, 0.05, 0.05))}, {"kp", 0.5},
          {"ki", 40.0}, {"kd", 0.0}, {"derivative_cutoff_hz", 50.0}, {"max_correction", nullptr},
          {"schedule", {{0.5, 0.8}, {2.0, 1.5}}}, {"limits", unbounded()}};
}

// the good single-input compensator files (each loads), by name
inline std::vector<std::pair<std::string, json>> good_compensator_files() {
  return {{"backlash", inverse_file(backlash_model4(1.2, 0.8, 0.1, 0.05))},
          {"scaled", inverse_file(scaled_model(), 0.06)},
          {"bouc_wen_backlash", inverse_file(bouc_wen_backlash_model())},
          {"chain", inverse_file(chain_model())},
          {"plant", inverse_file(plant_model())},
          {"angle_dependent", inverse_file(angle_dependent_model())},
          {"generalized_pi", inverse_file(generalized_pi_model())},
          {"curve_angle", curve_angle_file()},
          {"continuum", continuum_file()},
          {"learned", learned_file()},
          {"encoder_loop", encoder_loop_file(learned_file())},
          {"tip_loop", tip_loop_file()}};
}

// a malformed file, what the message of compensator_from_json(file, "f") must say, and how it
// starts: "f", or the name of the core's class whose check refused the value
struct BadFile {
  json file;
  std::string words;
  std::string start = "f";
};

// `good` changed by `change`
inline json changed(json good, const std::function<void(json&)>& change) {
  change(good);
  return good;
}

// 42 malformed single-input files: the cases of test_io_json.cpp and test_cpp_example_12.py
inline std::vector<BadFile> compensator_cases() {
  const json curve = curve_angle_file();
  const json inv = inverse_file(backlash_model4(1, 1, 0.1, 0.1));
  std::vector<BadFile> out{
      {changed(curve, [](json& f) { f.erase("pretension"); }), "'pretension' is missing"},
      {changed(curve, [](json& f) { f["extra"] = 1; }), "unknown key 'extra'"},
      {changed(curve, [](json& f) { f["friction"] = true; }), "'friction' must be a number"},
      {changed(curve, [](json& f) { f["stiffness"] = nullptr; }), "'stiffness' must be a number"},
      {changed(curve, [](json& f) { f["limits"]["low"] = 0.0; }), "limits: unknown key 'low'"},
      {changed(curve, [](json& f) { f["format"] = "tendonsheath.model"; }), "'format'"},
      {changed(curve, [](json& f) { f["compensator"] = "AdaptiveController"; }),
       "unknown compensator"},
      {changed(curve, [](json& f) { f["play"] = "wide"; }), "play"},
      {changed(curve, [](json& f) { f["play"] = -0.1; }), "CurveAngleFeedforward: play must be >= 0"},
      {changed(curve,
               [](json& f) {
                 f.erase("stiffness");
                 f["compliance"] = 2e-4;
               }),
       "unknown key 'length'"},
      {changed(inv, [](json& f) { f["model"]["model"] = "PolynomialHysteresis"; }), "key 'model'"},
      {changed(inv, [](json& f) { f["model"]["params"].erase("B_l"); }),
       "model: params: key 'B_l' is missing"},
      {changed(inv, [](json& f) { f["model"]["params"]["B_left"] = f["model"]["params"]["B_l"]; }),
       "unknown key 'B_left'"},
      {changed(inv, [](json& f) { f["filter_hz"] = -1.0; }), "filter_hz must be > 0"},
      {changed(inv, [](json& f) { f["input_range"] = {1.0}; }), "'input_range' must be [lo, hi]"},
      {changed(inv, [](json& f) { f["range_margin"] = "wide"; }),
       "'range_margin' must be a number"},
      {changed(inverse_file(bouc_wen_backlash_model()),
               [](json& f) { f["model"]["options"]["max_substeps"] = std::int64_t{1} << 40; }),
       "'max_substeps' is out of the range of an int"},
      {changed(inverse_file(angle_dependent_model()),
               [](json& f) { f["model"]["params"]["laws"]["B_r"] = "cubic"; }),
       "law of 'B_r'"},
      {changed(inverse_file(plant_model()),
               [](json& f) { f["model"]["params"]["viscosity"] = 1.0; }),
       "unknown key 'viscosity'"},
      {changed(inverse_file(chain_model()),
               [](json& f) { f["model"]["second"]["params"].erase("damping"); }),
       "second: params: key 'damping' is missing"},
      {changed(inverse_file(generalized_pi_model()),
               [](json& f) { f["model"]["options"]["envelope_range"] = {0.7, -0.5}; }),
       "'envelope_range' must be null or [lo, hi]"},
      {changed(inverse_file(generalized_pi_model()),
               [](json& f) { f["model"]["options"] = {{"range", {0.0, 1.0}}}; }),
       "unknown key 'range'"},
      {changed(learned_file(), [](json& f) { f["table"] = json::array(); }), "the table is empty"},
      {changed(learned_file(), [](json& f) { f["table"] = {0.0, "x"}; }),
       "'table' must hold only numbers"},
      {changed(learned_file(), [](json& f) { f["table_dt"] = 0.0; }), "table_dt must be > 0"},
      {changed(learned_file(), [](json& f) { f["hold_last"] = 1; }),
       "'hold_last' must be true or false"},
      {changed(learned_file(), [](json& f) { f.erase("table"); }), "'table' is missing"},
      {changed(learned_file(), [](json& f) { f["feedforward"] = encoder_loop_file(learned_file()); }),
       "not an EncoderLoop"},
      {changed(tip_loop_file(), [](json& f) { f["schedule"] = {{0.0, 1.0, 2.0}}; }), "entry 0"},
      {changed(tip_loop_file(), [](json& f) { f["schedule"] = {{1.0, 1.0}, {0.5, 2.0}}; }),
       "increasing"},
      {changed(tip_loop_file(), [](json& f) { f["feedforward"] = tip_loop_file(); }), "not a"},
      {changed(encoder_loop_file(inv), [&](json& f) { f["feedforward"] = encoder_loop_file(inv); }),
       "not another EncoderLoop"},
      {load_compensated_file(0.0, 0.0, 1.0, 0.0), "io::load_compensated_from_json"},
      {three_joints(), "io::coupled_feedforward_from_json"},
  };
  for (const json& version : {json(true), json(1.0), json("1"), json(2)}) {  // 8 more
    out.push_back({changed(curve, [&](json& f) { f["version"] = version; }), "unsupported 'version'"});
    out.push_back({changed(inv, [&](json& f) { f["model"]["version"] = version; }),
                   "unsupported 'version'"});
  }
  return out;
}

}  // namespace malformed_json
