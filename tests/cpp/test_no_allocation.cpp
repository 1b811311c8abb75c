// The real-time contract, counted: after construction and a warm-up, step() of every
// real-time class (and the streaming shape updates) allocates nothing. The global
// operator new is replaced to count allocations while a counter is armed.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <tendonsheath/tendonsheath.hpp>
#include <vector>

#include "counting_new.hpp"  // counts allocations while armed
#include "listed_steppers.hpp"
#include "model_inverse_cases.hpp"

namespace ts = tendonsheath;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Allocations made by f() (run twice, so lazily sized state is sized by the first run).
template <class F>
long allocations_in(F&& f) {
  f();
  allocations = 0;
  armed = true;
  f();
  armed = false;
  return allocations.load();
}

// A demanding input: sines of two rates, reversals, a shock, a NaN and an extreme value.
double input(int k) {
  const double t = k * 1e-3;
  double u = 0.5 * std::sin(2 * kPi * 0.7 * t) + 0.1 * std::sin(2 * kPi * 5.0 * t);
  if (k == 300) u = NAN;
  if (k == 400) u = 1e12;
  return u;
}
}  // namespace

TEST(NoAllocation, PlantsMotorAndSensorStep) {
  ts::PullPullParams p;
  p.elements = 40;
  p.sheath_viscosity = 8.0;
  p.relaxation_fraction = 0.08;
  p.distal_inertia = 2e-5;
  p.distal_damping = 2e-3;
  ts::PullPullPlant pair(p, ts::Route::uniform(1.2, kPi));
  ts::ContinuumParams c;
  c.elements = 30;
  ts::ContinuumPlant continuum(c, ts::Route::uniform(1.0, kPi));
  ts::SingleTendonParams s;
  s.elements = 30;
  ts::SingleTendonPlant single(s, ts::Route::uniform(1.0, 2.0));
  ts::MotorParams mp;
  mp.inertia = 1e-4;
  mp.coulomb_friction = 0.01;
  mp.gear_backlash = 0.01;
  ts::Motor motor(mp);
  mp.integral_time = 0.1;  // the PID servo, speed-limited some of the time
  mp.max_speed = 3.0;
  ts::Motor pid(mp);
  ts::Sensor sensor(ts::SensorParams{1e-4, 2e-4, 3});
  ts::SensorParams delayed_params{1e-4, 2e-4, 3};
  delayed_params.delay = 0.005;  // a latency in its history, and one beyond it (flagged)
  ts::Sensor delayed(delayed_params);
  delayed_params.history = 3;
  ts::Sensor short_history(delayed_params);
  std::vector<double> angles(pair.n_node_angles(), 0.05);
  const long n = allocations_in([&] {
    for (int k = 0; k < 1000; ++k) {
      if (k % 250 == 0) {
        for (double& a : angles) a = 0.02 + 0.0005 * (k / 250);
        pair.set_node_angles(angles.data());  // a route change in the loop
      }
      const double q = motor.step(input(k), 1e-3, pair.drive_reaction());
      const double y = pair.step(q, 1e-3);
      sensor.measure(y);
      delayed.measure(y, 1e-3);
      short_history.measure(y, 1e-3);
      pid.step(input(k), 1e-3, 0.01);
      continuum.step(input(k), 1e-3);
      single.step(1e-3 * input(k), 1e-3);
      (void)pair.status();
    }
  });
  EXPECT_EQ(n, 0);
}

