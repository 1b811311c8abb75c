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

// Each row says parameter or option; assign() reads the parameter rows, in table order.
constexpr auto& kBoucWen = ts::ParamTable<ts::BoucWenParams>::fields;
static_assert(std::get<5>(kBoucWen).role == ts::Role::parameter);  // k
static_assert(std::get<6>(kBoucWen).role == ts::Role::option);     // max_step
static_assert(ts::parameter_count<ts::BoucWenParams>() == 6);
static_assert(ts::parameter_count<ts::HystereticOscillatorParams>() == 8);
// The inverse's table starts with the model's rows (rows_of), not a copy.
constexpr auto& kInverse = ts::ParamTable<ts::BacklashInverseParams>::fields;
static_assert(ts::field_count<ts::BacklashInverseParams>() == 6);
static_assert(std::get<2>(kInverse).member ==
              static_cast<double ts::BacklashInverseParams::*>(&ts::BacklashParams::B_r));
static_assert(std::get<2>(kInverse).range.check == std::get<2>(kBacklash).range.check);
}  // namespace

TEST(ParamTable, AssignReadsTheParameterRowsInTableOrderAndKeepsTheOptions) {
  const double v[] = {1.5, 0.4, 0.3, 2.0, 0.25, -1.0};
  ts::BoucWenParams p;
  p.max_step = 0.01;
  p.assign(v);
  EXPECT_EQ(p.A, 1.5);
  EXPECT_EQ(p.beta, 0.4);
  EXPECT_EQ(p.gamma, 0.3);
  EXPECT_EQ(p.n, 2.0);
  EXPECT_EQ(p.alpha, 0.25);
  EXPECT_EQ(p.k, -1.0);
  EXPECT_EQ(p.max_step, 0.01);
  EXPECT_EQ(p.max_substeps, 256);
}

TEST(ParamTable, TheInversesModelRowsCheckItsFields) {
  ts::BacklashInverseParams p;
  p.B_l = -1.0;
  EXPECT_EQ(message_of([&] { ts::BacklashInverseFeedforward f(p); }),
            "BacklashInverseFeedforward: B_l must be >= 0 (got -1)");
}

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
