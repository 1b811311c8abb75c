"""One simulate result type (issue 14 item 2): plants and models return a SimulationResult,
which is still the output array (np.asarray, indexing, arithmetic) and carries t, input,
success, message, status and .plot()."""

import pickle

import matplotlib
import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.models import (
    Backlash,
    BoucWen,
    BoucWenBacklash,
    Chain,
    CurveAngleModel,
    FirstOrderLag,
    HystereticOscillator,
    PrandtlIshlinskii,
    Scaled,
    SecondOrderLag,
)

matplotlib.use("Agg")


def _models(rng):
    b = Backlash(c_r=rng.uniform(0.8, 1.2), c_l=rng.uniform(0.8, 1.2), B_r=0.05, B_l=0.04)
    return [
        b,
        BoucWen(),
        BoucWenBacklash(B_r=rng.uniform(0, 0.1), B_l=rng.uniform(0, 0.1)),
        PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.2], weights=list(rng.uniform(0.2, 1, 3))),
        Scaled(b, input_offset=0.1, output_gain=-1.5),
        Chain(b, FirstOrderLag()),
        SecondOrderLag(),
        HystereticOscillator(),
    ]


def _plants():
    route = ts.Route.uniform(0.8, 2.0)
    return [
        ts.PullPullPlant(route, elements=20, motor=ts.Motor.position(60.0, 0.8)),
        ts.ContinuumPlant(route, elements=20),
        ts.SingleTendonPlant(route, elements=20),
    ]


def _check_array_access(res, t, x):
    assert isinstance(res, ts.SimulationResult) and isinstance(res, np.ndarray)
    y = np.asarray(res)
    assert type(y) is np.ndarray and y.shape == x.shape
    np.testing.assert_array_equal(res.output, y)
    assert type(res[5:]) is np.ndarray and res[3] == y[3]
    assert type(res - y) is np.ndarray and not np.any(res - y)
    assert float(np.mean(res)) == float(np.mean(y))
    np.testing.assert_array_equal(res.t, t)
    np.testing.assert_array_equal(res.input, x)
    assert res.success and res.message == ""


@pytest.mark.parametrize("seed", range(3))
def test_models_return_the_result_type(seed):
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, 2.0, 1e-3)
    x = rng.uniform(0.3, 1.0) * np.sin(2 * np.pi * rng.uniform(0.5, 2) * t)
    for model in _models(rng):
        res = model.simulate(t, x)
        _check_array_access(res, t, x)
        if model.reports_status:  # each sample's flags, always there
            assert res.status.dtype == np.uint8 and res.status.shape == x.shape
        else:  # a linear block reports none
            assert res.status is None
    curve = CurveAngleModel().simulate(t, x, curve_angle=1.0)
    _check_array_access(curve, t, x)


def test_plants_return_the_result_type_with_their_fields():
    t = np.arange(0.0, 2.0, 1e-3)
    for plant in _plants():
        x = (5e-3 if isinstance(plant, ts.SingleTendonPlant) else 1.0) * np.sin(2 * np.pi * t)
        res = plant.simulate(t, x)
        _check_array_access(res, t, x)
        np.testing.assert_array_equal(res.command, x)
        np.testing.assert_array_equal(res.q_out, res.output)
        assert res.q_in.shape == x.shape and res.status.shape == x.shape
        assert res.status.dtype == np.uint8


def test_the_old_status_and_full_switches_are_gone():
    """simulate(..., status=True), command(..., status=True) and a plant's full=True were
    removed (0.x, CHANGELOG): each is Python's own TypeError naming the argument, never the old
    tuple returned quietly; the flags are the result's ``status``."""
    t = np.arange(0.0, 1.0, 1e-3)
    x = np.sin(2 * np.pi * t)
    plant = _plants()[1]
    ff = ts.compensate.InverseFeedforward(BoucWenBacklash(B_r=0.05, B_l=0.05), smoothing=0.01)
    calls = [
        lambda: Backlash().simulate(t, x, status=True),
        lambda: Backlash().simulate(t, x, True),  # the old positional switch
        lambda: HystereticOscillator().simulate(t, x, None, True),
        lambda: Scaled(Backlash(), output_gain=2.0).simulate(t, x, status=True),
        lambda: plant.simulate(t, x, status=True),
        lambda: ff.command(t, 0.5 * x, status=True),
        lambda: plant.simulate(t, x, full=True),
    ]
    for call in calls:
        with pytest.raises(TypeError, match="status|full|positional argument"):
            call()
    assert ff.command(t, 0.5 * x).status.dtype == np.uint8


def test_command_returns_the_result_type():
    t = np.arange(0.0, 1.0, 1e-3)
    y_d = 0.5 * np.sin(2 * np.pi * t)
    ff = ts.compensate.InverseFeedforward(BoucWenBacklash(B_r=0.05, B_l=0.05), smoothing=0.01)
    u = ff.command(t, y_d)
    _check_array_access(u, t, y_d)
    assert u.status.dtype == np.uint8 and u.status.shape == y_d.shape
    # bit for bit the commands of the engine's call without flags (what command gave before)
    raw = ts._core.ModelInverse.command(ff, t, y_d, None, None, None, False)
    np.testing.assert_array_equal(u, raw)
    model = BoucWenBacklash(B_r=0.05, B_l=0.05)
    np.testing.assert_array_equal(
        model.simulate(t, y_d), ts._core.BoucWenBacklash.simulate(model, t, y_d, False)
    )


