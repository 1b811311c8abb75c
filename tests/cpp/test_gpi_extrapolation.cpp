// The generalized PI envelopes beyond their input range [lo, hi]: the tangent line, continuous,
// with a continuous slope, increasing; the operator and its inverse there.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

namespace {

ts::Envelope random_envelope(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ts::Envelope e{0.3 + 2.0 * u(rng), 0.2 + 4.0 * u(rng), u(rng) - 0.5, u(rng) - 0.5};
  e.lo = lo;
  e.hi = hi;
  return e;
}

}  // namespace

TEST(GpiEnvelope, TangentBeyondTheRangeIsContinuousSmoothAndIncreasing) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double lo = -1.5 * u(rng), hi = lo + 0.2 + 1.5 * u(rng);
    const ts::Envelope e = random_envelope(rng, lo, hi);
    ts::Envelope plain = e;  // the tanh everywhere
    plain.lo = -std::numeric_limits<double>::infinity();
    plain.hi = std::numeric_limits<double>::infinity();
    const double h = 1e-8 * (hi - lo);
    for (double end : {lo, hi}) {
      // continuous, and the slope on both sides is the tanh's slope at the end
      EXPECT_NEAR(e(end + h), e(end - h), 3.0 * h * e.slope_at(end) + 1e-13) << trial;
      const double left = (e(end) - e(end - h)) / h, right = (e(end + h) - e(end)) / h;
      EXPECT_NEAR(left, right, 1e-5 * (1.0 + e.slope_at(end))) << trial;
    }
    double prev = e(lo - 5.0 * (hi - lo));
    for (int k = 1; k <= 1100; ++k) {  // lo - 5 span .. hi + 5 span
      const double x = lo - 5.0 * (hi - lo) + k * 11.0 * (hi - lo) / 1100.0;
      const double g = e(x);
      ASSERT_TRUE(std::isfinite(g));
      ASSERT_GE(g, prev) << "trial " << trial << " x " << x;  // never decreasing
      if (x >= lo && x <= hi) {
        ASSERT_EQ(g, plain(x));  // the tanh inside the range
      } else if (x > hi) {
        ASSERT_NEAR(g, e.tanh_at(hi) + e.slope_at(hi) * (x - hi), 1e-12 * (1 + std::fabs(g)));
      } else {
        ASSERT_NEAR(g, e.tanh_at(lo) + e.slope_at(lo) * (x - lo), 1e-12 * (1 + std::fabs(g)));
      }
      // the inverse finds x again, beyond the range too, wherever the slope is not negligible
      const double s = x > hi ? e.slope_at(hi) : (x < lo ? e.slope_at(lo) : e.slope_at(x));
      if (s > 1e-6 * e.a * e.b) {
        ASSERT_NEAR(e.inverse(g), x, 1e-6 * (1.0 + std::fabs(x))) << trial;
      }
      prev = g;
    }
    // past the range the envelope keeps growing: it passes the tanh's ceiling d + a, which the
    // tanh alone never reaches
    const double s = e.slope_at(hi);
    if (s > 0.0) {
      const double far = hi + (e.d + e.a - e.tanh_at(hi)) / s + 1.0;
      EXPECT_GT(e(far), plain(far)) << trial;
      EXPECT_GT(e(far), e.d + e.a) << trial;
    }
  }
}

TEST(GpiEnvelope, RangeIsValidated) {
  ts::GeneralizedPrandtlIshlinskiiParams p;
  p.rising.lo = 1.0;
  p.rising.hi = 1.0;
  EXPECT_THROW(ts::GeneralizedPrandtlIshlinskii{p}, std::invalid_argument);
  p.rising.hi = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(ts::GeneralizedPrandtlIshlinskii{p}, std::invalid_argument);
  p.rising.hi = 2.0;
  EXPECT_NO_THROW(ts::GeneralizedPrandtlIshlinskii{p});
}

TEST(GpiEnvelope, OperatorKeepsItsSlopePastTheRangeAndInvertsThere) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> step(0.0, 0.05);
  for (int trial = 0; trial < 30; ++trial) {
    ts::GeneralizedPrandtlIshlinskiiParams p;
    p.rising = random_envelope(rng, -0.6, 0.6);
    p.falling = random_envelope(rng, -0.6, 0.6);
    p.thresholds = {0.0, 0.05 + 0.1 * u(rng), 0.2 + 0.1 * u(rng)};
    p.weights = {0.3 + u(rng), 0.4 * u(rng), 0.4 * u(rng)};
    ts::GeneralizedPrandtlIshlinskiiParams plain_p = p;
    for (ts::Envelope* e : {&plain_p.rising, &plain_p.falling}) {
      e->lo = -std::numeric_limits<double>::infinity();
      e->hi = std::numeric_limits<double>::infinity();
    }
    ts::GeneralizedPrandtlIshlinskii fwd(p), plain(plain_p);
    // inside the range: the same operator
    double x = 0.0;
    for (int k = 0; k < 500; ++k) {
      x = std::fmin(0.6, std::fmax(-0.6, x + step(rng)));
      ASSERT_EQ(fwd.step(x), plain.step(x)) << trial;
    }
    // a ramp from inside to far beyond: the output keeps rising, never decreasing, and
    // grows at least as fast as the centre line's tangent slope times weights[0]
    const double y_hi = fwd.step(0.6);
    double prev = y_hi;
    for (int k = 1; k <= 200; ++k) {
      const double y = fwd.step(0.6 + 0.01 * k);
      ASSERT_GE(y, prev) << trial;
      prev = y;
    }
    const double tangent = 0.5 * (p.rising.slope_at(0.6) + p.falling.slope_at(0.6));
    EXPECT_GE(prev - y_hi, 0.999 * p.weights[0] * tangent * 2.0) << trial;
    // the inverse is exact on a path that leaves the range on both sides
    ts::GeneralizedPrandtlIshlinskii f2(p);
    ts::GeneralizedPrandtlIshlinskiiInverse inv(p);
    for (int k = 0; k < 1500; ++k) {
      const double xk = 1.5 * std::sin(0.01 * k);  // +-1.5: 2.5 times the range's half-width
      ASSERT_NEAR(inv.step(f2.step(xk)), xk, 1e-8) << "trial " << trial << " step " << k;
    }
  }
}
