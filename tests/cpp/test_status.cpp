// The status each real-time class reports for its last step (status.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

TEST(Status, FlagsCombineAndTest) {
  const ts::Status s = ts::Status::slack | ts::Status::input_clamped;
  EXPECT_TRUE(ts::has(s, ts::Status::slack));
  EXPECT_TRUE(ts::has(s, ts::Status::input_clamped));
  EXPECT_FALSE(ts::has(s, ts::Status::not_converged));
  EXPECT_FALSE(ts::has(s, ts::Status::slack | ts::Status::fallback));
}

TEST(Status, PlantReportsHeldClampedAndOk) {
  ts::PullPullParams p;
  p.elements = 20;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 1.0));
  plant.step(0.1);
  EXPECT_EQ(plant.status(), ts::Status::ok);
  const double y = plant.step(NAN);
  EXPECT_TRUE(ts::has(plant.status(), ts::Status::held_nonfinite_input));
  EXPECT_EQ(y, plant.output());
  EXPECT_TRUE(std::isfinite(plant.step(1e300)));
  EXPECT_TRUE(ts::has(plant.status(), ts::Status::input_clamped));
  plant.step(0.0);
  EXPECT_FALSE(ts::has(plant.status(), ts::Status::input_clamped));
}

TEST(Status, MotorReportsAHugeStep) {
  ts::MotorParams mp;
  mp.bandwidth_hz = 10.0;
  ts::Motor motor(mp);
  motor.step(0.0, 0.0);
  EXPECT_EQ(motor.status(), ts::Status::ok);
  EXPECT_NEAR(motor.step(1.0, 1e300), 1.0, 1e-9);
  EXPECT_TRUE(ts::has(motor.status(), ts::Status::input_clamped));
  motor.step(NAN, 1e-3);
  EXPECT_TRUE(ts::has(motor.status(), ts::Status::held_nonfinite_input));
}

namespace {
constexpr double kPi = 3.14159265358979323846;

// Steps a model through a finite history, then NaN: held and the last output kept; then a
// finite input clears the flag.
template <class Model>
void expect_held_on_nan(Model model, const char* name) {
  ts::Status s = ts::Status::ok;
  double y = 0.0;
  for (int k = 0; k < 50; ++k) y = ts::step_with_status(model, s, 0.3 * std::sin(0.2 * k), 1e-3);
  EXPECT_FALSE(ts::has(s, ts::Status::held_nonfinite_input)) << name;
  EXPECT_EQ(ts::step_with_status(model, s, NAN, 1e-3), y) << name;
  EXPECT_TRUE(ts::has(s, ts::Status::held_nonfinite_input)) << name;
  ts::step_with_status(model, s, 0.1, 1e-3);
  EXPECT_FALSE(ts::has(s, ts::Status::held_nonfinite_input)) << name;
}

ts::PrandtlIshlinskiiParams pi_params() { return {{0.0, 0.1, 0.2}, {0.5, 0.3, 0.2}}; }
}  // namespace

TEST(Status, EveryModelAndInverseReportsAHeldInput) {
  expect_held_on_nan(ts::Backlash(ts::BacklashParams{}), "Backlash");
  expect_held_on_nan(ts::BoucWen(ts::BoucWenParams{}), "BoucWen");
  expect_held_on_nan(ts::BoucWenBacklash(ts::BoucWenBacklashParams{}), "BoucWenBacklash");
  expect_held_on_nan(ts::PrandtlIshlinskii(pi_params()), "PrandtlIshlinskii");
  expect_held_on_nan(ts::PrandtlIshlinskiiInverse(pi_params()), "PrandtlIshlinskiiInverse");
  const ts::GeneralizedPrandtlIshlinskiiParams gpi{};
  expect_held_on_nan(ts::GeneralizedPrandtlIshlinskii(gpi), "GeneralizedPrandtlIshlinskii");
  expect_held_on_nan(ts::GeneralizedPrandtlIshlinskiiInverse(gpi), "GPI inverse");
  expect_held_on_nan(ts::CurveAngleModel(ts::CurveAngleParams{}), "CurveAngleModel");
  expect_held_on_nan(ts::HystereticOscillator(ts::HystereticOscillatorParams{}), "Oscillator");
  ts::PolynomialParams poly;
  poly.coefficients = {0.0, 1.0, 0.5};
  expect_held_on_nan(ts::Polynomial(poly), "Polynomial");
  expect_held_on_nan(ts::Chain<ts::Backlash, ts::Polynomial>(ts::Backlash(ts::BacklashParams{}),
                                                            ts::Polynomial(poly)),
                     "Chain");
}

