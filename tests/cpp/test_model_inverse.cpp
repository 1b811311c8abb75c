// The inverse of every identified model (compensators/model_inverse.hpp): closed forms and
// invariants over many random cases. The root search finds the root nearest the previous
// command and stays in its range; the lag and oscillator inverses make their models follow the
// filtered reference; the angle laws equal their closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "model_inverse_cases.hpp"

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

ts::InverseModel one(const ts::ModelPart& p) {
  ts::InverseModel m;
  m.parts = {p};
  return m;
}

ts::ModelInverse build(const ts::InverseModel& m, ts::InputRange range = {}, double hz = 0.0) {
  ts::InverseSettings s;
  s.range = range;
  s.filter_hz = hz;
  return ts::make_model_inverse(m, s);
}

// y of a first-order-hold lag 1/(tau s + 1) started at rest at its first input (Python's
// FirstOrderLag.filter_coefficients, closed form)
std::vector<double> foh_lag(const std::vector<double>& u, double tau, double dt) {
  const double r = dt / tau, a = std::exp(-r), g = -std::expm1(-r) / r;
  std::vector<double> y(u.size());
  y[0] = u[0];
  for (std::size_t k = 1; k < u.size(); ++k) y[k] = a * y[k - 1] + (1 - g) * u[k] + (g - a) * u[k - 1];
  return y;
}
}  // namespace

// A monotone cubic: the root is exact (the map's output equals y_d to rounding), random
// coefficients and targets.
TEST(ModelInverse, RootOfAMonotoneStaticMapIsExact) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> c(0.1, 2.0), y(-3.0, 3.0);
  for (int trial = 0; trial < 100; ++trial) {
    ts::ModelPart p = ts::cases::part("Polynomial");
    p.polynomial.coefficients = {c(rng) - 1.0, c(rng), 0.0, c(rng)};  // a1, a3 > 0: increasing
    ts::ModelInverse inv = build(one(p));
    ts::Polynomial f(p.polynomial);
    for (int k = 0; k < 50; ++k) {
      const double yd = y(rng), x = inv.step(yd, 1e-3);
      ASSERT_NEAR(f.evaluate(x), yd, 1e-11 * (1.0 + std::fabs(yd))) << trial;
      ASSERT_EQ(inv.status(), ts::Status::ok);
    }
  }
}

// Of the roots of a non-monotone map, the one nearest the previous command: y = x^3 - x has
// three roots of y = 0 (-1, 0, 1); from x near 1 the search stays on that branch.
TEST(ModelInverse, TheRootNearestThePreviousCommand) {
  ts::ModelPart p = ts::cases::part("Polynomial");
  p.polynomial.coefficients = {0.0, -1.0, 0.0, 1.0};
  ts::ModelInverse inv = build(one(p));
  EXPECT_NEAR(inv.step(6.0, 1e-3), 2.0, 1e-12);  // the only real root
  for (double yd = 6.0; yd >= 0.0; yd -= 0.01) inv.step(yd, 1e-3);
  EXPECT_NEAR(inv.step(0.0, 1e-3), 1.0, 1e-12);  // not -1 or 0
  for (int k = 0; k < 20; ++k) inv.step(-0.3 - 0.005 * k, 1e-3);  // past the local minimum
  EXPECT_LT(inv.step(-0.5, 1e-3), -1.0);  // unreachable near 1: jumps to the left branch
}

// An unreachable target: held at the range's edge and flagged out_of_range, for the root
// search, the exact PI inverse and the direct D.2 inverse alike.
TEST(ModelInverse, UnreachableTargetsAreHeldAtTheEdgeAndFlagged) {
  const ts::InputRange range{-0.5, 0.5};
  for (int i : {0, 1, 2, 3, 4, 5, 7}) {
    ts::ModelInverse inv = ts::cases::inverse_case(i, range);
    double x = 0.0;
    for (int k = 0; k <= 100; ++k) x = inv.step(0.05 * k, 1e-3);  // up to 5: out of reach
    EXPECT_EQ(x, 0.5) << "case " << i;
    EXPECT_TRUE(ts::has(inv.status(), ts::Status::out_of_range)) << "case " << i;
    x = inv.step(-5.0, 1e-3);
    EXPECT_EQ(x, -0.5) << "case " << i;
    for (int k = 0; k < 200; ++k) x = inv.step(0.0, 1e-3);  // reachable again
    EXPECT_FALSE(ts::has(inv.status(), ts::Status::out_of_range)) << "case " << i;
  }
}