def test_failure_is_reported_and_results_pickle():
    bad = ts.SimulationResult([0.0, np.nan, 1.0], t=np.arange(3.0), input=np.zeros(3))
    assert not bad.success and bad.message == "1 non-finite output sample(s)"
    slack = ts.SimulationResult(np.zeros(4), slack=np.array([0, 0, 1, 1], bool))
    assert not slack.success and "first at sample 2" in slack.message
    assert slack.first_slack_index == 2 and slack.any_slack
    t = np.arange(0.0, 1.0, 1e-3)
    res = _plants()[0].simulate(t, np.sin(2 * np.pi * t))
    back = pickle.loads(pickle.dumps(res))
    np.testing.assert_array_equal(back, res)
    np.testing.assert_array_equal(back.q_in, res.q_in)
    assert back.success and back.nonconverged == res.nonconverged
    with pytest.raises(AttributeError, match="has no attribute 'q_nope'"):
        _ = res.q_nope


def test_plot_draws_input_and_output():
    t = np.arange(0.0, 1.0, 1e-3)
    x = np.sin(2 * np.pi * t)
    res = BoucWenBacklash().simulate(t, x)
    fig = res.plot()
    left, right = fig.axes
    np.testing.assert_array_equal(left.lines[1].get_ydata(), res.output)
    np.testing.assert_array_equal(right.lines[0].get_xdata(), x)
    assert left.get_xlabel() == "t (s)"
    matplotlib.pyplot.close(fig)


def test_simulate_binds_its_arguments_and_names_an_unknown_keyword():
    # t and x by keyword give the same result; an unknown keyword is a TypeError naming it,
    # before anything is simulated, for a model's and a plant's simulate alike
    t = np.arange(0.0, 1.0, 1e-3)
    x = np.sin(2 * np.pi * t)
    for model in (BoucWenBacklash(), Scaled(Backlash(), output_gain=2.0), FirstOrderLag()):
        by_name = model.simulate(x=x, t=t)
        np.testing.assert_array_equal(by_name, model.simulate(t, x))
        np.testing.assert_array_equal(by_name.t, t)
        np.testing.assert_array_equal(by_name.input, x)
        with pytest.raises(TypeError, match="'no_such_keyword'"):
            model.simulate(t, x, no_such_keyword=1)
    with pytest.raises(TypeError, match="'no_such_keyword'"):
        _plants()[0].simulate(t, x, no_such_keyword=1)


def test_an_unknown_result_field_is_a_type_error_naming_it():
    with pytest.raises(TypeError, match="'mesured'.*measured"):
        ts.SimulationResult(np.zeros(3), mesured=np.zeros(3))
    ok = ts.SimulationResult(np.zeros(3), measured=np.ones(3))
    np.testing.assert_array_equal(ok.measured, np.ones(3))


def test_motor_simulate_returns_the_result_type_too():
    t = np.linspace(0.0, 1.0, 201)
    command = np.sin(2 * np.pi * t)
    motor = ts.Motor.position(bandwidth_hz=5.0)
    res = motor.simulate(t, command)
    assert isinstance(res, ts.SimulationResult) and res.success
    np.testing.assert_array_equal(res.t, t)
    np.testing.assert_array_equal(res.input, command)
    # the same samples as stepping the motor by hand
    fresh = ts.Motor.position(bandwidth_hz=5.0)
    by_hand = [fresh.step(u, 0.0 if k == 0 else t[k] - t[k - 1]) for k, u in enumerate(command)]
    np.testing.assert_allclose(np.asarray(res), by_hand, rtol=0, atol=1e-15)


def test_one_name_per_quantity_across_the_run_results():
    """bench.Result's motor angle is q_motor (as a plant's result names it), a scenario's
    metrics a field (a dict), a coupled run's command and q_out also input and output."""
    from tendonsheath.bench.run import Result
    from tendonsheath.bench.scenarios.common import ScenarioResult
    from tendonsheath.plant.coupled import CoupledSimulation

    n = np.arange(4.0)
    run = Result("none", n, n, n + 1, n, n, 2 * n, n < 0, n < 0, 0.0, {"rmse": 1.0})
    np.testing.assert_array_equal(run.q_motor, 2 * n)
    assert not hasattr(run, "motor")  # the old name was removed (0.x)
    scenario = ScenarioResult("s", "S", "", {}, {"none": run}, [], {})
    assert scenario.metrics == {"none": {"rmse": 1.0}}
    assert type(scenario.metrics) is dict  # no longer callable as the old metrics()
    coupled = CoupledSimulation(n, n + 1, n, n, n + 2, n)
    assert coupled.input is coupled.command and coupled.output is coupled.q_out