TEST(Status, EveryFeedforwardReportsHeldAndSaturated) {
  ts::CommandLimits lim;
  lim.min = -0.2;
  lim.max = 0.2;
  ts::BacklashInverseParams bp;
  bp.limits = lim;
  ts::CurveAngleFeedforwardParams cp;
  cp.limits = lim;
  ts::ContinuumFeedforwardParams kp;
  kp.limits = lim;
  ts::BacklashInverseFeedforward backlash(bp);
  ts::PrandtlIshlinskiiFeedforward pi(pi_params(), lim);
  ts::CurveAngleFeedforward curve(cp);
  ts::ContinuumFeedforward continuum(kp);
  auto check = [&](auto& ff, const char* name) {
    ts::Status s = ts::Status::ok;
    ts::step_with_status(ff, s, 0.0, 1e-3);
    EXPECT_FALSE(ts::has(s, ts::Status::saturated)) << name;
    const double u = ts::step_with_status(ff, s, 50.0, 1e-3);  // far past the limits
    EXPECT_TRUE(ts::has(s, ts::Status::saturated)) << name;
    EXPECT_EQ(u, 0.2) << name;
    EXPECT_EQ(ts::step_with_status(ff, s, NAN, 1e-3), u) << name;
    EXPECT_TRUE(ts::has(s, ts::Status::held_nonfinite_input)) << name;
  };
  check(backlash, "BacklashInverseFeedforward");
  check(pi, "PrandtlIshlinskiiFeedforward");
  check(curve, "CurveAngleFeedforward");
  check(continuum, "ContinuumFeedforward");
}

TEST(Status, TheRateLimitIsASaturation) {
  ts::CommandLimits lim;
  lim.max_rate = 1.0;  // per s
  ts::CommandShaper shaper(lim);
  shaper.apply(0.0, 1e-3);
  EXPECT_EQ(shaper.status(), ts::Status::ok);
  EXPECT_NEAR(shaper.apply(0.0005, 1e-3), 0.0005, 1e-15);  // within the rate
  EXPECT_EQ(shaper.status(), ts::Status::ok);
  EXPECT_NEAR(shaper.apply(1.0, 1e-3), 0.0015, 1e-15);
  EXPECT_EQ(shaper.status(), ts::Status::saturated);
}

TEST(Status, SensorReportsAHeldReading) {
  ts::Sensor sensor(ts::SensorParams{1e-4, 0.0, 1});
  const double y = sensor.measure(0.5);
  EXPECT_EQ(sensor.status(), ts::Status::ok);
  EXPECT_EQ(sensor.measure(NAN), y);
  EXPECT_EQ(sensor.status(), ts::Status::held_nonfinite_input);
}

TEST(Status, MotorReportsTheTorqueAndSpeedLimits) {
  ts::MotorParams mp;
  mp.kind = ts::MotorKind::Torque;
  mp.max_torque = 0.1;
  mp.inertia = 1e-4;
  ts::Motor motor(mp);
  motor.step(0.05, 1e-3);
  EXPECT_EQ(motor.status(), ts::Status::ok);
  motor.step(5.0, 1e-3);
  EXPECT_TRUE(ts::has(motor.status(), ts::Status::saturated));
  ts::MotorParams pos;
  pos.bandwidth_hz = 50.0;
  pos.max_speed = 1.0;
  ts::Motor position(pos);
  position.step(0.0, 1e-3);
  position.step(1e-6, 1e-3);
  EXPECT_EQ(position.status(), ts::Status::ok);
  position.step(10.0, 1e-3);  // asks for far more than 1 rad/s
  EXPECT_TRUE(ts::has(position.status(), ts::Status::saturated));
}

