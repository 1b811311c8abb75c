"""The population of drives: draws inside their priors, reproducible, every member a working
drive; its test conditions off the calibration's; the motor encoder's resolution and noise
reaching the logs and the controllers."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench.population import demo_draw
from tendonsheath.plant import population as pop

DRAWS = {
    "pull-pull": ts.presets.random_realistic_plant,
    "continuum": ts.presets.random_continuum_plant,
    "single-tendon": ts.presets.random_single_tendon_plant,
}


@pytest.mark.parametrize("kind", list(DRAWS))
def test_every_value_is_drawn_inside_its_prior_and_reproducibly(kind):
    draw = DRAWS[kind]
    priors = {
        **pop.PRIORS,
        **{"continuum": pop.CONTINUUM_PRIORS, "single-tendon": pop.SINGLE_TENDON_PRIORS}.get(
            kind, {}
        ),
    }
    seen = {name: [] for name in priors}
    for seed in range(60):
        d = draw(seed)
        assert d.kind == kind
        assert pop.in_priors(d) == []
        assert d.values == draw(seed).values  # the same seed, the same drive
        for name in seen:
            seen[name].append(d.values[name])
    # the draws spread over their priors (a prior stuck at one value would not)
    for name, (_, low, high) in priors.items():
        v = np.asarray(seen[name], dtype=float)
        assert np.ptp(v) > 0.3 * (high - low), name


def test_the_demo_plant_is_a_member():
    assert pop.in_priors(demo_draw()) == []


def test_a_value_outside_its_prior_is_named():
    d = ts.presets.random_realistic_plant(0)
    odd = pop.PlantDraw(0, d.kind, {**d.values, "friction": 0.5}, d.nominal_route)
    assert any(s.startswith("friction = 0.5 outside") for s in pop.in_priors(odd))


@pytest.mark.parametrize("seed", [-1, 1.5, "3", True])
def test_a_bad_seed_is_refused(seed):
    with pytest.raises(ValueError, match="population seed"):
        ts.presets.random_realistic_plant(seed)


@pytest.mark.parametrize("seed", range(8))
def test_routes_keep_the_drawn_length_and_the_angle_range(seed):
    d = ts.presets.random_realistic_plant(seed)
    assert d.nominal_route.length == pytest.approx(d.values["length"], rel=1e-9)
    assert d.nominal_route.curve_angle == pytest.approx(d.values["route_angle"], rel=1e-9)
    for r in d.calibration_routes:
        assert r.length == pytest.approx(d.values["length"], rel=1e-9)
    times, routes = d.route_schedule(60.0, seed=3)
    assert times[0] == 0.0 and np.all(np.diff(times) > 0.0) and times[-1] < 60.0
    for r in routes[1:]:
        assert r.length == pytest.approx(d.values["length"], rel=1e-9)
        assert math.radians(90.0) - 1e-9 <= r.curve_angle <= math.radians(720.0) + 1e-9
    # another route seed, another schedule
    assert d.route_schedule(60.0, seed=4)[0] != times


@pytest.mark.parametrize("seed", range(10))
def test_references_stay_in_the_workspace_off_the_calibration_frequency(seed):
    d = ts.presets.random_realistic_plant(seed)
    t, y = d.reference(80.0, seed=seed)
    assert np.abs(y).max() <= d.values["workspace"] + 1e-12
    spectrum = np.abs(np.fft.rfft(y * np.hanning(y.size)))
    peak = np.fft.rfftfreq(y.size, t[1] - t[0])[np.argmax(spectrum)]
    assert not 0.19 < peak < 0.31  # the calibration's main frequency is 0.25 Hz
    t2, y2 = d.reference(20.0, seed=seed, lead_in=3.0)
    assert y2[0] == pytest.approx(0.0, abs=1e-12)  # from rest
    np.testing.assert_array_equal(y2[t2 >= 3.0], d.reference(20.0, seed=seed)[1][t2 >= 3.0])


def test_a_drifted_drive_moves_only_the_drifting_values_and_within_their_share():
    d = ts.presets.random_realistic_plant(5)
    for s in range(20):
        e = d.drifted(s)
        for name, value in d.values.items():
            share = pop.DRIFT.get(name, 0.0)
            assert abs(e.values[name] / value - 1.0) <= share + 1e-12 if value else True, name
        assert any(e.values[n] != d.values[n] for n in pop.DRIFT)


@pytest.mark.parametrize("kind", list(DRAWS))
def test_every_member_is_a_working_drive(kind):
    for seed in range(6):
        d = DRAWS[kind](seed)
        t, y = d.reference(6.0, seed=seed)
        r = ts.bench.run(d.plant(), None, t, y, routes=d.routes(6.0, seed))
        assert np.isfinite(r.metrics["mse"]) and r.metrics["mse"] > 0.0
        # more stroke moves the tip further (the kinematic command of a soft continuum draw
        # may barely clear its dead band: the tendons stretch first)
        small = np.ptp(d.plant().simulate(t, d.kinematic_gain * y).q_out)
        large = np.ptp(d.plant().simulate(t, 8.0 * d.kinematic_gain * y).q_out)
        assert large > 2.0 * small


@pytest.mark.parametrize("seed", range(5))
def test_the_motor_encoder_reads_in_counts(seed):
    d = ts.presets.random_realistic_plant(seed)
    res = d.encoder_resolution
    lines = 2 ** int(d.values["encoder_lines_log2"])
    assert res == pytest.approx(2 * math.pi / (4 * lines * d.values["gear_ratio"]), rel=1e-12)
    exact = ts.Sensor(resolution=res)  # quantisation alone: every reading a whole count
    plant = ts.PullPullPlant(route=d.nominal_route, motor=d.motor(), encoder=exact, **d.physics())
    t, y = d.reference(3.0, seed=seed)
    sim = plant.simulate(t, y)
    counts = sim.q_motor / res
    np.testing.assert_allclose(counts, np.round(counts), atol=1e-6)
    r = ts.bench.run(plant, None, t, y)
    counts = r.q_motor / res
    np.testing.assert_allclose(counts, np.round(counts), atol=1e-6)
    # and the shaft itself is not quantised: without the encoder the log is the shaft
    bare = ts.PullPullPlant(route=d.nominal_route, motor=d.motor(), **d.physics())
    shaft = bare.simulate(t, y).q_motor
    assert np.abs(shaft / res - np.round(shaft / res)).max() > 0.1
    assert np.abs(sim.q_motor - shaft).max() <= 0.5 * res + 1e-12


def test_encoder_noise_reaches_the_controller_reading():
    d = ts.presets.random_realistic_plant(2)
    noisy = ts.Sensor(noise_std=1e-3, seed=4)
    plant = ts.PullPullPlant(route=d.nominal_route, motor=d.motor(), encoder=noisy, **d.physics())
    bare = ts.PullPullPlant(route=d.nominal_route, motor=d.motor(), **d.physics())
    t, y = d.reference(4.0, seed=1)
    diff = ts.bench.run(plant, None, t, y).q_motor - ts.bench.run(bare, None, t, y).q_motor
    # the uncompensated command ignores the encoder, so the difference is the noise alone
    assert np.std(diff) == pytest.approx(1e-3, rel=0.1)


def test_an_encoder_needs_a_motor_and_a_sensor():
    route = ts.Route.uniform(1.0, math.pi)
    with pytest.raises(ValueError, match="encoder reads a motor"):
        ts.PullPullPlant(route=route, encoder=ts.Sensor())
    with pytest.raises(TypeError, match="encoder must be a tendonsheath.Sensor"):
        ts.PullPullPlant(route=route, motor=ts.Motor.position(), encoder=1e-3)


def test_a_member_study_chooses_its_loop_by_trials_and_reports_both():
    from tendonsheath.bench.population import flatten, member_study

    m = member_study(3, studies=("sensorless",), duration=8.0,
                     budget={"maxiter": 8, "popsize": 6})  # fmt: skip
    s = m["sensorless"]
    chosen = s["feedforward + EncoderLoop"] if s["loop kept"] else s["feedforward"]
    assert s["chosen"] == chosen
    assert ("chosen: feedforward + EncoderLoop" in s["why"]) == s["loop kept"]
    # the loop is kept only where it helped on every calibration trial by 5 %
    assert (s["trial ratio"] < 0.95) == s["loop kept"]
    for figures in (s["feedforward"], s["feedforward + EncoderLoop"]):
        assert len(figures["seeds"]) == 5
        assert figures["median"] == pytest.approx(np.median(figures["seeds"]))
        assert figures["min"] == min(figures["seeds"])
    # the identified feedforward helps on the drive it was calibrated on (drifted since)
    assert s["feedforward"]["median"] > 3.0
    with pytest.raises(KeyError):  # only the studies asked for are run
        flatten(m)
    with pytest.raises(ValueError, match="unknown studies"):
        member_study(3, studies=("tip", "magic"))


def test_every_route_of_a_drive_keeps_its_length_even_with_a_tiny_lead_in():
    rng = np.random.default_rng(0)
    for lead_in in (0.0, 1e-5, 4e-4, 0.1):
        r = pop._route(2.0, math.pi, 3, lead_in, rng)
        assert r.length == pytest.approx(2.0, rel=1e-12)


def test_the_demo_member_is_the_demos_plant():
    from tendonsheath.bench.scenarios import do

    d = demo_draw()
    demo = do.physics()
    mine = d.physics()
    for key in (
        "friction",
        "stiffness",
        "pretension",
        "proximal_radius",
        "distal_radius",
        "distal_inertia",
        "distal_damping",
        "sheath_viscosity",
        "friction2",
        "stiffness2",
        "relaxation_fraction",
        "relaxation_time",
    ):
        assert mine[key] == pytest.approx(demo[key], rel=1e-12), key
    assert d.motor().params == do.servo_motor("pid").params
    assert d.servo == "pid"


def test_the_report_reads_the_population_study_from_its_committed_json(tmp_path):
    import json
    from pathlib import Path

    import tendonsheath.apps.demo as demo

    assert demo.population_section(tmp_path / "none.json") is None  # outside the repository
    path = Path(__file__).resolve().parents[1] / "benchmarks" / "results" / "population.json"
    body, data = demo.population_section(path)
    figures = json.loads(path.read_text())
    assert data == {"source": str(path), "members": figures["members"]}
    for name in demo.POPULATION_TARGETS:
        median = figures["pull_pull"][name]["median"]["median"]
        assert f"<td>{name}</td><td>{median:.3g}x</td>" in body
    assert figures["members"] >= 20 and figures["route_seeds"] >= 5
