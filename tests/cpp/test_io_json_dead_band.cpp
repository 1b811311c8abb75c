// DeadBandInverse, the worked example of docs/contributing.md ("Adding a compensator"): with only
// its header and its entry in the compensator list, it inverts a dead zone to its closed form,
// runs in the closed loop's generic CompensatorLoop, and loads from the file Python writes (one
// key per row of its table; tests/test_contributor_compensator.py checks Python writes it so).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tendonsheath/io/json.hpp>
#include <tendonsheath/tendonsheath.hpp>
#include <variant>

namespace ts = tendonsheath;
using ts::io::json;

namespace {

double dead_zone(const ts::DeadBandInverseParams& p, double u) {
  if (u > p.d_r) return p.c_r * (u - p.d_r);
  if (u < -p.d_l) return p.c_l * (u + p.d_l);
  return 0.0;
}

json dead_band_file() {
  return json::parse(R"({"format": "tendonsheath.compensator", "version": 1,
    "compensator": "DeadBandInverse", "c_r": 2.0, "c_l": 0.5, "d_r": 0.1, "d_l": 0.2,
    "eps": 0.01})");
}

}  // namespace

TEST(DeadBandInverse, InvertsADeadZoneToItsClosedFormOverRandomCases) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int c = 0; c < 50; ++c) {
    ts::DeadBandInverseParams p;
    p.c_r = 0.2 + 5.0 * u(rng);
    p.c_l = 0.2 + 5.0 * u(rng);
    p.d_r = 0.5 * u(rng);
    p.d_l = 0.5 * u(rng);
    p.eps = c % 2 ? 0.0 : 0.2 * u(rng);
    ts::DeadBandInverse inv(p);
    for (int k = 0; k < 200; ++k) {
      const double y_d = 2.0 * u(rng) - 1.0;
      const double y = dead_zone(p, inv.step(y_d, 1e-3));
      if (std::fabs(y_d) >= p.eps) {
        EXPECT_NEAR(y, y_d, 1e-12);  // c (y/c + d - d) = y, to rounding
      } else {  // inside the smoothing width: the same sign, no larger
        EXPECT_LE(std::fabs(y), std::fabs(y_d) + 1e-12);
        EXPECT_GE(y * y_d, -1e-15);
      }
    }
    EXPECT_EQ(dead_zone(p, inv.step(0.0, 1e-3)), 0.0);  // 0 is the dead zone's middle
  }
}

TEST(DeadBandInverse, HoldsANonFiniteInputAndSaysSo) {
  ts::DeadBandInverseParams p;
  p.d_r = 0.1;
  ts::DeadBandInverse inv(p);
  const double u = inv.step(0.3, 1e-3);
  EXPECT_EQ(inv.step(NAN, 1e-3), u);
  EXPECT_EQ(inv.status(), ts::Status::held_nonfinite_input);
  EXPECT_EQ(inv.step(INFINITY, 1e-3), u);
  EXPECT_TRUE(std::isfinite(inv.step(-1e308, 1e-3)));
  EXPECT_EQ(inv.status(), ts::Status::ok);
  static_assert(noexcept(inv.step(0.0, 0.0)));
}

TEST(DeadBandInverse, BadParametersAreNamed) {
  ts::DeadBandInverseParams p;
  p.c_l = 0.0;
  EXPECT_THROW(ts::DeadBandInverse{p}, std::invalid_argument);
  const auto r = ts::make<ts::DeadBandInverse>(p);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("DeadBandInverse: c_l must be > 0"), std::string::npos) << r.error();
}

TEST(DeadBandInverse, IsInTheListAndRunsInTheGenericLoop) {
  static_assert(ts::list_contains_v<ts::Compensators, ts::DeadBandInverse>);
  static_assert(std::is_same_v<ts::loop_of_t<ts::DeadBandInverse>,
                               ts::CompensatorLoop<ts::DeadBandInverse>>);
  ts::DeadBandInverseParams p;
  p.c_r = 2.0;
  p.d_r = 0.1;
  ts::CompensatorLoop<ts::DeadBandInverse> loop{ts::DeadBandInverse(p)};
  ts::DeadBandInverse alone(p);
  loop.reset();
  for (int k = 0; k < 100; ++k) {
    const double y_d = std::sin(0.1 * k);
    EXPECT_EQ(loop.command(y_d, NAN, 0.0, 1e-3), alone.step(y_d, 1e-3));
  }
  EXPECT_FALSE(loop.in_fallback());
}

TEST(DeadBandInverse, LoadsFromTheFilePythonWrites) {
  ts::io::LoadedCompensator c = ts::io::compensator_from_json(dead_band_file());
  EXPECT_EQ(c.kind(), "DeadBandInverse");
  ASSERT_TRUE(std::holds_alternative<ts::DeadBandInverse>(c.engine()));
  const ts::DeadBandInverseParams& p = std::get<ts::DeadBandInverse>(c.engine()).params();
  EXPECT_EQ(p.c_r, 2.0);
  EXPECT_EQ(p.c_l, 0.5);
  EXPECT_EQ(p.d_r, 0.1);
  EXPECT_EQ(p.d_l, 0.2);
  EXPECT_EQ(p.eps, 0.01);
  ts::DeadBandInverse direct(p);
  for (int k = 0; k < 100; ++k) {
    const double y_d = 0.5 * std::sin(0.07 * k);
    EXPECT_EQ(c.step(y_d, 1e-3), direct.step(y_d, 1e-3));
  }
}

TEST(DeadBandInverse, AMalformedFileIsNamed) {
  const auto message = [](const json& f) {
    const auto r = ts::io::try_compensator_from_json(f, "f.json");
    return r.ok() ? std::string("loaded") : r.error();
  };
  json f = dead_band_file();
  f.erase("eps");
  EXPECT_EQ(message(f), "f.json: key 'eps' is missing");
  f = dead_band_file();
  f["gain"] = 1.0;
  EXPECT_EQ(message(f), "f.json: unknown key 'gain'");
  f = dead_band_file();
  f["c_r"] = "2";
  EXPECT_EQ(message(f), "f.json: key 'c_r' must be a number (got \"2\")");
  f = dead_band_file();
  f["d_l"] = -1.0;
  EXPECT_EQ(message(f), "f.json: DeadBandInverse: d_l must be >= 0 (got -1)");
  f = dead_band_file();
  f["compensator"] = "NoSuch";
  EXPECT_NE(message(f).find("(known: ContinuumFeedforward, CurveAngleFeedforward, DeadBandInverse, "
                            "EncoderLoop, InverseFeedforward, LearnedFeedforward, TipLoop)"),
            std::string::npos)
      << message(f);
}