TEST(NoAllocation, ModelsStep) {
  ts::Backlash backlash(ts::BacklashParams{});
  ts::BoucWenBacklash bwb(ts::BoucWenBacklashParams{});
  ts::BoucWen bw(ts::BoucWenParams{});
  ts::HystereticOscillator osc(ts::HystereticOscillatorParams{});
  ts::PrandtlIshlinskii pi(ts::PrandtlIshlinskiiParams{{0.0, 0.1, 0.2}, {0.5, 0.3, 0.2}});
  ts::PrandtlIshlinskiiInverse pi_inv(ts::PrandtlIshlinskiiParams{{0.0, 0.1, 0.2}, {0.5, 0.3, 0.2}});
  ts::GeneralizedPrandtlIshlinskii gpi(ts::GeneralizedPrandtlIshlinskiiParams{});
  ts::GeneralizedPrandtlIshlinskiiInverse gpi_inv(ts::GeneralizedPrandtlIshlinskiiParams{});
  ts::CurveAngleModel curve(ts::CurveAngleParams{});
  const long n = allocations_in([&] {
    for (int k = 0; k < 1000; ++k) {
      const double x = input(k);
      backlash.step(x);
      bwb.step(x, 1e-3);
      bw.step(x, 1e-3);
      osc.step(x, 1e-3);
      pi.step(x);
      pi_inv.step(x);
      gpi.step(x);
      gpi_inv.step(0.5 * x);
      curve.step(x, 1e-3, 1.0 + 0.001 * k);
      curve.set_shape(ts::ShapeIntegrals{0.8, 1.3, 2.0 + 0.001 * k});
      curve.step(x, 1e-3);
    }
  });
  EXPECT_EQ(n, 0);
}

TEST(NoAllocation, CompensatorsStep) {
  ts::BacklashInverseFeedforward inverse(ts::BacklashInverseParams{});
  ts::CurveAngleFeedforward curve(ts::CurveAngleFeedforwardParams{});
  ts::ContinuumFeedforward continuum(ts::ContinuumFeedforwardParams{});
  ts::AdaptiveController adaptive(ts::AdaptiveControllerParams{});
  ts::EncoderLoopParams lp;
  lp.kp = 1.0, lp.kd = 1e-3, lp.limits.max = 0.4;
  ts::EncoderLooped<ts::CurveAngleFeedforward> looped(curve, ts::EncoderLoop(lp));
  ts::LearnedFeedforwardParams learned_p;
  learned_p.table_dt = 2e-3, learned_p.limits.max_rate = 50.0;
  std::vector<double> table(300);  // 0.6 s: the loop below runs past its end
  for (std::size_t i = 0; i < table.size(); ++i) table[i] = 0.01 * std::sin(0.05 * i);
  ts::LearnedFeedforward<ts::CurveAngleFeedforward> learned(
      curve, ts::LearnedCorrection(table, learned_p));
  ts::TipLoopParams tp;
  tp.kp = 0.5, tp.ki = 40.0, tp.kd = 1e-3, tp.limits.max = 0.4, tp.schedule_size = 3;
  tp.schedule_angles = {0.0, 1.0, 3.0};
  tp.schedule_gains = {0.5, 1.0, 2.0};
  ts::TipLooped<ts::CurveAngleFeedforward> tipped(curve, ts::TipLoop(tp));
  const long n = allocations_in([&] {
    for (int k = 0; k < 1000; ++k) {
      const double y = input(k);
      if (k % 100 == 0) curve.set_curve_angle(0.5 + 0.01 * k);
      if (k % 150 == 0) looped.set_shape(ts::uniform_shape(0.1, 0.2 + 0.01 * k));
      inverse.step(y, 1e-3);
      curve.step(y, 1e-3);
      continuum.step(y, 1e-3);
      adaptive.step(y, k % 200 == 0 ? NAN : 0.9 * y, 0.8 * y, 1e-3);
      looped.step(y, k % 250 == 0 ? NAN : 0.7 * y, 1e-3);
      if (k % 150 == 0) learned.set_shape(ts::uniform_shape(0.1, 0.2 + 0.01 * k));
      if (k == 500) learned.reset();
      learned.step(y, k % 333 == 0 ? NAN : 1e-3);
      if (k % 120 == 0) tipped.set_shape(ts::uniform_shape(0.1, 0.01 * k));
      if (k % 170 == 0) tipped.set_curve_angle(k % 340 == 0 ? NAN : 0.02 * k);
      tipped.step(y, k % 230 == 0 ? NAN : 0.8 * y, 1e-3);
    }
  });
  EXPECT_EQ(n, 0);
}

