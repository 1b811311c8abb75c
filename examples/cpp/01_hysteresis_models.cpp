// 01: run a hysteresis model sample by sample, as inside a 1 kHz control loop.
#include <cmath>
#include <cstdio>
#include <tendonsheath/tendonsheath.hpp>

int main() {
  namespace ts = tendonsheath;
  ts::BoucWenBacklashParams p;
  p.c_r = 1.0;
  p.c_l = 0.95;
  p.B_r = 0.12;
  p.B_l = 0.10;
  p.rho = 2.0 / (p.B_r + p.B_l);
  p.n = 8.0;
  ts::BoucWenBacklash model(p);  // validates once; step() is noexcept and allocation-free

  const double dt = 1e-3, pi = 3.14159265358979323846;
  double peak_gap = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    const double x = std::sin(2.0 * pi * 0.3 * k * dt);  // motor position, rad
    const double y = model.step(x, dt);                    // distal output, rad
    peak_gap = std::fmax(peak_gap, std::fabs(x - y));
    if (k % 1000 == 0) std::printf("t = %5.2f s   x = %+.4f   y = %+.4f\n", k * dt, x, y);
  }
  std::printf("largest |x - y| over 10 s: %.4f rad (dead band %.2f rad)\n", peak_gap,
              p.B_r + p.B_l);
  return peak_gap > 0.0 && peak_gap < 1.0 ? 0 : 1;
}
