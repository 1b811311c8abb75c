// tendonsheath/io/json.hpp: compensator files as Python writes them load into the core's
// feedforwards with the same numbers, and every malformed key is an error naming it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <tendonsheath/io/json.hpp>

#include "json_malformed_cases.hpp"

namespace ts = tendonsheath;
using ts::io::json;

using malformed_json::backlash_model4;
using malformed_json::curve_angle_file;
using malformed_json::inverse_file;

namespace {

std::string error_of(const json& file) {
  try {
    ts::io::compensator_from_json(file, "f");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST(IoJson, BacklashInverseStepsEqualTheCoreObjectOverRandomCases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 2.0), b(0.0, 0.3), y(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    ts::BacklashInverseParams p;
    p.c_r = u(rng), p.c_l = u(rng), p.B_r = b(rng), p.B_l = b(rng), p.smoothing = 0.01 + b(rng);
    ts::io::LoadedCompensator loaded =
        ts::io::compensator_from_json(inverse_file(backlash_model4(p.c_r, p.c_l, p.B_r, p.B_l), p.smoothing));
    ts::BacklashInverseFeedforward direct(p);
    EXPECT_EQ(loaded.kind(), "InverseFeedforward");
    for (int k = 0; k < 200; ++k) {
      const double yd = y(rng);
      ASSERT_EQ(loaded.step(yd, 1e-3), direct.step(yd, 1e-3)) << "trial " << trial;
    }
  }
}

TEST(IoJson, ScaledModelAppliesItsMapAroundTheInnerInverse) {
  json scaled = malformed_json::scaled_model();
  json file = inverse_file(scaled, 0.06);
  file["limits"]["max"] = 1.0;
  ts::io::LoadedCompensator loaded = ts::io::compensator_from_json(file);
  ts::BacklashInverseParams p;
  p.c_r = 1.2, p.c_l = 0.8, p.B_r = 0.1, p.B_l = 0.05, p.smoothing = 0.06 / 1.5;
  p.limits.max = (1.0 - 0.3) / 2.0;  // the raw command's limit in the inner units
  ts::BacklashInverseFeedforward inner(p);
  for (int k = 0; k < 500; ++k) {
    const double yd = std::sin(0.02 * k);
    const double expected = 0.3 + 2.0 * inner.step((yd + 0.1) / -1.5, 1e-3);
    ASSERT_EQ(loaded.step(yd, 1e-3), expected);
    ASSERT_LE(loaded.step(yd, 0.0), 1.0 + 1e-12);  // the raw limit holds
  }
}

TEST(IoJson, PrandtlIshlinskiiAndBoucWenBacklashModelsLoad) {
  json pi = {{"format", "tendonsheath.model"}, {"version", 1}, {"model", "PrandtlIshlinskii"},
             {"params", {{"thresholds", {0.0, 0.1, 0.2}}, {"weights", {1.0, 0.4, 0.2}}}}};
  const ts::io::InvertibleModel m = ts::io::invertible_model_from_json(pi, "m");
  EXPECT_EQ(m.pi.weights, (std::vector<double>{1.0, 0.4, 0.2}));
  ts::io::LoadedCompensator loaded = ts::io::compensator_from_json(inverse_file(pi));
  ASSERT_TRUE(std::holds_alternative<ts::ModelInverse>(loaded.engine()));
  const auto& inverse = std::get<ts::ModelInverse>(loaded.engine());
  EXPECT_TRUE(std::holds_alternative<ts::PrandtlIshlinskiiInverse>(inverse.core()));  // exact
  json bw = backlash_model4(1.0, 1.1, 0.1, 0.2);
  bw["model"] = "BoucWenBacklash";
  bw["params"].update({{"rho", 5.0}, {"sigma", 0.5}, {"n", 1.0}});
  bw["options"] = {{"max_step", 0.01}, {"max_substeps", 100}};
  EXPECT_EQ(ts::io::invertible_model_from_json(bw, "m").backlash.c_l, 1.1);
}

TEST(IoJson, CurveAngleFileFillsEveryField) {
  const ts::CurveAngleFeedforwardParams p =
      ts::io::curve_angle_feedforward_params(curve_angle_file(), "f");
  EXPECT_EQ(p.friction, 0.12);
  EXPECT_EQ(p.stiffness, 5000.0);
  EXPECT_EQ(p.length, 1.0);
  EXPECT_EQ(p.distal_radius, 4e-3);
  EXPECT_EQ(p.curve_angle, 2.0);
  EXPECT_EQ(p.smoothing, 0.03);
  EXPECT_TRUE(std::isinf(p.max_correction_rate));
  EXPECT_EQ(p.limits.min, -3.0);
  EXPECT_EQ(p.limits.max_rate, 20.0);
  ts::io::LoadedCompensator loaded = ts::io::compensator_from_json(curve_angle_file());
  ts::CurveAngleFeedforward direct(p);
  for (int k = 0; k < 300; ++k)
    ASSERT_EQ(loaded.step(std::sin(0.01 * k), 1e-3), direct.step(std::sin(0.01 * k), 1e-3));
}

// The play (added later) is read when the file has it, and 0 in a file written before it.
TEST(IoJson, CurveAnglePlayIsOptional) {
  EXPECT_EQ(ts::io::curve_angle_feedforward_params(curve_angle_file(), "f").play, 0.0);
  json file = curve_angle_file();
  file["play"] = 0.02;
  EXPECT_EQ(ts::io::curve_angle_feedforward_params(file, "f").play, 0.02);
  file["play"] = "wide";
  EXPECT_NE(error_of(file).find("play"), std::string::npos);
  file["play"] = -0.1;
  EXPECT_NE(error_of(file).find("play"), std::string::npos);
}

// Files written before docs/vocabulary.md renamed the settings load to the same numbers.
TEST(IoJson, FilesWithTheOldSettingNamesStillLoad) {
  json old = curve_angle_file();
  old.erase("stiffness");
  old.erase("length");
  old["compliance"] = 2e-4;
  const ts::CurveAngleFeedforwardParams was = ts::io::curve_angle_feedforward_params(old, "f");
  EXPECT_EQ(was.length, 1.0);  // as Python reads it: EA = 1 / compliance, L = 1 m
  EXPECT_DOUBLE_EQ(was.length / was.stiffness, 2e-4);
  EXPECT_EQ(error_of(old), "(no error)");
  old["length"] = 1.0;  // both the old and a new name: refused
  EXPECT_NE(error_of(old).find("unknown key 'length'"), std::string::npos) << error_of(old);
  json now = {{"format", "tendonsheath.compensator"}, {"version", 1},
              {"compensator", "ContinuumFeedforward"}, {"friction", 0.1}, {"length", 0.9},
              {"stiffness", 2e4}, {"pretension", 10.0}, {"curve_angle", 2.5},
              {"bending_stiffness", 4e-4}, {"tendon_offset", 2e-3}, {"backbone_length", 0.03},
              {"proximal_radius", 5e-3}, {"gap_factor", 1.0}, {"smoothing", 0.1},
              {"mode", "exact"},
              {"limits", {{"min", nullptr}, {"max", nullptr}, {"max_rate", nullptr}}}};
  json before = now;
  before["sheath_length"] = before["length"];
  before["total_angle"] = before["curve_angle"];
  before.erase("length");
  before.erase("curve_angle");
  for (const json& f : {now, before}) {
    const ts::ContinuumFeedforwardParams p = ts::io::continuum_feedforward_params(f, "f");
    EXPECT_EQ(p.length, 0.9);
    EXPECT_EQ(p.curve_angle, 2.5);
    EXPECT_EQ(error_of(f), "(no error)");
  }
}

TEST(IoJson, MalformedFilesNameTheKey) {
  json f = curve_angle_file();
  f.erase("pretension");
  EXPECT_NE(error_of(f).find("'pretension' is missing"), std::string::npos) << error_of(f);
  f = curve_angle_file();
  f["extra"] = 1;
  EXPECT_NE(error_of(f).find("unknown key 'extra'"), std::string::npos) << error_of(f);
  f = curve_angle_file();
  f["friction"] = true;
  EXPECT_NE(error_of(f).find("'friction' must be a number"), std::string::npos) << error_of(f);
  f = curve_angle_file();
  f["stiffness"] = nullptr;
  EXPECT_NE(error_of(f).find("'stiffness' must be a number"), std::string::npos) << error_of(f);
  f = curve_angle_file();
  f["limits"]["low"] = 0.0;
  EXPECT_NE(error_of(f).find("limits: unknown key 'low'"), std::string::npos) << error_of(f);
  f = curve_angle_file();
  f["format"] = "tendonsheath.model";
  EXPECT_NE(error_of(f).find("'format'"), std::string::npos) << error_of(f);
  json inv = inverse_file(backlash_model4(1, 1, 0.1, 0.1));
  inv["model"]["model"] = "PolynomialHysteresis";
  EXPECT_NE(error_of(inv).find("key 'model'"), std::string::npos) << error_of(inv);
  inv = inverse_file(backlash_model4(1, 1, 0.1, 0.1));
  inv["model"]["params"].erase("B_l");
  EXPECT_NE(error_of(inv).find("model: params: key 'B_l' is missing"), std::string::npos)
      << error_of(inv);
  f = curve_angle_file();
  f["compensator"] = "AdaptiveController";
  EXPECT_NE(error_of(f).find("unknown compensator"), std::string::npos) << error_of(f);
}

TEST(IoJson, UnreadableFilesAreOneLineErrors) {
  EXPECT_THROW(ts::io::load_compensator_json("/nonexistent/ff.json"), std::invalid_argument);
}

// The error of loading `text` from a file (empty: it loaded).
std::string file_error_of(const std::string& text) {
  const std::string path = ::testing::TempDir() + "ts_io_json_huge.json";
  std::FILE* out = std::fopen(path.c_str(), "wb");
  std::fwrite(text.data(), 1, text.size(), out);
  std::fclose(out);
  try {
    ts::io::load_compensator_json(path);
  } catch (const std::invalid_argument& e) {  // anything else fails the test
    std::remove(path.c_str());
    return e.what();
  }
  std::remove(path.c_str());
  return "";
}

// A number beyond a double's range (an integer of 400 digits, 1e999) is nlohmann's
// out_of_range: it comes out as an invalid_argument naming the file and the key.
TEST(IoJson, NumbersBeyondADoubleNameTheFileAndTheKey) {
  const std::string huge(400, '9');
  json f = curve_angle_file();
  std::string text = f.dump();
  const std::string good = "\"max_rate\":20.0";
  ASSERT_NE(text.find(good), std::string::npos) << text;
  for (const std::string& number : {huge, std::string("-1e999")}) {
    std::string bad = text;
    bad.replace(bad.find(good), good.size(), "\"max_rate\":" + number);
    const std::string e = file_error_of(bad);
    EXPECT_NE(e.find("ts_io_json_huge.json: key 'limits.max_rate' is out of range"),
              std::string::npos)
        << e;
  }
  EXPECT_EQ(file_error_of(text), "");
  // an integer setting beyond an int is named too (get<int> would wrap it round)
  json bw = backlash_model4(1.0, 1.1, 0.1, 0.2);
  bw["model"] = "BoucWenBacklash";
  bw["params"].update({{"rho", 5.0}, {"sigma", 0.5}, {"n", 1.0}});
  bw["options"] = {{"max_step", 0.01}, {"max_substeps", 100}};
  EXPECT_EQ(error_of(inverse_file(bw)), "(no error)");
  bw["options"]["max_substeps"] = std::int64_t{1} << 40;
  const std::string e = error_of(inverse_file(bw));
  EXPECT_NE(e.find("'max_substeps' is out of the range of an int"), std::string::npos) << e;
}

// The settings of the inverse of every model: input_range ([lo, hi], null, or absent: the
// model's own), range_margin and filter_hz; the commands stay in the widened range.
TEST(IoJson, InverseRangeSettings) {
  json model = backlash_model4(1.0, 1.0, 0.1, 0.1);
  model["input_range"] = {-0.4, 0.6};
  json file = inverse_file(model);
  auto widest = [](ts::io::LoadedCompensator c) {
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 400; ++k) {
      const double x = c.step(3.0 * std::sin(0.02 * k), 1e-3);
      lo = std::fmin(lo, x), hi = std::fmax(hi, x);
    }
    return std::make_pair(lo, hi);
  };
  // absent: the model's range, the default margin 0.1 of its span
  EXPECT_EQ(widest(ts::io::compensator_from_json(file)), std::make_pair(-0.5, 0.7));
  file["range_margin"] = 0.0;
  EXPECT_EQ(widest(ts::io::compensator_from_json(file)), std::make_pair(-0.4, 0.6));
  file["input_range"] = {-1.0, 1.0};
  EXPECT_EQ(widest(ts::io::compensator_from_json(file)), std::make_pair(-1.0, 1.0));
  file["input_range"] = nullptr;  // unbounded
  EXPECT_GT(widest(ts::io::compensator_from_json(file)).second, 2.0);
  file["filter_hz"] = nullptr;
  EXPECT_EQ(error_of(file), "(no error)");
  file["filter_hz"] = -1.0;
  EXPECT_NE(error_of(file).find("filter_hz must be > 0"), std::string::npos) << error_of(file);
  file["filter_hz"] = 10.0;
  file["input_range"] = {1.0};
  EXPECT_NE(error_of(file).find("'input_range' must be [lo, hi]"), std::string::npos)
      << error_of(file);
  file["input_range"] = {-1.0, 1.0};
  file["range_margin"] = "wide";
  EXPECT_NE(error_of(file).find("'range_margin' must be a number"), std::string::npos)
      << error_of(file);
}

// Every model class the identification returns loads (a Chain, a Scaled one, a lag, a plant,
// an angle-dependent one), and a bad key inside any of them is named.
TEST(IoJson, EveryModelClassLoads) {
  const json chain = malformed_json::chain_model();  // a Backlash then a SecondOrderLag
  EXPECT_EQ(error_of(inverse_file(chain)), "(no error)");
  const json plant = malformed_json::plant_model();
  EXPECT_EQ(error_of(inverse_file(plant)), "(no error)");
  json angle = malformed_json::angle_dependent_model();
  ts::io::LoadedCompensator loaded = ts::io::compensator_from_json(inverse_file(angle));
  EXPECT_TRUE(std::get<ts::ModelInverse>(loaded.engine()).follows_route());
  angle["params"]["laws"]["B_r"] = "cubic";
  EXPECT_NE(error_of(inverse_file(angle)).find("law of 'B_r'"), std::string::npos);
  json bad = plant;
  bad["params"]["viscosity"] = 1.0;
  EXPECT_NE(error_of(inverse_file(bad)).find("unknown key 'viscosity'"), std::string::npos);
  json chained = chain;
  chained["second"]["params"].erase("damping");
  EXPECT_NE(error_of(inverse_file(chained)).find("second: params: key 'damping' is missing"),
            std::string::npos)
      << error_of(inverse_file(chained));
}

// A LearnedFeedforward file: the inverse's command plus the table, played in time; an EncoderLoop
// file may hold one; its malformed keys are named.
TEST(IoJson, LearnedFeedforwardAddsItsTableAndNamesBadKeys) {
  auto learned_file = [] {
    return json{{"format", "tendonsheath.compensator"}, {"version", 1},
                {"compensator", "LearnedFeedforward"},
                {"feedforward", inverse_file(backlash_model4(1, 1, 0.05, 0.05))},
                {"table", {0.0, 0.01, 0.03}}, {"table_dt", 2e-3}, {"hold_last", true},
                {"limits", {{"min", nullptr}, {"max", nullptr}, {"max_rate", nullptr}}}};
  };
  ts::io::LoadedCompensator loaded = ts::io::compensator_from_json(learned_file());
  EXPECT_EQ(loaded.kind(), "LearnedFeedforward");
  ASSERT_NE(loaded.learned_correction(), nullptr);
  ts::io::LoadedCompensator plain =
      ts::io::compensator_from_json(inverse_file(backlash_model4(1, 1, 0.05, 0.05)));
  const double expected[] = {0.0, 0.005, 0.01, 0.02, 0.03, 0.03, 0.03};
  for (int k = 0; k < 7; ++k) {
    const double y = 0.3 * std::sin(0.2 * k), dt = k == 0 ? 0.0 : 1e-3;
    EXPECT_NEAR(loaded.step(y, dt), plain.step(y, dt) + expected[k], 1e-12) << k;
  }
  EXPECT_TRUE(ts::has(loaded.status(), ts::Status::input_clamped));

  json f = learned_file();
  f["table"] = json::array();
  EXPECT_NE(error_of(f).find("the table is empty"), std::string::npos) << error_of(f);
  f = learned_file();
  f["table"] = {0.0, "x"};
  EXPECT_NE(error_of(f).find("'table' must hold only numbers"), std::string::npos) << error_of(f);
  f = learned_file();
  f["table_dt"] = 0.0;
  EXPECT_NE(error_of(f).find("table_dt must be > 0"), std::string::npos) << error_of(f);
  f = learned_file();
  f["hold_last"] = 1;
  EXPECT_NE(error_of(f).find("'hold_last' must be true or false"), std::string::npos) << error_of(f);
  f = learned_file();
  f.erase("table");
  EXPECT_NE(error_of(f).find("'table' is missing"), std::string::npos) << error_of(f);
  json loop{{"format", "tendonsheath.compensator"}, {"version", 1}, {"compensator", "EncoderLoop"},
            {"feedforward", learned_file()}, {"kp", 0.0}, {"ki", 10.0}, {"kd", 0.0},
            {"derivative_cutoff_hz", 50.0}, {"max_correction", nullptr},
            {"limits", {{"min", nullptr}, {"max", nullptr}, {"max_rate", nullptr}}}};
  ts::io::LoadedCompensator looped = ts::io::compensator_from_json(loop);
  EXPECT_EQ(looped.kind(), "EncoderLoop");
  EXPECT_NE(looped.learned_correction(), nullptr);
  f = learned_file();
  f["feedforward"] = loop;
  EXPECT_NE(error_of(f).find("not an EncoderLoop"), std::string::npos) << error_of(f);
}

// A GeneralizedPrandtlIshlinskii file's options.envelope_range (as Python writes it) sets both
// envelopes' tanh input range; absent or null leaves them unbounded; a bad one is named.
TEST(IoJson, GeneralizedPIEnvelopeRangeLoads) {
  json gpi = malformed_json::generalized_pi_model();
  const ts::ModelPart part = ts::io::detail::part_from_json(gpi, "m");
  const auto& g = part.generalized_prandtl_ishlinskii;
  EXPECT_EQ(g.rising.lo, -0.5);
  EXPECT_EQ(g.rising.hi, 0.7);
  EXPECT_EQ(g.falling.lo, -0.5);
  EXPECT_EQ(g.falling.hi, 0.7);
  EXPECT_EQ(error_of(inverse_file(gpi)), "(no error)");
  json open = gpi;
  open["options"]["envelope_range"] = nullptr;
  EXPECT_TRUE(std::isinf(ts::io::detail::part_from_json(open, "m").generalized_prandtl_ishlinskii.rising.hi));
  open["options"] = json::object();
  EXPECT_TRUE(std::isinf(ts::io::detail::part_from_json(open, "m").generalized_prandtl_ishlinskii.falling.lo));
  json bad = gpi;
  bad["options"]["envelope_range"] = {0.7, -0.5};
  EXPECT_NE(error_of(inverse_file(bad)).find("'envelope_range' must be null or [lo, hi]"),
            std::string::npos)
      << error_of(inverse_file(bad));
  bad["options"] = {{"range", {0.0, 1.0}}};
  EXPECT_NE(error_of(inverse_file(bad)).find("unknown key 'range'"), std::string::npos);
}

// "version" is the integer 1: JSON true (Python's True == 1) and 1.0 are refused, as in Python.
TEST(IoJson, TheVersionMustBeTheInteger) {
  for (const json& version : {json(true), json(1.0), json("1"), json(2)}) {
    json f = curve_angle_file();
    f["version"] = version;
    EXPECT_NE(error_of(f).find("unsupported 'version'"), std::string::npos) << error_of(f);
    json inv = inverse_file(backlash_model4(1, 1, 0.1, 0.1));
    inv["model"]["version"] = version;
    EXPECT_NE(error_of(inv).find("unsupported 'version'"), std::string::npos) << error_of(inv);
  }
  EXPECT_EQ(error_of(curve_angle_file()), "(no error)");
}