// Every model inverse (each kind of core and stage), with route changes for those that follow
// it and a bounded input range (the root search's peeks copy-assign the model: no allocation).
TEST(NoAllocation, ModelInversesStep) {
  std::vector<ts::ModelInverse> inverses;
  for (int i = 0; i < ts::cases::kInverseCases; ++i)
    inverses.push_back(ts::cases::inverse_case(i, i % 2 ? ts::InputRange{-0.8, 0.8} : ts::InputRange{}));
  const ts::ShapeIntegrals bent = ts::uniform_shape(0.1, 3.0);
  for (auto& inv : inverses) {
    const long n = allocations_in([&] {
      inv.reset();
      for (int k = 0; k < 1000; ++k) {
        if (k % 100 == 0) inv.set_curve_angle(0.5 + 0.002 * k);
        if (k % 100 == 50) inv.set_shape(bent);
        inv.step(input(k), k % 300 == 7 ? 2e-3 : 1e-3);  // dt changes: the lag filters redesign
      }
    });
    EXPECT_EQ(n, 0) << "core " << inv.core().index();
  }
}

// Coupled joints: every joint's inverse (a root-searching one among them) and the coupling.
TEST(NoAllocation, CoupledFeedforwardStep) {
  std::vector<ts::ModelInverse> joints;
  for (int i = 0; i < 3; ++i) joints.push_back(ts::cases::inverse_case(i, ts::InputRange{}));
  ts::CoupledFeedforward ff(joints, {0.0, 0.0, 0.0, 0.25, 0.0, 0.0, -0.1, 0.2, 0.0});
  const long n = allocations_in([&] {
    ff.reset();
    double u[3];
    for (int k = 0; k < 1000; ++k) {
      const double y_d[3] = {input(k), 0.5 * input(k + 50), 0.3 * input(k + 120)};
      ff.step(y_d, u, 1e-3);
    }
  });
  EXPECT_EQ(n, 0);
}

// The peek of the root search: copy-assigning a forward model (plays, a plant, a chain with a
// polynomial) to a scratch one of the same kind and sizes reuses its storage.
TEST(NoAllocation, ForwardModelCopyAssignment) {
  ts::PlantModelParams pm;
  pm.elements = 20;
  ts::ForwardModel plant{ts::ForwardModel::First{ts::PlantModel(pm)}};
  ts::ForwardModel pi{ts::ForwardModel::First{ts::PrandtlIshlinskii(ts::PrandtlIshlinskiiParams{})},
                      ts::Polynomial(ts::PolynomialParams{{0.0, 1.0, 0.2}, false})};
  ts::ForwardModel gpi{ts::ForwardModel::First{
      ts::GeneralizedPrandtlIshlinskii(ts::GeneralizedPrandtlIshlinskiiParams{})}};
  ts::ForwardModel plant_scratch = plant, pi_scratch = pi, gpi_scratch = gpi;
  const long n = allocations_in([&] {
    for (int k = 0; k < 200; ++k) {
      plant.step(input(k), 1e-3);
      pi.step(input(k), 1e-3);
      gpi.step(input(k), 1e-3);
      plant_scratch = plant;
      pi_scratch = pi;
      gpi_scratch = gpi;
      plant_scratch.step(input(k + 1), 1e-3);
    }
  });
  EXPECT_EQ(n, 0);
}

