// LoadCompensated: the load's play half-width against its closed form, the inverse driving a
// loaded backlash (base backlash, play of the load's width, stretch gain L) to the desired
// output, held loads, validation and the real-time contract.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

using Comp = ts::LoadCompensated<ts::BacklashInverseFeedforward>;
static_assert(noexcept(std::declval<Comp&>().step(0.0, 0.0, 0.0)));
static_assert(noexcept(std::declval<ts::LoadPlayInverse&>().step(0.0, 0.0)));

namespace {

ts::LoadTerms random_terms(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ts::LoadTerms t;
  t.gain = -2.0 + 4.0 * u(rng);
  t.slack = 0.01 + 0.04 * u(rng);
  t.slack_load = 0.02 + 0.08 * u(rng);
  t.friction = 0.2 * u(rng);
  t.switch_travel = 0.25 * t.slack;
  return t;
}

}  // namespace

TEST(LoadTerms, RadiusIsTheClosedForm) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 100; ++trial) {
    const ts::LoadTerms t = random_terms(rng);
    const double load = 0.3 * u(rng);
    const double a = std::fabs(load);
    EXPECT_NEAR(t.radius(load), t.slack * std::exp(-a / t.slack_load) + t.friction * a, 1e-15);
    EXPECT_DOUBLE_EQ(t.radius(load), t.radius(-load));
  }
}

TEST(LoadCompensated, DrivesALoadedBacklashToTheDesiredOutput) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 5; ++trial) {
    const ts::LoadTerms terms = random_terms(rng);
    ts::BacklashParams bp{1.1, 1.1, 0.02, 0.02};
    ts::BacklashInverseParams ip{1.1, 1.1, 0.02, 0.02, 0.05, {}};
    Comp comp(ts::BacklashInverseFeedforward(ip), terms);
    ts::Backlash base(bp);
    const double dt = 1e-3, phase = 6.0 * u(rng);
    double z = 0.0, worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const double t = k * dt;
      const double y_d = 0.3 * std::sin(2.0 * M_PI * t + phase);
      const double load = -0.05 * (1.5 + std::sin(2.0 * M_PI * 0.3 * t));
      const double x = comp.step(y_d, k == 0 ? 0.0 : dt, load);
      const double r = terms.radius(load);
      z = k == 0 ? x : std::clamp(z, x - r, x + r);  // the plant's play, mid-band at start
      const double y = base.step(z) + terms.gain * load;
      if (t > 0.5) worst = std::max(worst, std::fabs(y - y_d));
    }
    // the switches are smoothed (a quarter of the slack, 0.05 /s of rate): the output lags
    // by a few mrad at a reversal; 12 mrad is under a third of the band 2 r (~40 mrad)
    EXPECT_LT(worst, 0.012) << "trial " << trial;
  }
}

TEST(LoadCompensated, ANonFiniteLoadHoldsTheLastAndCommandsStayFinite) {
  ts::LoadTerms terms;
  terms.gain = 1.5;
  terms.slack = 0.03;
  terms.slack_load = 0.05;
  terms.friction = 0.1;
  terms.switch_travel = 0.01;
  ts::BacklashInverseParams ip{1.0, 1.0, 0.02, 0.02, 0.05, {}};
  Comp a(ts::BacklashInverseFeedforward(ip), terms), b = a;
  double held = 0.0;  // b is given NaN where a is given the last load measured
  for (int k = 0; k < 200; ++k) {
    const double y_d = 0.2 * std::sin(0.05 * k), load = -0.04 - 0.01 * std::sin(0.1 * k);
    if (k % 3 == 0) held = load;
    const double ua = a.step(y_d, 1e-3, held);
    const double ub = b.step(y_d, 1e-3, k % 3 == 0 ? load : NAN);
    EXPECT_TRUE(std::isfinite(ub));
    EXPECT_DOUBLE_EQ(ua, ub);
  }
}

TEST(LoadCompensated, TermsOutOfRangeAreNamed) {
  ts::LoadTerms t;
  t.slack_load = 0.0;
  EXPECT_THROW(ts::LoadPlayInverse{t}, std::invalid_argument);
  try {
    ts::LoadPlayInverse{t};
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("slack_load"), std::string::npos);
  }
  t = ts::LoadTerms{};
  t.friction = -1.0;
  EXPECT_THROW(ts::LoadPlayInverse{t}, std::invalid_argument);
}
