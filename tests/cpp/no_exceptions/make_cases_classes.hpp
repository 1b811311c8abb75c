// The classes make_cases.cpp builds: models, compensators and plants with random bad values
// (spoiled), with good ones (steps), and the structural bad cases that would read or allocate
// past a bound if a constructor went on after its failed check.
#pragma once

namespace {

ts::PrandtlIshlinskiiParams pi_params() {
  ts::PrandtlIshlinskiiParams p;
  p.thresholds = {0.0, 0.1, 0.25};
  p.weights = {0.9, 0.3, 0.15};
  return p;
}

void models(Rng& rng) {
  using BL = ts::BacklashParams;
  spoiled<ts::Backlash, BL>("Backlash", {},
                            {bad(&BL::c_r), bad(&BL::c_l), bad(&BL::B_r), bad(&BL::B_l)}, rng);
  steps<ts::Backlash>("Backlash", 1.0, rng, BL{});
  using BW = ts::BoucWenParams;
  spoiled<ts::BoucWen, BW>("BoucWen", {},
                           {bad(&BW::A), bad(&BW::beta), bad(&BW::n), bad(&BW::max_step),
                            bad_int(&BW::max_substeps)},
                           rng);
  steps<ts::BoucWen>("BoucWen", 1.0, rng, BW{});
  using BWB = ts::BoucWenBacklashParams;
  spoiled<ts::BoucWenBacklash, BWB>("BoucWenBacklash", {},
                                    {bad(&BWB::c_r), bad(&BWB::rho), bad(&BWB::sigma),
                                     bad(&BWB::n), bad_int(&BWB::max_substeps)},
                                    rng);
  steps<ts::BoucWenBacklash>("BoucWenBacklash", 1.0, rng, BWB{});
  steps<ts::PrandtlIshlinskii>("PrandtlIshlinskii", 1.0, rng, pi_params());
  steps<ts::PrandtlIshlinskiiInverse>("PrandtlIshlinskiiInverse", 1.0, rng, pi_params());
  using GPI = ts::GeneralizedPrandtlIshlinskiiParams;
  steps<ts::GeneralizedPrandtlIshlinskii>("GeneralizedPrandtlIshlinskii", 1.0, rng, GPI{});
  steps<ts::GeneralizedPrandtlIshlinskiiInverse>("GeneralizedPrandtlIshlinskiiInverse", 0.5, rng,
                                                 GPI{});
  using HO = ts::HystereticOscillatorParams;
  HO bandlimited;
  bandlimited.input_interpolation = ts::kInputBandlimited;
  spoiled<ts::HystereticOscillator, HO>(
      "HystereticOscillator", bandlimited,
      {bad(&HO::m), bad(&HO::nu), bad_int(&HO::substeps), bad_int(&HO::lookahead)}, rng);
  steps<ts::HystereticOscillator>("HystereticOscillator", 1.0, rng, bandlimited);
  using CA = ts::CurveAngleParams;
  spoiled<ts::CurveAngleModel, CA>(
      "CurveAngleModel", {},
      {bad(&CA::stiffness), bad(&CA::length), bad(&CA::proximal_radius), bad(&CA::play)}, rng);
  steps<ts::CurveAngleModel>("CurveAngleModel", 1.0, rng, CA{});
  using PM = ts::PlantModelParams;
  spoiled<ts::PlantModel, PM>(
      "PlantModel", {},
      {bad(&PM::friction_angle), bad(&PM::backlash), bad(&PM::gain), bad_int(&PM::elements)}, rng);
  steps<ts::PlantModel>("PlantModel", 1.0, rng, PM{});
}

void compensators(Rng& rng) {
  using BI = ts::BacklashInverseParams;
  spoiled<ts::BacklashInverseFeedforward, BI>("BacklashInverseFeedforward", {},
                                              {bad(&BI::c_r), bad(&BI::B_l), bad(&BI::smoothing)}, rng);
  steps<ts::BacklashInverseFeedforward>("BacklashInverseFeedforward", 1.0, rng, BI{});
  ts::CommandLimits limits;
  limits.max_rate = 25.0;
  steps<ts::PrandtlIshlinskiiFeedforward>("PrandtlIshlinskiiFeedforward", 1.0, rng, pi_params(),
                                          limits);
  using CF = ts::CurveAngleFeedforwardParams;
  spoiled<ts::CurveAngleFeedforward, CF>("CurveAngleFeedforward", {},
                                         {bad(&CF::stiffness), bad(&CF::curve_angle),
                                          bad(&CF::smoothing), bad(&CF::max_correction_rate)},
                                         rng);
  steps<ts::CurveAngleFeedforward>("CurveAngleFeedforward", 1.0, rng, CF{});
  using CN = ts::ContinuumFeedforwardParams;
  CN published;
  published.mode = ts::ContinuumMode::Published;
  spoiled<ts::ContinuumFeedforward, CN>("ContinuumFeedforward", published,
                                        {bad(&CN::friction), bad(&CN::length),
                                         bad(&CN::curve_angle), bad(&CN::bending_stiffness)},
                                        rng);
  steps<ts::ContinuumFeedforward>("ContinuumFeedforward", 0.5, rng, published);
  using LI = ts::LagInverseParams;
  spoiled<ts::LagInverse, LI>(
      "LagInverse", {}, {bad(&LI::time_constant), bad(&LI::filter_hz), bad_int(&LI::order)}, rng);
  steps<ts::LagInverse>("LagInverse", 1.0, rng, LI{});
  steps<ts::OscillatorInverse>("OscillatorInverse", 1.0, rng, ts::HystereticOscillatorParams{},
                               20.0);
  using EL = ts::EncoderLoopParams;
  spoiled<ts::EncoderLoop, EL>(
      "EncoderLoop", {},
      {bad(&EL::ki), bad(&EL::derivative_cutoff_hz), bad(&EL::max_correction)}, rng);
  using TL = ts::TipLoopParams;
  spoiled<ts::TipLoop, TL>(
      "TipLoop", {}, {bad(&TL::kp), bad(&TL::derivative_cutoff_hz), bad(&TL::max_correction)},
      rng);
  using AC = ts::AdaptiveControllerParams;
  spoiled<ts::AdaptiveController, AC>(
      "AdaptiveController", {},
      {bad(&AC::lambda), bad(&AC::epsilon), bad(&AC::phi_min), bad(&AC::max_torque)}, rng);
  for (double dt : kBad)
    built<ts::LearnedCorrection>("LearnedCorrection", std::vector<double>{0.0, 0.1, 0.2},
                                 ts::LearnedFeedforwardParams{dt, true, {}});
}

void plants(Rng& rng) {
  const ts::Route route = ts::Route::uniform(1.0, 2.0);
  using ST = ts::SingleTendonParams;
  ST tendon;
  tendon.elements = 20;
  spoiled<ts::SingleTendonPlant, ST>("SingleTendonPlant", tendon,
                                     {bad(&ST::friction), bad(&ST::stiffness),
                                      bad(&ST::load_force), bad_int(&ST::elements)},
                                     rng, route);
  steps<ts::SingleTendonPlant>("SingleTendonPlant", 2e-3, rng, tendon, route);
  using PP = ts::PullPullParams;
  PP pair;
  pair.elements = 20;
  spoiled<ts::PullPullPlant, PP>("PullPullPlant", pair,
                                 {bad(&PP::stiffness), bad(&PP::pretension),
                                  bad(&PP::distal_radius), bad_int(&PP::elements)},
                                 rng, route);
  steps<ts::PullPullPlant>("PullPullPlant", 0.5, rng, pair, route);
  using CP = ts::ContinuumParams;
  CP segment;
  segment.elements = 20;
  spoiled<ts::ContinuumPlant, CP>(
      "ContinuumPlant", segment,
      {bad(&CP::bending_stiffness), bad(&CP::tendon_offset), bad_int(&CP::elements)}, rng, route);
  steps<ts::ContinuumPlant>("ContinuumPlant", 0.5, rng, segment, route);
  using MP = ts::MotorParams;
  spoiled<ts::Motor, MP>("Motor", {},
                         {bad(&MP::bandwidth_hz), bad(&MP::damping), bad(&MP::max_speed),
                          bad_int(&MP::max_substeps)},
                         rng);
  using SP = ts::SensorParams;
  SP delayed;
  delayed.delay = 0.01;
  spoiled<ts::Sensor, SP>("Sensor", delayed,
                          {bad(&SP::resolution), bad(&SP::delay), bad_int(&SP::history)}, rng);
}

// the cases a constructor going on past its failed check would turn into a read past a vector,
// an allocation of a negative size or a division by zero
void structural() {
  ts::PrandtlIshlinskiiParams pi = pi_params();
  pi.thresholds.clear();
  built<ts::PrandtlIshlinskii>("PrandtlIshlinskii empty", pi);
  pi = pi_params();
  pi.weights.resize(1);
  built<ts::PrandtlIshlinskiiInverse>("PrandtlIshlinskiiInverse short weights", pi);
  built<ts::PrandtlIshlinskiiFeedforward>("PrandtlIshlinskiiFeedforward short weights", pi,
                                          ts::CommandLimits{});
  ts::GeneralizedPrandtlIshlinskiiParams gpi;
  gpi.weights.resize(2);
  built<ts::GeneralizedPrandtlIshlinskiiInverse>("GPI inverse short weights", gpi);
  gpi.thresholds.clear();
  built<ts::GeneralizedPrandtlIshlinskii>("GeneralizedPrandtlIshlinskii empty", gpi);
  built<ts::Route>("Route mismatched", std::vector<double>{0.0, 0.5, 1.0},
                   std::vector<double>{0.0});
  built<ts::Route>("Route one sample", std::vector<double>{0.0}, std::vector<double>{0.0});
  built<ts::Polynomial>("Polynomial empty", ts::PolynomialParams{{}, false});
  for (int half_width : {-3, 0, 1000})
    built<ts::SincKernel>("SincKernel " + std::to_string(half_width), half_width);
  ts::TipLoopParams tip;
  tip.schedule_size = 1000;
  built<ts::TipLoop>("TipLoop schedule_size 1000", tip);
  ts::SensorParams sensor;
  sensor.delay = 0.01;
  sensor.history = -5;
  built<ts::Sensor>("Sensor history -5", sensor);
  built<ts::LearnedCorrection>("LearnedCorrection empty", std::vector<double>{},
                               ts::LearnedFeedforwardParams{});
  ts::SingleTendonParams tendon;
  tendon.elements = -7;
  built<ts::SingleTendonPlant>("SingleTendonPlant elements -7", tendon,
                               ts::Route::uniform(1.0, 1.0));
  ts::PlantModelParams plant;
  plant.elements = 1;
  built<ts::PlantModel>("PlantModel elements 1", plant);
  ts::HystereticOscillatorParams osc;
  osc.m = 0.0;
  built<ts::OscillatorInverse>("OscillatorInverse m 0", osc, -1.0);
  ts::AdaptiveControllerParams adaptive;
  adaptive.feedforward.c_r = kNaN;
  built<ts::AdaptiveController>("AdaptiveController feedforward NaN", adaptive);
}

// the classes built from other objects: a bad setting, a coupling of the wrong size, more
// angle laws than their arrays hold
void composed(Rng& rng) {
  ts::ModelPart part;
  part.kind = "Backlash";
  ts::InverseModel model;
  model.parts = {part};
  const ts::ModelInverse joint = ts::make_model_inverse(model, ts::InverseSettings{});
  const std::vector<ts::ModelInverse> joints{joint, joint};
  built<ts::CoupledFeedforward>("CoupledFeedforward 3 couplings", joints,
                                std::vector<double>{0.0, 0.1, 0.2});
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<double> coupling{0.0, 0.2, 0.1, 0.0};
    coupling[rng.below(4)] = kBad[rng.below(3)];
    built<ts::CoupledFeedforward>("CoupledFeedforward #" + std::to_string(trial), joints,
                                  coupling);
  }
  const ts::Backlash backlash{ts::BacklashParams{}};
  built<ts::RootInverse<ts::Backlash>>("RootInverse range", backlash, ts::InputRange{1.0, -1.0},
                                       ts::RootSearchSettings{});
  ts::RootSearchSettings search;
  search.max_evaluations = 2;
  built<ts::RootInverse<ts::Backlash>>("RootInverse settings", backlash, ts::InputRange{}, search);
  ts::LoadTerms terms;
  terms.slack_load = kNaN;
  built<ts::LoadPlayInverse>("LoadPlayInverse", terms);
  ts::AngleLaws laws;
  laws.count = 100;
  const ts::BacklashInverseFeedforward engine{ts::BacklashInverseParams{}};
  built<ts::AngleDependentInverse<ts::BacklashInverseFeedforward>>("AngleDependentInverse 100 laws",
                                                                   engine, laws, 0.0);
}

