// The status each real-time class reports for its last step (status.hpp).
#include <gtest/gtest.h>

#include <cmath>
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
