// Validation messages: built only when a check fails (validate.hpp), and then they name the
// parameter, the bound and the value, with numbers written by std::to_chars.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

namespace {
std::string message_of(void (*f)()) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(nothing thrown)";
}
}  // namespace

TEST(Validate, APassingCheckThrowsNothing) {
  EXPECT_NO_THROW(ts::require(true, "Where", "never formatted ", 1.5, " ", 7));
  EXPECT_NO_THROW(ts::require_in_range(0.5, 0.0, 1.0, "Where", "x"));
}

TEST(Validate, AFailingCheckFormatsTextIntegersAndDoubles) {
  EXPECT_EQ(message_of([] { ts::require(false, "Where", "n must be >= ", 2, " (got ", -3, ")"); }),
            "Where: n must be >= 2 (got -3)");
  EXPECT_EQ(message_of([] { ts::require_in_range(1.25, 0.0, 1.0, "BoucWen", "alpha"); }),
            "BoucWen: alpha must be in [0, 1] (got 1.25)");
  EXPECT_EQ(message_of([] { ts::require_positive(-0.1, "Backlash", "c_r"); }),
            "Backlash: c_r must be > 0 (got -0.1)");
  EXPECT_EQ(message_of([] { ts::require(false, std::string("W"), 'x', std::size_t{12}); }),
            "W: x12");
}

TEST(Validate, ASeriesNamesTheBadSample) {
  const double x[3] = {0.0, 1.0, 2.0};
  const double t[3] = {0.0, 0.5, 0.5};
  try {
    ts::check_series(t, x, 3, "simulate");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "simulate: time is not strictly increasing at t[2] = 0.5 <= t[1] = 0.5");
  }
}

TEST(Validate, ARouteOfTheWrongLengthIsNamed) {
  ts::PullPullParams p;
  p.elements = 10;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 1.0));
  try {
    plant.set_route(ts::Route::uniform(2.0, 1.0));
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()),
              "PullPullPlant.set_route (sheath 1): the new route is 2 m long but the sheath is 1 m "
              "(a route may bend, not change length)");
  }
}

// A rest tension that strains the tendon by 5 % or more breaks it (spec A.2 is small-strain).
TEST(Validate, APretensionThatWouldBreakTheTendonIsRefused) {
  EXPECT_EQ(message_of([] {
              ts::PullPullParams p;
              p.stiffness = 5.0;
              p.pretension = 20.0;
              ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 1.0));
            }),
            "PullPullPlant: pretension / EA must be < 0.05 (got 20 N / 5 N = 4): a tendon breaks "
            "near 2-4 % strain and the model (spec A.2) is small-strain");
  EXPECT_NE(message_of([] {
              ts::SingleTendonParams p;
              p.stiffness = 100.0;
              p.load_force = 10.0;
              ts::SingleTendonPlant plant(p, ts::Route::uniform(1.0, 1.0));
            }).find("load_force / EA must be < 0.05"),
            std::string::npos);
  EXPECT_NO_THROW({
    ts::PullPullParams p;
    p.stiffness = 5e3;
    p.pretension = 40.0;  // the spec's extremes: T0 / EA = 8e-3
    ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 1.0));
  });
}