// The GPI saturates: with no range its unreachable target exhausts the search budget, which
// bounds the work, and the command is the best probe, flagged not_converged.
TEST(ModelInverse, TheSearchBudgetBoundsTheWork) {
  ts::ModelInverse inv = ts::cases::inverse_case(3);
  const double x = inv.step(100.0, 1e-3);
  EXPECT_TRUE(std::isfinite(x));
  EXPECT_TRUE(ts::has(inv.status(), ts::Status::not_converged));
  const auto& root = std::get<ts::RootInverse<ts::ForwardModel>>(inv.core());
  EXPECT_LE(root.evaluations(), ts::RootSearchSettings{}.max_evaluations);
}

// FirstOrderLag: its FOH form after the lag inverse follows y_d through 1/(tau_f s + 1):
// compared with that filter's own FOH closed form, random tau, corners and references.
TEST(ModelInverse, FirstOrderLagInverseFollowsTheFilter) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double dt = 1e-3;
  for (int trial = 0; trial < 30; ++trial) {
    ts::ModelPart p = ts::cases::part("FirstOrderLag");
    p.lag.order = 1;
    p.lag.time_constant = 0.005 + 0.1 * u(rng);
    const double hz = 5.0 + 40.0 * u(rng);
    ts::ModelInverse inv = build(one(p), {}, hz);
    const double f1 = 0.2 + u(rng), f2 = 1.0 + 3.0 * u(rng);
    std::vector<double> yd(4000), x(4000);
    for (std::size_t k = 0; k < yd.size(); ++k) {
      const double t = k * dt;
      yd[k] = 0.5 * std::sin(2 * kPi * f1 * t) + 0.2 * std::sin(2 * kPi * f2 * t);
      x[k] = inv.step(yd[k], k ? dt : 0.0);
    }
    const std::vector<double> y = foh_lag(x, p.lag.time_constant, dt);
    const std::vector<double> ref = foh_lag(yd, 1.0 / (2 * kPi * hz), dt);
    double worst = 0.0;
    for (std::size_t k = 0; k < y.size(); ++k) worst = std::fmax(worst, std::fabs(y[k] - ref[k]));
    // Tustin against the first-order hold: O((w dt)^2) of the signal; measured <= 5.2e-5
    EXPECT_LT(worst, 2e-4) << trial;
  }
}

// The oscillator follows the inverse's filtered reference (the filter's bound, nothing left
// of the dynamics but the RK4 and trapezoid discretisation), random oscillators.
TEST(ModelInverse, OscillatorFollowsTheFilteredReference) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double dt = 1e-3;
  for (int trial = 0; trial < 20; ++trial) {
    ts::HystereticOscillatorParams h;
    h.m = 1e-3 * (0.5 + u(rng)), h.c = 0.1 * u(rng), h.k = 0.5 + u(rng), h.alpha = u(rng);
    h.beta = 2.0 * u(rng), h.gamma = u(rng) - 0.2, h.delta = 0.5 * u(rng);
    ts::OscillatorInverse inv(h, 0.0);
    ts::HystereticOscillator osc(h);
    double worst = 0.0, peak = 0.0;
    for (int k = 0; k < 3000; ++k) {
      const double yd = 0.4 * std::sin(2 * kPi * 0.7 * k * dt) + 0.1 * std::sin(2 * kPi * 3.0 * k * dt);
      const double y = osc.step(inv.step(yd, k ? dt : 0.0), k ? dt : 0.0);
      worst = std::fmax(worst, std::fabs(y - inv.filtered()));
      peak = std::fmax(peak, std::fabs(yd));
    }
    // measured <= 6.7e-5 of the amplitude (the forward's linear input between samples)
    EXPECT_LT(worst, 3e-4 * peak) << trial;
  }
}