#if !TENDONSHEATH_EXCEPTIONS
// Runs f in a child process, its stderr into a pipe: (how it ended, what it wrote there).
std::pair<int, std::string> in_child(void (*f)()) {
  int fd[2];
  std::fflush(stdout);  // the child must not print the parent's buffered lines again
  if (pipe(fd) != 0) return {-1, ""};
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fd[1], 2);
    close(fd[0]);
    f();
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buf[512];
  for (ssize_t n; (n = read(fd[0], buf, sizeof buf)) > 0;)
    text.append(buf, static_cast<std::size_t>(n));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return {status, text};
}

ts::BacklashParams bad_backlash() {
  ts::BacklashParams p;
  p.c_l = -1.0;
  return p;
}

void record_and_exit(const char* message) {
  std::fprintf(stderr, "handler: %s", message);
  std::fflush(stderr);
  _exit(42);
}
void record_and_return(const char* message) { std::fprintf(stderr, "returned: %s", message); }

void handler_checks() {
  const std::string message = ts::make<ts::Backlash>(bad_backlash()).error();
  check(message == "Backlash: c_l must be > 0 (got -1)", "make() said: " + message);
  // a constructor outside make() (after a make() on the same thread): the handler, once
  auto [status, text] = in_child([] {
    (void)ts::make<ts::Backlash>(bad_backlash());
    ts::set_error_handler(record_and_exit);
    ts::Backlash b(bad_backlash());
    (void)b;
  });
  check(WIFEXITED(status) && WEXITSTATUS(status) == 42, "the handler did not end the child");
  check(text == "handler: " + message, "the handler got: " + text);
  // the default handler: the message on stderr, then std::abort()
  std::tie(status, text) = in_child([] {
    ts::Sensor s(ts::SensorParams{0.0, -1.0});
    (void)s;
  });
  check(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT, "the default handler did not abort");
  check(text == "Sensor: noise_std must be >= 0 (got -1)\n", "the default handler wrote: " + text);
  // a handler that returns: std::abort() all the same
  std::tie(status, text) = in_child([] {
    ts::set_error_handler(record_and_return);
    ts::Route r = ts::Route::uniform(-1.0, 0.0);
    (void)r;
    std::fprintf(stderr, "went on");
  });
  check(WIFSIGNALED(status) && WTERMSIG(status) == SIGABRT, "a returning handler went on");
  check(text == "returned: Route.uniform: length must be > 0 (got -1)", "returned: " + text);
  // value() of an error is an error too
  std::tie(status, text) = in_child([] {
    ts::set_error_handler(record_and_exit);
    (void)ts::make<ts::Backlash>(bad_backlash()).value();
  });
  check(WIFEXITED(status) && WEXITSTATUS(status) == 42 && text == "handler: " + message,
        "value() of an error: " + text);
  check(ts::set_error_handler(nullptr) == nullptr, "the parent's handler changed");
}
#endif

}  // namespace
