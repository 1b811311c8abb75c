// The parameter tables (param_table.hpp): constexpr rows next to each params struct, and
// validate_fields(), which checks their single-field bounds in table order with validate.hpp's
// messages and allocates nothing while every value is in range.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <tendonsheath/tendonsheath.hpp>

#include "counting_new.hpp"  // counts allocations while armed

namespace ts = tendonsheath;

namespace {
template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

// The table is a compile-time constant: its rows and their member pointers.
constexpr auto& kBacklash = ts::ParamTable<ts::BacklashParams>::fields;
static_assert(ts::field_count<ts::BacklashParams>() == 4);
static_assert(std::get<0>(kBacklash).member == &ts::BacklashParams::c_r);
static_assert(std::get<0>(kBacklash).range.check == ts::Check::positive);
static_assert(std::get<3>(kBacklash).range.lo_closed);
static_assert(ts::field_count<ts::AdaptiveControllerParams>() == 25);
}  // namespace

TEST(ParamTable, RowsNameTheirFieldsInStructOrder) {
  const char* names[] = {"c_r", "c_l", "B_r", "B_l"};
  int i = 0;
  ts::BacklashParams p;
  p.c_r = 1.5;
  ts::for_each_field<ts::BacklashParams>([&](const auto& row) {
    EXPECT_STREQ(row.name, names[i++]);
    EXPECT_NE(row.doc[0], '\0');
  });
  EXPECT_EQ(i, 4);
  EXPECT_EQ(p.*std::get<0>(kBacklash).member, 1.5);
}

TEST(ParamTable, TheFirstBadFieldInTableOrderIsReportedWithValidatesMessage) {
  ts::BoucWenBacklashParams p;
  p.sigma = 0.25;  // row 6
  p.B_l = -1.0;    // row 4: reported first
  EXPECT_EQ(message_of([&] { ts::validate_fields(p, "BoucWenBacklash"); }),
            "BoucWenBacklash: B_l must be >= 0 (got -1)");
  p.B_l = 0.1;
  EXPECT_EQ(message_of([&] { ts::validate_fields(p, "BoucWenBacklash"); }),
            "BoucWenBacklash: sigma must be >= 0.5 (got 0.25)");
  EXPECT_EQ(message_of([&] { ts::BoucWenBacklash m(p); }),
            "BoucWenBacklash: sigma must be >= 0.5 (got 0.25)");
}

TEST(ParamTable, ANamedRangeChecksOnlyItsRows) {
  ts::BoucWenParams p;
  p.A = 0.0;      // outside "n" .. "max_step"
  p.alpha = 2.0;  // inside
  EXPECT_EQ(message_of([&] { ts::validate_fields(p, "BoucWen", "n", "max_step"); }),
            "BoucWen: alpha must be in [0, 1] (got 2)");
  p.alpha = 0.5;
  EXPECT_EQ(message_of([&] { ts::validate_fields(p, "BoucWen", "n", "max_step"); }),
            "(nothing thrown)");
  EXPECT_EQ(message_of([&] { ts::BoucWen m(p); }), "BoucWen: A must be > 0 (got 0)");
}

TEST(ParamTable, DocumentedAndNonScalarRowsAreLeftToTheConstructor) {
  ts::HystereticOscillatorParams p;
  p.substeps = 0;  // documented: the constructor's own message
  EXPECT_EQ(message_of([&] { ts::validate_fields(p, "HystereticOscillator"); }),
            "(nothing thrown)");
  EXPECT_EQ(message_of([&] { ts::HystereticOscillator m(p); }),
            "HystereticOscillator: substeps must be >= 1");
  ts::PolynomialParams poly;  // a vector and a bool: no bound of their own
  EXPECT_EQ(message_of([&] { ts::validate_fields(poly, "Polynomial"); }), "(nothing thrown)");
}

TEST(ParamTable, APassingCheckAllocatesNothing) {
  const ts::ContinuumFeedforwardParams p;
  allocations = 0;
  armed = true;
  ts::validate_fields(p, "ContinuumFeedforward");
  ts::validate_fields(p, "ContinuumFeedforward", "bending_stiffness", "play");
  armed = false;
  EXPECT_EQ(allocations.load(), 0);
}
