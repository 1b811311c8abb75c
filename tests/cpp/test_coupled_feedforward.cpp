// CoupledFeedforward (compensators/coupled_feedforward.hpp): over random coupled Backlash joints
// its commands make the coupled model y = H(x) + C y follow the desired angles; the targets are
// y_d - C y_d exactly; a non-finite desired angle holds its joint only; construction refuses
// bad couplings; step() allocates nothing (test_no_allocation covers it).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

ts::ModelInverse backlash_inverse(const ts::BacklashParams& b) {
  ts::ModelPart p;
  p.kind = "Backlash";
  p.backlash = b;
  ts::InverseModel m;
  m.parts = {p};
  ts::InverseSettings s;
  s.smoothing = 0.002;
  return ts::make_model_inverse(m, s);
}

// y = (I - C)^-1 h for a lower-triangular C (joint i coupled to joints j < i): forward
// substitution
std::vector<double> joint_angles(const std::vector<double>& h, const std::vector<double>& c) {
  const std::size_t n = h.size();
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i) {
    y[i] = h[i];
    for (std::size_t j = 0; j < i; ++j) y[i] += c[i * n + j] * y[j];
  }
  return y;
}
}  // namespace

TEST(CoupledFeedforward, TheCoupledModelFollowsTheDesiredAnglesOverRandomCases) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> gain(0.8, 1.2), band(0.01, 0.1), coupling(-0.3, 0.3);
  const std::size_t n = 3;
  const double dt = 1e-3;
  for (int trial = 0; trial < 10; ++trial) {
    std::vector<ts::ModelInverse> inverses;
    std::vector<ts::Backlash> models;
    for (std::size_t i = 0; i < n; ++i) {
      ts::BacklashParams b;
      b.c_r = b.c_l = gain(rng);  // equal slopes: the branches never cross
      b.B_r = band(rng);
      b.B_l = band(rng);
      inverses.push_back(backlash_inverse(b));
      models.emplace_back(b);
    }
    std::vector<double> c(n * n, 0.0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < i; ++j) c[i * n + j] = coupling(rng);
    ts::CoupledFeedforward ff(inverses, c);
    double worst = 0.0, worst_uncoupled = 0.0;
    std::vector<ts::Backlash> plain = models;
    ts::CoupledFeedforward uncoupled(inverses, std::vector<double>(n * n, 0.0));
    for (int k = 0; k < 4000; ++k) {
      const double t = k * dt;
      double y_d[3], u[3], v[3];
      for (std::size_t i = 0; i < n; ++i) y_d[i] = 0.5 * std::sin(2 * kPi * (0.4 + 0.25 * i) * t);
      ff.step(y_d, u, k ? dt : 0.0);
      uncoupled.step(y_d, v, k ? dt : 0.0);
      std::vector<double> h(n), g(n);
      for (std::size_t i = 0; i < n; ++i) {
        h[i] = models[i].step(u[i]);
        g[i] = plain[i].step(v[i]);
        // the targets are y_d - C y_d, to rounding
        double target = y_d[i];
        for (std::size_t j = 0; j < n; ++j) target -= c[i * n + j] * y_d[j];
        ASSERT_NEAR(ff.targets()[i], target, 1e-15);
      }
      const auto y = joint_angles(h, c), z = joint_angles(g, c);
      if (k < 10) continue;
      for (std::size_t i = 0; i < n; ++i) {
        worst = std::max(worst, std::fabs(y[i] - y_d[i]));
        worst_uncoupled = std::max(worst_uncoupled, std::fabs(z[i] - y_d[i]));
      }
    }
    // the smoothed branch switch costs a little at each reversal (Python's test of the same
    // cases measured at most 3.3e-5 rad); ignoring the coupling misses by a coupling's share
    EXPECT_LT(worst, 2e-4) << "trial " << trial;
    EXPECT_GT(worst_uncoupled, 0.02) << "trial " << trial;
  }
}

TEST(CoupledFeedforward, ANonFiniteDesiredAngleHoldsItsJointOnly) {
  ts::BacklashParams b;
  std::vector<ts::ModelInverse> inverses{backlash_inverse(b), backlash_inverse(b)};
  ts::CoupledFeedforward ff(inverses, {0.0, 0.0, 0.25, 0.0});
  double u[2], held[2];
  for (int k = 0; k < 100; ++k) {
    const double y_d[2] = {0.3 * std::sin(0.05 * k), 0.2 * std::sin(0.03 * k)};
    ff.step(y_d, u, 1e-3);
  }
  const double bad[2] = {NAN, 0.2};
  ff.step(bad, held, 1e-3);
  EXPECT_EQ(held[0], u[0]);  // joint 0 holds its command
  EXPECT_TRUE(std::isfinite(held[1]));
  // joint 1's target used joint 0's last finite desired angle
  EXPECT_NEAR(ff.targets()[1], 0.2 - 0.25 * 0.3 * std::sin(0.05 * 99), 1e-15);
  EXPECT_TRUE(ts::has(ff.status(), ts::Status::held_nonfinite_input));
  ff.reset();
  const double zero[2] = {0.0, 0.0};
  ff.step(zero, u, 0.0);
  EXPECT_TRUE(std::isfinite(u[0]) && std::isfinite(u[1]));
}

TEST(CoupledFeedforward, RefusesBadCouplings) {
  ts::BacklashParams b;
  std::vector<ts::ModelInverse> two{backlash_inverse(b), backlash_inverse(b)};
  EXPECT_THROW(ts::CoupledFeedforward({}, {}), std::invalid_argument);
  EXPECT_THROW(ts::CoupledFeedforward(two, {0.0, 0.1, 0.2}), std::invalid_argument);
  EXPECT_THROW(ts::CoupledFeedforward(two, {0.1, 0.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(ts::CoupledFeedforward(two, {0.0, 1.0, 1.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(ts::CoupledFeedforward(two, {0.0, NAN, 0.0, 0.0}), std::invalid_argument);
  try {
    ts::CoupledFeedforward(two, {0.0, 0.0, 0.0, 0.5});
    FAIL() << "a non-zero diagonal was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("diagonal"), std::string::npos) << e.what();
  }
  ts::CoupledFeedforward ok(two, {0.0, 0.0, 0.25, 0.0});
  EXPECT_EQ(ok.joints(), 2u);
  EXPECT_EQ(ok.coupling(1, 0), 0.25);
}
