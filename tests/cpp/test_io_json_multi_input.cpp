// tendonsheath/io/json_multi_input.hpp: LoadCompensated and CoupledFeedforward files (as Python
// writes them) load into the core's classes, which then give their closed forms; every malformed
// key is a one-line error naming the file and the key; the loaded step allocates nothing.
// (Python's commands against these loaders: tests/test_cpp_multi_input_json.py.)
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <new>
#include <random>
#include <string>
#include <tendonsheath/io/json_multi_input.hpp>
#include <vector>

#include "counting_new.hpp"  // counts allocations while armed
#include "json_malformed_cases.hpp"  // the malformed files, shared with no_exceptions/json_cases.cpp

namespace ts = tendonsheath;
using ts::io::json;

static_assert(noexcept(std::declval<ts::io::LoadCompensatedInverse&>().step(0.0, 0.0, 0.0)));
static_assert(noexcept(std::declval<ts::CoupledFeedforward&>().step(nullptr, nullptr, 0.0)));

namespace {

using malformed_json::backlash_model;
using malformed_json::BadCase;
using malformed_json::coupled_file;
using malformed_json::load_compensated_file;
using malformed_json::three_joints;

// the loader's message for `file` ("(no error)" when it loads)
std::string error_of(const std::function<void(const json&)>& load, const json& file) {
  try {
    load(file);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

void load_lc(const json& f) { ts::io::load_compensated_from_json(f, "f.json"); }
void load_cf(const json& f) { ts::io::coupled_feedforward_from_json(f, "f.json"); }

void expect_named(const std::function<void(const json&)>& load, const json& good,
                  const std::vector<BadCase>& cases) {
  for (std::size_t k = 0; k < cases.size(); ++k) {
    json f = good;
    cases[k].change(f);
    const std::string msg = error_of(load, f);
    EXPECT_EQ(msg.rfind("f.json", 0), 0u) << "case " << k << ": " << msg;
    EXPECT_NE(msg.find(cases[k].words), std::string::npos) << "case " << k << ": " << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "case " << k << ": " << msg;
  }
}

}  // namespace

TEST(IoJsonMultiInput, LoadCompensatedWithoutPlayIsTheStretchTakenOff) {
  // identity base, no play (slack = friction = 0): x = y_d - gain L, L held when not finite
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const double gain = 2.0 * u(rng);
    auto c = ts::io::load_compensated_from_json(load_compensated_file(gain, 0.0, 0.5, 0.0));
    double last = 0.0;
    for (int k = 0; k < 200; ++k) {
      const double y_d = u(rng), load = k % 37 == 5 ? NAN : u(rng);
      if (std::isfinite(load)) last = load;
      ASSERT_NEAR(c.step(y_d, k ? 1e-3 : 0.0, load), y_d - gain * last, 1e-12) << trial;
    }
  }
}

TEST(IoJsonMultiInput, LoadCompensatedAddsThePlayRadiusOfTheLoadInTheDirectionOfTravel) {
  // identity base: after one base-input step beyond the switch travel the play's direction is
  // +1 on a rise and -1 on a fall: x = z +- (slack exp(-|L| / slack_load) + friction |L|)
  const double gain = -0.7, slack = 0.04, slack_load = 0.3, friction = 0.2, load = -0.45;
  auto c = ts::io::load_compensated_from_json(
      load_compensated_file(gain, slack, slack_load, friction, 1e-3));
  const double r = slack * std::exp(-0.45 / slack_load) + friction * 0.45;
  for (int k = 0; k < 100; ++k) {
    const double y_d = 0.01 * k, z = y_d - gain * load;
    const double x = c.step(y_d, k ? 1e-3 : 0.0, load);
    if (k > 0) {
      ASSERT_NEAR(x, z + r, 1e-12) << k;
    }
  }
  for (int k = 99; k >= 0; --k) {
    const double y_d = 0.01 * k - 0.005, z = y_d - gain * load;
    ASSERT_NEAR(c.step(y_d, 1e-3, load), z - r, 1e-12) << k;
  }
  EXPECT_EQ(c.terms().switch_travel, 1e-3);
}

TEST(IoJsonMultiInput, CoupledFeedforwardOfIdentityJointsIsYdMinusCYdRowMajor) {
  auto c = ts::io::coupled_feedforward_from_json(three_joints());
  const double C[3][3] = {{0.0, 0.2, -0.1}, {0.05, 0.0, 0.3}, {-0.25, 0.15, 0.0}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double y[3], x[3];
  for (int k = 0; k < 300; ++k) {
    for (double& v : y) v = u(rng);
    c.step(y, x, k ? 1e-3 : 0.0);
    for (int i = 0; i < 3; ++i) {
      double h = y[i];
      for (int j = 0; j < 3; ++j) h -= C[i][j] * y[j];
      ASSERT_NEAR(x[i], h, 1e-12) << "step " << k << " joint " << i;
    }
  }
}

TEST(IoJsonMultiInput, CoupledJointsTakeTheirOwnModelsRangeUnlessTheFileGivesOne) {
  json narrow = backlash_model();
  narrow["input_range"] = {-0.1, 0.1};  // span 0.2: commands held in [-0.12, 0.12]
  json f = coupled_file({backlash_model(), narrow}, {{0.0, 0.0}, {0.0, 0.0}});
  auto own = ts::io::coupled_feedforward_from_json(f);
  const double y[2] = {0.5, 0.5};
  double x[2];
  own.step(y, x, 0.0);
  EXPECT_NEAR(x[0], 0.5, 1e-12);  // no range of its own: not held
  EXPECT_NEAR(x[1], 0.12, 1e-12);
  EXPECT_TRUE(ts::has(own.status(), ts::Status::out_of_range));
  f["input_range"] = {-1.0, 1.0};  // the file's range, for every joint
  auto given = ts::io::coupled_feedforward_from_json(f);
  given.step(y, x, 0.0);
  EXPECT_NEAR(x[1], 0.5, 1e-12);
  f["input_range"] = nullptr;  // null: unbounded
  auto none = ts::io::coupled_feedforward_from_json(f);
  const double far[2] = {5.0, 5.0};
  none.step(far, x, 0.0);
  EXPECT_NEAR(x[1], 5.0, 1e-12);
}

TEST(IoJsonMultiInput, MalformedLoadCompensatedFilesNameTheKey) {
  const json good = load_compensated_file(0.3, 0.02, 0.1, 0.05);
  ASSERT_EQ(error_of(load_lc, good), "(no error)");
  expect_named(load_lc, good, malformed_json::load_compensated_cases());
}

TEST(IoJsonMultiInput, MalformedCoupledFeedforwardFilesNameTheKey) {
  const json good = three_joints();
  ASSERT_EQ(error_of(load_cf, good), "(no error)");
  expect_named(load_cf, good, malformed_json::coupled_feedforward_cases());
  json singular = coupled_file({backlash_model(), backlash_model()}, {{0.0, 1.0}, {1.0, 0.0}});
  EXPECT_NE(error_of(load_cf, singular).find("singular"), std::string::npos);
}

TEST(IoJsonMultiInput, AFileNamesItselfAndANumberBeyondADouble) {
  const std::string path = ::testing::TempDir() + "load_compensated.json";
  std::string text = load_compensated_file(0.3, 0.02, 0.1, 0.05).dump();
  text.replace(text.find("\"switch\":0.001"), 14, "\"switch\":1e999");
  std::FILE* out = std::fopen(path.c_str(), "w");
  ASSERT_NE(out, nullptr);
  std::fputs(text.c_str(), out);
  std::fclose(out);
  try {
    ts::io::load_load_compensated_json(path);
    FAIL() << "1e999 loaded";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_NE(msg.find("key 'switch'"), std::string::npos) << msg;
  }
  EXPECT_THROW(ts::io::load_coupled_feedforward_json(path), std::invalid_argument);
}

TEST(IoJsonMultiInput, TheSingleInputLoaderPointsHere) {
  const auto single = [](const json& f) { ts::io::compensator_from_json(f, "f.json"); };
  EXPECT_NE(error_of(single, load_compensated_file(0.0, 0.0, 1.0, 0.0))
                .find("io::load_compensated_from_json"),
            std::string::npos);
  EXPECT_NE(error_of(single, three_joints()).find("io::coupled_feedforward_from_json"),
            std::string::npos);
  EXPECT_NE(error_of(load_lc, three_joints()).find("key 'compensator' must be \"LoadCompensated\""),
            std::string::npos);
}

TEST(IoJsonMultiInput, LoadedStepsAllocateNothing) {
  auto lc = ts::io::load_compensated_from_json(load_compensated_file(0.3, 0.02, 0.1, 0.05));
  auto cf = ts::io::coupled_feedforward_from_json(three_joints());
  double y[3], x[3], sum = 0.0;
  const auto run = [&] {
    for (int k = 0; k < 500; ++k) {
      const double t = 1e-3 * k, s = std::sin(6.0 * t);
      sum += lc.step(s, 1e-3, k == 100 ? NAN : 0.2 * s);
      y[0] = s, y[1] = k == 200 ? NAN : -s, y[2] = 0.5 * s;
      cf.step(y, x, 1e-3);
      sum += x[0] + x[1] + x[2];
    }
  };
  run();
  allocations = 0;
  armed = true;
  run();
  armed = false;
  EXPECT_EQ(allocations.load(), 0);
  EXPECT_TRUE(std::isfinite(sum));
  armed = true;  // the counter counts: loading allocates
  const auto again = ts::io::coupled_feedforward_from_json(three_joints());
  armed = false;
  EXPECT_GT(allocations.load(), 0);
  EXPECT_EQ(again.joints(), 3u);
}