TEST(Status, PlantsStepWithStatusAndFlagTheHeldInputFromTheChainsResult) {
  ts::SingleTendonParams sp;
  sp.elements = 20;
  ts::SingleTendonPlant single(sp, ts::Route::uniform(1.0, 2.0));
  ts::ContinuumParams cp;
  cp.elements = 20;
  ts::ContinuumPlant continuum(cp, ts::Route::uniform(1.0, kPi));
  ts::Status s = ts::Status::ok;
  const double y = ts::step_with_status(single, s, 1e-3, 1e-3);
  EXPECT_EQ(s, ts::Status::ok);
  EXPECT_EQ(ts::step_with_status(single, s, NAN, 1e-3), y);
  EXPECT_EQ(s, ts::Status::held_nonfinite_input);
  ts::step_with_status(continuum, s, 0.2, 1e-3);
  EXPECT_EQ(s, ts::Status::ok);
  ts::step_with_status(continuum, s, INFINITY, 1e-3);
  EXPECT_EQ(s, ts::Status::held_nonfinite_input);
}

// Issue 16 item 10: ContinuumPlant declares Params = ContinuumParams, and params() returns them.
TEST(Status, ContinuumPlantParamsAreContinuumParams) {
  static_assert(std::is_same_v<decltype(std::declval<const ts::ContinuumPlant&>().params()),
                               const ts::ContinuumPlant::Params&>);
  ts::ContinuumParams cp;
  cp.elements = 12;
  cp.bending_stiffness = 7e-4;
  ts::ContinuumPlant plant(cp, ts::Route::uniform(1.0, 1.0));
  EXPECT_EQ(plant.params().bending_stiffness, 7e-4);
  EXPECT_EQ(plant.pull_pull_params().load_stiffness, 7e-4 / cp.backbone_length);
}

// Issue 16 item 10: each feedforward reports its errors under its own name.
TEST(Status, FeedforwardsNameThemselvesInErrors) {
  ts::CommandLimits bad;
  bad.min = 1.0;
  bad.max = 0.0;
  try {
    ts::PrandtlIshlinskiiFeedforward ff(pi_params(), bad);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("PrandtlIshlinskiiFeedforward: ", 0), 0u) << e.what();
  }
  ts::BacklashInverseParams bp;
  bp.limits = bad;
  try {
    ts::BacklashInverseFeedforward ff(bp);
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("BacklashInverseFeedforward: ", 0), 0u) << e.what();
  }
}

// A curve angle that is not finite or negative changes nothing and is reported (it was
// ignored with Status::ok before), until an angle is taken again.
TEST(Status, CurveAngleFeedforwardRejectsABadCurveAngle) {
  ts::CurveAngleFeedforwardParams cp;
  cp.curve_angle = 1.0;
  ts::CurveAngleFeedforward ff(cp);
  const double before = ff.step(0.3, 0.0);
  for (double bad : {-1.0, static_cast<double>(NAN)}) {
    EXPECT_FALSE(ff.set_curve_angle(bad));
    EXPECT_TRUE(ff.angle_rejected());
    EXPECT_TRUE(ts::has(ff.status(), ts::Status::input_clamped));
    EXPECT_EQ(ff.shape().curve_angle, 1.0);
    ff.reset();
    EXPECT_EQ(ff.step(0.3, 0.0), before);
  }
  EXPECT_FALSE(ff.set_shape({NAN, 1.0, 1.0}));
  EXPECT_TRUE(ff.set_curve_angle(2.0));
  EXPECT_FALSE(ff.angle_rejected());
  EXPECT_EQ(ff.status(), ts::Status::ok);
}
