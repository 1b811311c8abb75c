// The hard work bound of a plant step (friction_chain.hpp): at most
//   max_solves() = max_substeps + 2 (max_iterations + E),  E = extra_iterations (-1: 2 M + 50)
// solves, whatever the input; a step that reaches it reports not_converged, and the plant
// recovers: later steps converge and, after a sweep that wipes the friction memory, the
// plant agrees with one that never hit the bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

long long formula(const ts::ChainOptions& o, long long M) {
  const long long extra = o.extra_iterations >= 0 ? o.extra_iterations : 2 * M + 50;
  return o.max_substeps + 2 * (o.max_iterations + extra);
}

ts::PullPullParams damped(int n) {
  ts::PullPullParams p;
  p.elements = n;
  p.load_stiffness = 0.05;
  p.load_damping = 0.01;  // the damped load (SpringDamper) of the audit's item 9
  return p;
}

// The adversarial set: random routes every 250 steps, a slow sine with fast reversals and,
// every 97 steps, a shock of up to +-0.5 rad.
struct Adversary {
  std::mt19937 gen{5};
  std::uniform_real_distribution<double> U{0.0, 1.0};
  double input(int k) {
    const double t = k * 1e-3;
    double q = 0.5 * std::sin(2 * kPi * t) + 0.05 * std::sin(2 * kPi * 37.0 * t);
    if (k % 97 == 0) q += U(gen) - 0.5;
    return q;
  }
  void route(ts::PullPullPlant& plant, std::vector<double>& a) {
    const double total = 0.3 + 8.0 * U(gen);
    for (double& x : a) x = total * (0.2 + 1.6 * U(gen)) / static_cast<double>(a.size() / 2);
    plant.set_node_angles(a.data());
  }
};
}  // namespace

TEST(PlantWorkBound, FormulaOfTheOptionsAndN) {
  for (int n : {2, 10, 100, 400}) {
    ts::PullPullPlant pair(damped(n), ts::Route::uniform(1.0, kPi));
    EXPECT_EQ(pair.chain().max_solves(), 8LL * n + 264) << n;  // defaults: M = 2 N
    ts::SingleTendonParams s;
    s.elements = n;
    ts::SingleTendonPlant single(s, ts::Route::uniform(1.0, kPi));
    EXPECT_EQ(single.chain().max_solves(), 4LL * n + 264) << n;  // M = N
  }
  ts::PullPullParams p = damped(50);
  p.options.max_iterations = 7;
  p.options.max_substeps = 3;
  p.options.extra_iterations = 11;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, kPi));
  EXPECT_EQ(plant.chain().max_solves(), formula(p.options, 100));
}

// Default options, N = 100, the adversarial set: never past the formula.
TEST(PlantWorkBound, AdversarialInputsStayWithinTheFormula) {
  ts::PullPullPlant plant(damped(100), ts::Route::uniform(1.2, kPi));
  const long long bound = formula(plant.params().options, 200);
  Adversary adv;
  std::vector<double> a(plant.n_node_angles());
  int worst = 0;
  for (int k = 0; k < 4000; ++k) {
    if (k % 250 == 0) adv.route(plant, a);
    ASSERT_TRUE(std::isfinite(plant.step(adv.input(k), 1e-3))) << k;
    ASSERT_LE(plant.chain().last_solves(), bound) << "step " << k;
    worst = std::max(worst, plant.chain().last_solves());
  }
  EXPECT_GT(worst, 20);  // the set is adversarial: some steps need many solves
}

// Tight options make the bound bite: the steps that reach it say so, the next steps go on to
// the input and converge, and after a wiping sweep the plant agrees with an unbounded one.
TEST(PlantWorkBound, StepsThatHitTheBoundRecover) {
  ts::PullPullParams tight = damped(40);
  tight.options.max_iterations = 5;
  tight.options.max_halvings = 1;
  tight.options.max_substeps = 4;
  tight.options.extra_iterations = 4;  // bound: 4 + 2 (5 + 4) = 22 solves
  ts::PullPullParams loose = damped(40);
  loose.options.max_iterations = 200;
  const ts::Route route = ts::Route::uniform(1.2, kPi);
  ts::PullPullPlant bounded(tight, route), reference(loose, route);
  const long long bound = formula(tight.options, 80);
  ASSERT_EQ(bounded.chain().max_solves(), bound);
  Adversary adv, adv_ref;
  std::vector<double> a(bounded.n_node_angles()), b(reference.n_node_angles());
  int hits = 0;
  for (int k = 0; k < 3000; ++k) {
    if (k % 250 == 0) adv.route(bounded, a), adv_ref.route(reference, b);
    const double q = adv.input(k);
    adv_ref.input(k);
    ASSERT_TRUE(std::isfinite(bounded.step(q, 1e-3)));
    reference.step(q, 1e-3);
    ASSERT_LE(bounded.chain().last_solves(), bound);
    EXPECT_EQ(ts::has(bounded.status(), ts::Status::not_converged),
              !bounded.chain().last_converged());
    if (bounded.chain().last_solves() == bound && !bounded.chain().last_converged()) ++hits;
  }
  std::printf("steps that reached the bound: %d\n", hits);
  ASSERT_GT(hits, 10);  // the bound was reached (else this test shows nothing)
  // hold the last input: within a few steps the plant reaches it and converges
  const double q_end = adv.input(2999);
  int k = 0;
  while (k < 10 && !(bounded.chain().last_converged() && std::fabs(bounded.input() - q_end) < 1e-12)) {
    bounded.step(q_end, 1e-3);
    ++k;
  }
  EXPECT_LT(k, 10) << "no recovery within 10 steps";
  // a slow sweep beyond the backlash in both directions wipes the friction memory
  for (int i = 0; i <= 4000; ++i) {
    const double q = 3.0 * std::sin(2 * kPi * i / 4000.0);
    bounded.step(q, 1e-3);
    reference.step(q, 1e-3);
    ASSERT_TRUE(bounded.chain().last_converged()) << "sweep step " << i;
  }
  EXPECT_NEAR(bounded.output(), reference.output(), 1e-6);
}