// The shape dead-zone factor: tanh(a/2) for a uniform route, and the two forms of PLAN
// convention 2 agree, over random shapes.
TEST(ModelInverse, ShapeDeadZoneFactorClosedForms) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 1000; ++trial) {
    const double mu = 0.01 + 0.5 * u(rng), theta = 10.0 * u(rng), a = mu * theta;
    const ts::ShapeIntegrals s = ts::uniform_shape(mu, theta);
    ASSERT_NEAR(ts::shape_dead_zone_factor(s.g, s.G, a), std::tanh(0.5 * a), 1e-13);
    const double g = 0.1 + u(rng), G = 0.1 + 3.0 * u(rng);
    const double plan = g / (g + G * std::exp(-2 * a)) - G / (G + g * std::exp(2 * a));
    ASSERT_NEAR(ts::shape_dead_zone_factor(g, G, a), plan, 1e-12);
  }
}

// The angle laws at a curve angle and at the uniform shape of that angle agree; a linear law
// follows Theta itself.
TEST(ModelInverse, AngleLawsAtAnAngleAndAtItsUniformShapeAgree) {
  ts::AngleLaws laws;
  laws.count = 3;
  laws.angle_friction = 0.2;
  laws.law[0] = ts::AngleLaw::constant, laws.c0[0] = 1.5;
  laws.law[1] = ts::AngleLaw::linear, laws.c0[1] = 0.1, laws.c1[1] = 0.02;
  laws.law[2] = ts::AngleLaw::tanh, laws.c0[2] = 0.01, laws.c1[2] = 0.3;
  for (double theta = 0.0; theta < 12.0; theta += 0.37) {
    double a[3], b[3];
    laws.at_angle(theta, a);
    laws.at_shape(ts::uniform_shape(0.2, theta), b);
    EXPECT_EQ(a[0], 1.5);
    EXPECT_DOUBLE_EQ(a[1], 0.1 + 0.02 * theta);
    EXPECT_NEAR(a[2], 0.01 + 0.3 * std::tanh(0.1 * theta), 1e-15);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(a[i], b[i], 1e-13);
  }
}

// A route-following D.2 inverse inverts the Backlash of the parameters at the route: an exact
// backlash inverse (smoothing -> 0) away from reversals, at every curve angle.
TEST(ModelInverse, AngleDependentBacklashFollowsTheCurveAngle) {
  ts::ModelPart p = ts::cases::laws_part("Backlash", 4);
  ts::InverseSettings s;
  s.smoothing = 1e-6;
  for (double theta : {0.5, 2.0, 6.0}) {
    ts::ModelInverse inv = ts::make_model_inverse(one(p), s);
    inv.set_curve_angle(theta);
    double v[4];
    p.laws.at_angle(theta, v);
    ts::Backlash model(ts::BacklashParams{v[0], v[1], v[2], v[3]});
    double worst = 0.0;
    for (int k = 0; k < 2000; ++k) {
      const double yd = 0.5 * std::sin(2 * kPi * 0.5 * k * 1e-3);
      const double y = model.step(inv.step(yd, k ? 1e-3 : 0.0));
      const bool near_reversal = std::fabs(std::cos(2 * kPi * 0.5 * k * 1e-3)) < 0.02;
      if (k > 2 && !near_reversal) worst = std::fmax(worst, std::fabs(y - yd));
    }
    EXPECT_LT(worst, 1e-12) << theta;  // measured 1.1e-16
    EXPECT_TRUE(inv.follows_route());
  }
}

// Bad descriptions are refused with a message naming the problem.
TEST(ModelInverse, BadDescriptionsAreNamed) {
  auto error_of = [](const ts::InverseModel& m) {
    try {
      ts::make_model_inverse(m, ts::InverseSettings{});
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  EXPECT_NE(error_of(one(ts::cases::part("Hysteron"))).find("no inverse for a model of kind"),
            std::string::npos);
  ts::InverseModel chain;
  chain.parts = {ts::cases::part("Backlash"), ts::cases::part("BoucWen")};
  EXPECT_NE(error_of(chain).find("a Chain is inverted when"), std::string::npos);
  ts::ModelPart bad = ts::cases::laws_part("GeneralizedPrandtlIshlinskii", 2);
  EXPECT_NE(error_of(one(bad)).find("BoucWen or HystereticOscillator base"), std::string::npos);
  ts::ModelPart neg = ts::cases::part("Backlash");
  neg.backlash.c_r = -1.0;
  EXPECT_NE(error_of(one(neg)).find("c_r"), std::string::npos);
}
