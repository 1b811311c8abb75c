// 10: no tip sensor, a servo that yields. A backlash inverse feedforward drives a position servo
// without integral action (a PD servo with a reflected inertia: the tendons' pull deflects it)
// at 1 kHz, alone and inside an EncoderLoop, a PI loop on the motor's own encoder. The loop's
// gains would come from Python's EncoderLoop.from_calibration (the servo identified from a motor
// calibration run); the feedforward's dead band from an identified model (here the plant's own,
// to keep the example short: the bench's scenarios never do that).
// Exits 0 when the loop makes the motor follow the feedforward at least 3x more closely (the
// servo's own lag remains).
#include <cmath>
#include <cstdio>
#include <tendonsheath/tendonsheath.hpp>

namespace ts = tendonsheath;

int main() {
  const double pi = 3.14159265358979323846, dt = 1e-3;
  ts::PullPullParams pp;
  pp.friction = 0.1;
  pp.stiffness = 5e3;
  pp.pretension = 20.0;
  pp.proximal_radius = pp.distal_radius = 15e-3;
  pp.elements = 30;
  ts::MotorParams mp;  // a PD servo that yields: static stiffness J_r w^2 = 0.39 N m/rad
  mp.bandwidth_hz = 10.0;
  mp.damping = 0.8;
  mp.inertia = 1e-4;

  ts::BacklashInverseParams fp;  // its dead band at the motor, rad
  fp.B_r = fp.B_l = 0.05;
  fp.smoothing = 0.03;
  ts::EncoderLoopParams lp;  // PI gains: tune_encoder_loop's for a 10 Hz, damping 0.8 servo
  lp.kp = 1.7;
  lp.ki = 72.0;
  lp.max_correction = 0.5;

  double miss[2] = {0.0, 0.0};  // rms of (motor encoder - the feedforward's command)
  for (int looped = 0; looped < 2; ++looped) {
    const auto route = ts::Route::uniform(1.5, pi);
    ts::PullPullPlant plant(pp, route, route);
    ts::Motor motor(mp);
    ts::BacklashInverseFeedforward ff(fp);  // the command of the feedforward alone
    ts::EncoderLooped<ts::BacklashInverseFeedforward> loop{ts::BacklashInverseFeedforward(fp),
                                                           ts::EncoderLoop(lp)};
    double q = 0.0;  // the motor encoder of the last cycle
    for (int k = 0; k < 8000; ++k) {  // 8 s
      const double t = k * dt, y_d = 0.6 * std::sin(2 * pi * 0.4 * t), step = k ? dt : 0.0;
      const double target = ff.step(y_d, step);
      const double command = looped ? loop.step(y_d, q, step) : target;
      plant.step(motor.step(command, step, plant.drive_reaction()), step);
      q = motor.position();
      if (t >= 3.0) miss[looped] += (q - target) * (q - target);
    }
  }
  miss[0] = std::sqrt(miss[0] / 5000), miss[1] = std::sqrt(miss[1] / 5000);
  std::printf("motor encoder vs the feedforward's command, rms: alone %.4f rad, "
              "in the loop %.4f rad\n", miss[0], miss[1]);
  return miss[1] < miss[0] / 3.0 ? 0 : 1;
}
