// LearnedCorrection / LearnedFeedforward: a learned correction table played back in time and
// added to a feedforward's command. Checked against a direct interpolation over random tables and
// time steps, for what it adds past the table's end, its validation and the bench wrapper.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
ts::LearnedCorrection make(std::vector<double> table, double table_dt, bool hold_last = true) {
  ts::LearnedFeedforwardParams p;
  p.table_dt = table_dt, p.hold_last = hold_last;
  return ts::LearnedCorrection(std::move(table), p);
}

// The table at t written out directly: the two samples around t, weighted by distance.
double direct(const std::vector<double>& c, double table_dt, double t, bool hold_last) {
  const double end = (c.size() - 1) * table_dt;
  if (t > end) return hold_last ? c.back() : 0.0;
  if (t >= end) return c.back();
  const double pos = t / table_dt;
  const double lo = std::floor(pos);
  const auto i = static_cast<std::size_t>(lo);
  return (1.0 - (pos - lo)) * c[i] + (pos - lo) * c[i + 1];
}

std::string message_of(const std::vector<double>& table, double table_dt) {
  try {
    make(table, table_dt);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(LearnedCorrection, InterpolatesRandomTablesLikeADirectComputation) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> v(-1.0, 1.0), step(0.1e-3, 3e-3);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> table(2 + trial * 7);
    for (double& c : table) c = v(rng);
    const double table_dt = 1e-3 * (0.5 + 2.0 * (v(rng) + 1.0));
    const bool hold = trial % 2 == 0;
    ts::LearnedCorrection player = make(table, table_dt, hold);
    double t = 0.0;
    for (int k = 0; k < 400; ++k) {
      const double dt = k == 0 ? 0.0 : step(rng);
      t += dt;
      const double target = v(rng);
      const double u = player.correct(target, dt);
      const double c = direct(table, table_dt, t, hold);
      ASSERT_NEAR(u, target + c, 1e-12) << "trial " << trial << " k " << k;
      ASSERT_NEAR(player.time(), t, 1e-12);
      ASSERT_EQ(ts::has(player.status(), ts::Status::input_clamped), t > player.duration());
    }
  }
}

TEST(LearnedCorrection, SamplesAtTheTableTimesAreTheTableItself) {
  const std::vector<double> table{0.3, -0.2, 0.5, 0.1};
  ts::LearnedCorrection player = make(table, 1e-3);
  for (std::size_t k = 0; k < table.size(); ++k)
    EXPECT_NEAR(player.correct(1.0, k == 0 ? 0.0 : 1e-3) - 1.0, table[k], 1e-12);
}

TEST(LearnedCorrection, PastTheEndItHoldsTheLastSampleOrAddsZero) {
  ts::LearnedCorrection hold = make({0.1, 0.2, 0.4}, 0.01, true);
  ts::LearnedCorrection zero = make({0.1, 0.2, 0.4}, 0.01, false);
  for (int k = 0; k < 10; ++k) {
    const double dt = k == 0 ? 0.0 : 0.01;
    const double h = hold.correct(1.0, dt), z = zero.correct(1.0, dt);
    if (k <= 2) {
      EXPECT_DOUBLE_EQ(h, z);
      EXPECT_FALSE(ts::has(hold.status(), ts::Status::input_clamped));
    } else {
      EXPECT_DOUBLE_EQ(h, 1.4);
      EXPECT_DOUBLE_EQ(z, 1.0);
      EXPECT_TRUE(ts::has(hold.status(), ts::Status::input_clamped));
      EXPECT_TRUE(ts::has(zero.status(), ts::Status::input_clamped));
    }
  }
  hold.reset();  // the time back to 0
  EXPECT_DOUBLE_EQ(hold.correct(1.0, 0.0), 1.1);
  EXPECT_EQ(hold.status(), ts::Status::ok);
}

TEST(LearnedCorrection, ANonFiniteTargetHoldsTheLastCommandAndTimeGoesOn) {
  ts::LearnedCorrection player = make({0.0, 1.0, 2.0, 3.0}, 1.0);
  EXPECT_DOUBLE_EQ(player.correct(0.5, 0.0), 0.5);
  EXPECT_DOUBLE_EQ(player.correct(NAN, 1.0), 0.5);
  EXPECT_TRUE(ts::has(player.status(), ts::Status::held_nonfinite_input));
  EXPECT_DOUBLE_EQ(player.correct(0.5, 1.0), 2.5);  // t = 2
  EXPECT_DOUBLE_EQ(player.correct(0.5, NAN), 2.5);  // a bad dt: the time stays
  EXPECT_DOUBLE_EQ(player.time(), 2.0);
}