// A route change with a valid route: its validation formats no message when nothing is wrong
// (validate.hpp builds messages only on failure).
TEST(NoAllocation, SetRouteWithAValidRoute) {
  ts::PullPullParams p;
  p.elements = 100;
  ts::PullPullPlant pair(p, ts::Route::uniform(1.2, kPi));
  ts::SingleTendonParams s;
  s.elements = 50;
  ts::SingleTendonPlant single(s, ts::Route::uniform(1.2, 2.0));
  const ts::Route bent = ts::Route::arcs({{0.6, 0.5}, {0.6, 2.0}});
  const ts::Route straight = ts::Route::uniform(1.2, 0.0);
  const long n = allocations_in([&] {
    for (int k = 0; k < 20; ++k) {
      pair.set_route(k % 2 ? bent : straight, bent);
      pair.set_route(bent);
      single.set_route(k % 2 ? straight : bent);
      pair.step(0.01 * k, 1e-3);
    }
  });
  EXPECT_EQ(n, 0);
}

// The batch loops write each sample's Status into the caller's buffer: nothing allocated in
// the loop (nor in the validation before it, which formats messages only on failure).
TEST(NoAllocation, BatchLoopsCollectTheStatusPerSample) {
  constexpr std::size_t n = 2000;
  std::vector<double> t(n), x(n), y(n), measured(n), command(n);
  std::vector<unsigned char> flags(n);
  for (std::size_t k = 0; k < n; ++k) {
    t[k] = 1e-3 * static_cast<double>(k);
    x[k] = 0.5 * std::sin(2 * kPi * t[k]);
  }
  ts::Backlash backlash(ts::BacklashParams{});
  ts::PullPullParams p;
  p.elements = 30;
  ts::PullPullPlant plant(p, ts::Route::uniform(1.0, 2.0));
  ts::Sensor sensor(ts::SensorParams{1e-4, 1e-4, 2});
  ts::BacklashInverseParams bp;
  bp.limits.max = 0.3;
  ts::FeedforwardLoop<ts::BacklashInverseFeedforward> loop{ts::BacklashInverseFeedforward(bp)};
  const long allocated = allocations_in([&] {
    ts::simulate(backlash, t.data(), x.data(), y.data(), n, "simulate", flags.data());
    ts::PlantTrace trace;
    trace.q_out = y.data();
    trace.status = flags.data();
    ts::simulate_plant(plant, nullptr, nullptr, t.data(), x.data(), n, ts::RouteSchedule{}, trace,
                       "simulate_plant");
    ts::ClosedLoopTrace out;
    out.output = y.data();
    out.measured = measured.data();
    out.command = command.data();
    out.status = flags.data();
    ts::run_closed_loop(plant, nullptr, &sensor, loop, t.data(), x.data(), n, ts::RouteSchedule{},
                        ts::ShapeSchedule{}, nullptr, out, "bench");
  });
  EXPECT_EQ(allocated, 0);
  long saturated = 0;  // the loop's last run: the 0.3 limit cuts the 0.5 amplitude sine
  for (unsigned char f : flags) saturated += (f & static_cast<unsigned>(ts::Status::saturated)) != 0;
  EXPECT_GT(saturated, 100);
}

// The counter itself works: a vector's growth is counted (this test must be able to fail).
TEST(NoAllocation, TheCounterCounts) {
  std::vector<double> v;
  allocations = 0;
  armed = true;
  v.resize(1000);
  armed = false;
  EXPECT_GE(allocations.load(), 1);
}

// Every model and feedforward of the lists, built from its default parameters: one added to a
// list is checked here without a line of its own (the tests above also cover special cases).
TEST(NoAllocation, EveryModelAndFeedforwardOfTheListsSteps) {
  std::size_t checked = 0;
  ts::cases::for_each_listed_stepper([&](auto tag, const char* kind) {
    using C = typename decltype(tag)::type;
    C stepped{typename C::Params{}};  // the constructor may allocate (PlantModel's plant)
    const long n = allocations_in([&] {
      for (int k = 0; k < 1000; ++k) (void)stepped.step(input(k), 1e-3);
    });
    EXPECT_EQ(n, 0) << kind;
    ++checked;
  });
  EXPECT_GE(checked, 7u);  // the 7 root-invertible models at least (DeadZone among them)
}
