// 04: a compensator in a fixed-rate (1 kHz) control loop against the physics plant,
// while the endoscope bends from Theta = pi/2 to 2 pi. The curve-angle feedforward is
// told the current curve angle each cycle (as from shape sensing or a bending knob).
// Exits 0 when the compensated RMSE is below a third of the uncompensated one.
// The compensator is built with tendonsheath::make, which returns a bad parameter as an error
// value: the way to build one when the core is compiled without exceptions (-fno-exceptions).
#include <cmath>
#include <cstdio>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

int main() {
  const double pi = 3.14159265358979323846, dt = 1e-3, length = 1.2;
  ts::PullPullParams pp;
  pp.friction = 0.1;
  pp.stiffness = 5e3;
  pp.pretension = 20.0;
  pp.proximal_radius = pp.distal_radius = 10e-3;
  pp.elements = 40;
  ts::MotorParams mp;
  mp.bandwidth_hz = 60.0;
  mp.damping = 0.8;

  // The compensator's physics (in practice: from an identified CurveAngleModel).
  ts::CurveAngleFeedforwardParams fp;
  fp.friction = 0.1;
  fp.stiffness = 5e3;
  fp.length = length;
  fp.pretension = 20.0;
  fp.proximal_radius = fp.distal_radius = 10e-3;
  fp.smoothing = 0.02;
  fp.limits.max_rate = 20.0;  // rad/s: the motor's speed limit

  double sse[2] = {0.0, 0.0};
  for (int compensate = 0; compensate < 2; ++compensate) {
    const auto start = ts::Route::uniform(length, pi / 2);
    ts::PullPullPlant plant(pp, start, start);          // validated once, here
    ts::Motor motor(mp);
    auto built = ts::make<ts::CurveAngleFeedforward>(fp);
    if (!built.ok()) {
      std::fprintf(stderr, "%s\n", built.error().c_str());  // "CurveAngleFeedforward: ..."
      return 2;
    }
    ts::CurveAngleFeedforward& ff = built.value();
    for (int k = 0; k < 10000; ++k) {                   // 10 s
      const double t = k * dt;
      const double theta = pi / 2 + 1.5 * pi * std::fmin(1.0, std::fmax(0.0, (t - 3.0) / 2.0));
      // The plant's route is re-measured at 100 Hz. (Building a Route allocates; a robot's
      // loop would write its shape sensor's node angles into a preallocated buffer and call
      // plant.set_node_angles, which does not.)
      if (k % 10 == 0) plant.set_route(ts::Route::uniform(length, theta));
      const double y_d = 0.8 * std::sin(2 * pi * 0.2 * t);
      ff.set_curve_angle(theta);
      const double command = compensate ? ff.step(y_d, dt) : y_d;
      const double q_in = motor.step(command, dt, plant.drive_reaction());
      const double y = plant.step(q_in, dt);
      if (t >= 5.0) sse[compensate] += (y - y_d) * (y - y_d);
    }
  }
  const double rmse_none = std::sqrt(sse[0] / 5000), rmse_ff = std::sqrt(sse[1] / 5000);
  std::printf("RMSE without compensation: %.4f rad\n", rmse_none);
  std::printf("RMSE with CurveAngleFeedforward: %.4f rad\n", rmse_ff);
  return rmse_ff < rmse_none / 3.0 ? 0 : 1;
}
