// Per-step latency of each compensator: median and 99.9th percentile over
// 1e6 control cycles, each timed on its own (clock overhead subtracted).
// Prints one JSON object on stdout.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;
using Clock = std::chrono::steady_clock;

static volatile double sink = 0.0;

struct Stats {
  double median_ns, p999_ns, mean_ns;
};

template <class F>
Stats measure(std::size_t n, F&& step) {
  std::vector<double> samples(n);
  // clock overhead: the median of back-to-back reads
  std::vector<double> overhead(10000);
  for (auto& o : overhead) {
    const auto a = Clock::now();
    const auto b = Clock::now();
    o = std::chrono::duration<double, std::nano>(b - a).count();
  }
  std::nth_element(overhead.begin(), overhead.begin() + overhead.size() / 2, overhead.end());
  const double clock_ns = overhead[overhead.size() / 2];
  for (std::size_t k = 0; k < n; ++k) {
    const auto a = Clock::now();
    sink = step(k);
    const auto b = Clock::now();
    samples[k] = std::max(0.0, std::chrono::duration<double, std::nano>(b - a).count() - clock_ns);
  }
  double mean = 0.0;
  for (double s : samples) mean += s;
  mean /= n;
  std::sort(samples.begin(), samples.end());
  return {samples[n / 2], samples[static_cast<std::size_t>(0.999 * (n - 1))], mean};
}

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000000;
  const double dt = 1e-3, pi = 3.141592653589793;
  std::vector<double> yd(n);
  for (std::size_t k = 0; k < n; ++k) yd[k] = 0.5 * std::sin(2 * pi * 0.5 * k * dt) + 0.1 * std::sin(2 * pi * 3.1 * k * dt);

  ts::BacklashInverseParams ip;
  ip.c_l = 0.95;
  ip.B_r = 0.12;
  ip.B_l = 0.1;
  ts::BacklashInverseFeedforward inverse(ip);
  ts::PrandtlIshlinskiiParams pp;
  pp.thresholds = {0.0, 0.05, 0.1, 0.15, 0.2, 0.25, 0.3, 0.35};
  pp.weights = {1.0, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1, 0.1};
  ts::PrandtlIshlinskiiFeedforward pi_inverse(pp, {});
  ts::CurveAngleFeedforward curve({});
  ts::ContinuumFeedforwardParams cp;
  ts::ContinuumFeedforward continuum_exact(cp);
  cp.mode = ts::ContinuumMode::Published;
  ts::ContinuumFeedforward continuum_published(cp);
  ts::AdaptiveController adaptive({});
  ts::EncoderLoopParams lp;
  lp.kp = 1.3, lp.ki = 440.0;
  ts::EncoderLooped<ts::BacklashInverseFeedforward> looped{ts::BacklashInverseFeedforward(ip),
                                                           ts::EncoderLoop(lp)};
  ts::TipLoopParams tp;
  tp.kp = 0.45, tp.ki = 100.0, tp.kd = 0.0028, tp.derivative_cutoff_hz = 100.0;
  tp.schedule_size = 3;
  tp.schedule_angles = {1.7, 2.8, 5.7};
  tp.schedule_gains = {1.0, 1.0, 0.99};
  ts::TipLooped<ts::BacklashInverseFeedforward> tipped{ts::BacklashInverseFeedforward(ip),
                                                       ts::TipLoop(tp)};
  std::vector<double> table(n);  // a learned correction as long as the run
  for (std::size_t k = 0; k < n; ++k) table[k] = 0.01 * std::sin(2 * pi * 0.5 * k * dt);
  ts::LearnedFeedforward<ts::BacklashInverseFeedforward> learned{
      ts::BacklashInverseFeedforward(ip), ts::LearnedCorrection(table, {})};
  // root-finding inverses (ModelInverse): a GPI and a Bouc-Wen backlash with a cubic output map
  ts::InverseModel gpi_model;
  gpi_model.parts.resize(1);
  gpi_model.parts[0].kind = "GeneralizedPrandtlIshlinskii";
  ts::ModelInverse gpi_inverse = ts::make_model_inverse(gpi_model, {});
  ts::InverseModel chain_model;
  chain_model.parts.resize(2);
  chain_model.parts[0].kind = "BoucWenBacklash";
  chain_model.parts[1].kind = "Polynomial";
  chain_model.parts[1].polynomial.coefficients = {0.0, 1.0, 0.0, 0.2};
  ts::ModelInverse chain_inverse = ts::make_model_inverse(chain_model, {});

  struct Row {
    std::string name;
    Stats stats;
  };
  std::vector<Row> rows;
  rows.push_back({"InverseFeedforward (BoucWenBacklash)", measure(n, [&](std::size_t k) { return inverse.step(yd[k], dt); })});
  rows.push_back({"InverseFeedforward (PrandtlIshlinskii, 8 plays)", measure(n, [&](std::size_t k) { return pi_inverse.step(yd[k], dt); })});
  rows.push_back({"CurveAngleFeedforward (curve angle changing every cycle)", measure(n, [&](std::size_t k) {
                    curve.set_curve_angle(3.0 + std::sin(1e-3 * k));
                    return curve.step(yd[k], dt);
                  })});
  rows.push_back({"ContinuumFeedforward (exact)", measure(n, [&](std::size_t k) { return continuum_exact.step(yd[k], dt); })});
  rows.push_back({"ContinuumFeedforward (published)", measure(n, [&](std::size_t k) { return continuum_published.step(yd[k], dt); })});
  rows.push_back({"EncoderLoop (around the BoucWenBacklash inverse)", measure(n, [&](std::size_t k) {
                    return looped.step(yd[k], 0.97 * yd[k > 0 ? k - 1 : 0], dt);
                  })});
  rows.push_back({"TipLoop (around the BoucWenBacklash inverse, gains scheduled)", measure(n, [&](std::size_t k) {
                    if (k % 100 == 0) tipped.set_curve_angle(3.0 + std::sin(1e-3 * k));
                    return tipped.step(yd[k], 0.97 * yd[k > 0 ? k - 1 : 0], dt);
                  })});
  rows.push_back({"LearnedFeedforward (a 1e6-sample table around the BoucWenBacklash inverse)",
                  measure(n, [&](std::size_t k) { return learned.step(yd[k], dt); })});
  rows.push_back({"InverseFeedforward (GPI, root search)", measure(n, [&](std::size_t k) { return gpi_inverse.step(yd[k], dt); })});
  rows.push_back({"InverseFeedforward (BoucWenBacklash+poly3, root search)", measure(n, [&](std::size_t k) { return chain_inverse.step(yd[k], dt); })});
  rows.push_back({"AdaptiveController", measure(n, [&](std::size_t k) {
                    const double y = 0.98 * yd[k > 0 ? k - 1 : 0];
                    return adaptive.step(yd[k], y, yd[k], dt);
                  })});

  std::printf("{\"steps\": %zu, \"rows\": [", n);
  for (std::size_t i = 0; i < rows.size(); ++i)
    std::printf("%s{\"name\": \"%s\", \"median_ns\": %.1f, \"p999_ns\": %.1f, \"mean_ns\": %.1f}",
                i ? ", " : "", rows[i].name.c_str(), rows[i].stats.median_ns, rows[i].stats.p999_ns,
                rows[i].stats.mean_ns);
  std::printf("]}\n");
  return 0;
}
