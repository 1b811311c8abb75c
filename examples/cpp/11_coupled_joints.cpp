// 11: coupled joints in a 1 kHz control loop: a wrist whose joint-1 cables run over an idler on
// joint 0's axis (joint 1 turns 0.25 rad per rad of joint 0, whatever its motor does). Two
// physics pull-pull drives with the realistic effects; CoupledFeedforward inverts each joint's
// own BoucWenBacklash of (desired - coupling of the other joints' desired angles). The models
// and the coupling are those identify_coupled found from a calibration log of this wrist
// (benchmarks/coupled.py, calibration seed 0; in practice: load them from your own fit).
// Exits 0 when the coupled compensator's joint-1 RMSE is below a fifth of that of the same
// inverses with the coupling ignored.
#include <cmath>
#include <cstdio>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
ts::ModelInverse joint_inverse(double c_r, double c_l, double B_r, double B_l, double rho,
                               double sigma, double n) {
  ts::ModelPart p;
  p.kind = "BoucWenBacklash";
  p.bouc_wen_backlash = ts::BoucWenBacklashParams{c_r, c_l, B_r, B_l, rho, sigma, n};
  ts::InverseModel m;
  m.parts = {p};
  ts::InverseSettings s;
  s.smoothing = 0.03;
  return ts::make_model_inverse(m, s);  // validated here, once
}

ts::PullPullParams drive() {
  ts::PullPullParams p;
  p.friction = 0.1;
  p.stiffness = 5e3;
  p.pretension = 20.0;
  p.proximal_radius = p.distal_radius = 15e-3;
  p.elements = 40;
  p.distal_inertia = 2e-5;  // the realistic effects (tendonsheath.plant.presets.realistic_plant)
  p.distal_damping = 2e-3;
  p.sheath_viscosity = 8.0;
  p.relaxation_fraction = 0.08;
  p.relaxation_time = 1.5;
  p.friction2 = 0.115;
  p.stiffness2 = 4.5e3;
  return p;
}
}  // namespace

int main() {
  const double pi = 3.14159265358979323846, dt = 1e-3, idler = 0.25;
  const std::vector<ts::ModelInverse> joints{
      joint_inverse(0.998973, 0.999036, 0.0372273, 0.0368877, 26.9488, 0.738015, 12.0),
      joint_inverse(0.99995, 0.999908, 0.0530945, 0.0525132, 18.8375, 1.00573, 12.0)};
  const std::vector<double> identified{0.0, 0.00002, 0.25004, 0.0};  // C, row-major
  double sse[2] = {0.0, 0.0};
  for (int coupled = 0; coupled < 2; ++coupled) {
    const auto r0 = ts::Route::arcs({{0.5, 0.0}, {0.5, pi / 2}});
    const auto r1 = ts::Route::arcs({{0.4, 0.0}, {0.6, 3 * pi / 4}});
    ts::PullPullPlant plant0(drive(), r0, r0), plant1(drive(), r1, r1);
    ts::CoupledFeedforward ff(joints, coupled ? identified : std::vector<double>(4, 0.0));
    for (int k = 0; k < 10000; ++k) {  // 10 s
      const double t = k * dt;
      const double y_d[2] = {0.7 * std::sin(2 * pi * 0.4 * t) + 0.1 * std::sin(2 * pi * 1.1 * t),
                             0.6 * std::sin(0.5) - 0.6 * std::sin(2 * pi * 0.3 * t + 0.5)};
      double u[2];
      ff.step(y_d, u, k ? dt : 0.0);  // noexcept, no allocation
      const double y0 = plant0.step(u[0], k ? dt : 0.0);
      const double y1 = plant1.step(u[1], k ? dt : 0.0) + idler * y0;  // the idler's wrap
      if (t >= 1.0) sse[coupled] += (y1 - y_d[1]) * (y1 - y_d[1]);
    }
  }
  const double ignored = std::sqrt(sse[0] / 9000), coupled = std::sqrt(sse[1] / 9000);
  std::printf("joint 1 RMSE, coupling ignored: %.4f rad\n", ignored);
  std::printf("joint 1 RMSE, CoupledFeedforward: %.4f rad\n", coupled);
  return coupled < ignored / 5.0 ? 0 : 1;
}