TEST(LearnedCorrection, LimitsShapeTheCorrectedCommand) {
  ts::LearnedFeedforwardParams p;
  p.table_dt = 1e-3, p.limits.max = 1.2;
  ts::LearnedCorrection player({0.5, 0.5}, p);
  EXPECT_DOUBLE_EQ(player.correct(1.0, 0.0), 1.2);
  EXPECT_TRUE(ts::has(player.status(), ts::Status::saturated));
}

TEST(LearnedCorrection, BadInputsAreNamed) {
  EXPECT_NE(message_of({}, 1e-3).find("the table is empty"), std::string::npos);
  EXPECT_NE(message_of({0.0, NAN}, 1e-3).find("table[1] is not finite"), std::string::npos);
  EXPECT_NE(message_of({0.0, INFINITY}, 1e-3).find("table[1]"), std::string::npos);
  EXPECT_NE(message_of({0.0}, 0.0).find("table_dt must be > 0"), std::string::npos);
  EXPECT_NE(message_of({0.0}, -1.0).find("table_dt"), std::string::npos);
  EXPECT_NE(message_of({0.0}, INFINITY).find("table_dt"), std::string::npos);
  ts::LearnedFeedforwardParams p;
  p.limits.min = 1.0, p.limits.max = -1.0;
  EXPECT_THROW(ts::LearnedCorrection({0.0}, p), std::invalid_argument);
}

TEST(LearnedFeedforward, AddsTheTableToAFeedforwardsCommand) {
  ts::BacklashInverseParams bp;
  bp.B_r = 0.05, bp.B_l = 0.08;
  ts::BacklashInverseFeedforward plain(bp);
  const std::vector<double> table{0.0, 0.01, -0.02, 0.03, 0.0, 0.05};
  ts::LearnedFeedforward<ts::BacklashInverseFeedforward> learned(plain, make(table, 2e-3));
  for (int k = 0; k < 20; ++k) {
    const double y = std::sin(0.3 * k), dt = k == 0 ? 0.0 : 1e-3;
    const double x = plain.step(y, dt);
    EXPECT_NEAR(learned.step(y, dt), x + direct(table, 2e-3, 1e-3 * k, true), 1e-12);
  }
  learned.set_shape(ts::uniform_shape(0.1, 1.0));  // not a route follower: ignored
  EXPECT_TRUE(ts::has(learned.status(), ts::Status::input_clamped));
}

TEST(LearnedFeedforward, RunsInTheBenchsClosedLoop) {
  ts::PullPullParams pp;
  pp.elements = 10;
  const auto route = ts::Route::uniform(1.0, 1.0);
  ts::PullPullPlant plant(pp, route, route);
  const std::size_t n = 200;
  std::vector<double> t(n), y_d(n), out_plain(n), out_learned(n), cmd_plain(n), cmd_learned(n);
  std::vector<double> table(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = 1e-3 * k, y_d[k] = 0.3 * std::sin(10.0 * t[k]);
    table[k] = 0.01 * std::cos(5.0 * t[k]);
  }
  ts::OpenLoop open{1.0};
  ts::WithLearnedCorrection<ts::OpenLoop> learned{open, make(table, 1e-3)};
  ts::ClosedLoopTrace a{out_plain.data(), nullptr, cmd_plain.data()};
  ts::ClosedLoopTrace b{out_learned.data(), nullptr, cmd_learned.data()};
  ts::run_closed_loop(plant, nullptr, nullptr, open, t.data(), y_d.data(), n, {}, {}, nullptr, a,
                      "test");
  ts::run_closed_loop(plant, nullptr, nullptr, learned, t.data(), y_d.data(), n,
                      {}, {}, nullptr, b, "test");
  for (std::size_t k = 0; k < n; ++k) ASSERT_NEAR(cmd_learned[k], cmd_plain[k] + table[k], 1e-12);
}
