// Solves per PullPullPlant step under random routes every 250 steps, a sine with reversals
// every 37 steps and a shock every 997 steps (the set of tests/cpp/test_plant_effects.cpp's
// damped-load test): the solve-count distribution (independent of the machine's load) and the
// per-step thread CPU time. Builds against any commit's headers, for before/after figures:
//   g++ -O2 -std=c++17 -Iinclude benchmarks/cpp/plant_solves.cpp -o /tmp/plant_solves
//   /tmp/plant_solves N DAMPED [STEPS] [SEED]     (DAMPED: 0 spring load, 1 spring-damper)
#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
double cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec * 1e9 + t.tv_nsec;
}

template <class T>
T quantile(std::vector<T> v, double f) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(f * v.size()))];
}
}  // namespace

int main(int argc, char** argv) {
  const int N = argc > 1 ? std::atoi(argv[1]) : 100;
  const bool damped = argc > 2 && std::atoi(argv[2]) != 0;
  const int steps = argc > 3 ? std::atoi(argv[3]) : 20000;
  ts::PullPullParams p;
  p.elements = N;
  p.load_stiffness = 0.05;
  if (damped) p.load_damping = 0.01;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.2, 3.14));
  std::mt19937 gen(argc > 4 ? std::atoi(argv[4]) : 1);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  std::vector<double> a(plant.n_node_angles());
  std::vector<int> solves;
  std::vector<double> us;
  for (int k = 0; k < steps; ++k) {
    if (k % 250 == 0) {
      const double total = 0.3 + 6.0 * U(gen);
      for (double& x : a) x = total * (0.2 + 1.6 * U(gen)) / (N - 1);
      plant.set_node_angles(a.data());
    }
    const double shock = (k % 997 == 0) ? 0.3 * (U(gen) - 0.5) : 0.0;
    const double rev = (k % 37 == 0) ? 0.02 * (U(gen) - 0.5) : 0.0;
    const double q = 0.5 * std::sin(2 * 3.14159 * k * 1e-3) +
                     0.05 * std::sin(2 * 3.14159 * 7 * k * 1e-3) + shock + rev;
    const double t0 = cpu_ns();
    plant.step(q, 1e-3);
    us.push_back((cpu_ns() - t0) * 1e-3);
    solves.push_back(plant.chain().last_solves());
  }
  std::printf("N=%d damped=%d solves: median %d p99 %d p99.9 %d max %d | CPU us: median %.2f "
              "p99 %.1f p99.9 %.1f max %.1f | nonconverged %ld\n",
              N, damped ? 1 : 0, quantile(solves, 0.5), quantile(solves, 0.99),
              quantile(solves, 0.999), quantile(solves, 1.0), quantile(us, 0.5),
              quantile(us, 0.99), quantile(us, 0.999), quantile(us, 1.0), plant.nonconverged());
}
