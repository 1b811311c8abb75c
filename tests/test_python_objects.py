"""Models, compensators, plants and Fits behave like Python objects (issue 27, step 17 item 5):
they pickle (multiprocessing, joblib, caches) and deep-copy with identical outputs, a copy never
shares the C++ engine with its original, and an attribute the class does not declare raises
instead of being silently added."""

import copy
import pickle

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import compensate, models
from tendonsheath.models import Backlash, BoucWenBacklash

DT = 1e-3
N = 120  # samples per stream: enough to cross reversals of the inputs below


def _u(i):
    """A deterministic input with reversals (two turns in N samples)."""
    return 0.8 * np.sin(0.11 * i) + 0.1 * np.sin(0.53 * i)


def _single(obj, i):
    return obj.step(_u(i), DT)


def _with_angle(obj, i):
    return obj.step(_u(i), DT, curve_angle=1.2)


def _with_load(obj, i):
    return obj.step(_u(i), DT, 0.3 * np.cos(0.07 * i))


def _two_joints(obj, i):
    return obj.step(np.array([_u(i), -0.5 * _u(i + 7)]), DT)


def _loop(obj, i):  # y_d and a measured signal (tip or motor angle)
    return obj.step(_u(i), 0.9 * _u(i - 3), DT)


def _adaptive(obj, i):
    return obj.step(_u(i), 0.9 * _u(i - 3), 1.1 * _u(i - 1), DT)


def _plant(obj, i):
    return obj.step(0.02 * _u(i), DT)


def _sensor(obj, i):
    return obj.measure(_u(i), dt=DT)


def _coupled_model(obj, i):  # no streaming: the whole record up to sample i
    t = DT * np.arange(i + 1)
    x = np.column_stack([_u(np.arange(i + 1)), -_u(np.arange(i + 1) + 3)])
    return obj.simulate(t, x)[-1]


def _trial(obj, i):  # one ILC trial (while it learns): the next table from a measured tip
    if obj.stopped:
        return float(np.sum(obj.table))
    record = obj.update(0.9 * obj.reference + 0.01 * np.sin(50.0 * obj.t + len(obj.history)))
    return float(record.rmse) + float(np.sum(obj.table))


def _fit(obj, i):
    return obj.model.step(_u(i), DT)


def _route():
    return ts.Route.uniform(0.5, 2.0)


def _plant_kwargs():
    return {"friction": 0.1, "stiffness": 2e4, "elements": 8}


def _ilc_learner():
    t = DT * np.arange(40)
    ff = compensate.InverseFeedforward(Backlash(B_r=0.1, B_l=0.1))
    return compensate.IterativeLearning(ff, t, 0.5 * np.sin(20.0 * t), max_trials=50)


def _a_fit():
    t = DT * np.arange(300)
    x = np.sin(2 * np.pi * 5.0 * t)
    y = np.asarray(Backlash(B_r=0.1, B_l=0.05).simulate(t, x))
    return ts.identify(Backlash, t, x, y, seed=0, maxiter=3, workers=1)


MODELS = {
    "Backlash": (lambda: Backlash(c_r=1.1, c_l=0.9, B_r=0.12, B_l=0.08), _single),
    "BoucWenBacklash": (lambda: BoucWenBacklash(B_r=0.1, B_l=0.15, n=6, sigma=1.5), _single),
    "BoucWen": (lambda: models.BoucWen(A=1.2, beta=1.5, gamma=-0.5, alpha=0.2), _single),
    "PrandtlIshlinskii": (
        lambda: models.PrandtlIshlinskii([0, 0.1, 0.3], [0.6, 0.3, -0.1]),
        _single,
    ),
    "PrandtlIshlinskiiInverse": (
        lambda: models.PrandtlIshlinskiiInverse([0, 0.1, 0.3], [0.6, 0.3, 0.2]),
        _single,
    ),
    "GeneralizedPrandtlIshlinskii": (
        lambda: models.GeneralizedPrandtlIshlinskii(rising=(1.2, 1.5, 0.1, -0.1)),
        _single,
    ),
    "GeneralizedPrandtlIshlinskiiInverse": (
        lambda: models.GeneralizedPrandtlIshlinskiiInverse(rising=(1.2, 1.5, 0.0, 0.0)),
        _single,
    ),
    "HystereticOscillator": (
        lambda: models.HystereticOscillator(m=0.5, c=0.3, k=2.0, alpha=1.5, beta=2.0, gamma=0.7),
        _single,
    ),
    "Polynomial": (lambda: models.Polynomial(coefficients=[0.1, 0.9, -0.2, 0.05]), _single),
    "Chain": (
        lambda: models.Chain(BoucWenBacklash(n=5), models.FirstOrderLag(time_constant=0.01)),
        _single,
    ),
    "FirstOrderLag": (lambda: models.FirstOrderLag(time_constant=0.01), _single),
    "SecondOrderLag": (lambda: models.SecondOrderLag(frequency=20.0, damping=0.4), _single),
    "Scaled": (
        lambda: models.Scaled(Backlash(B_r=0.1), input_scale=1.5, output_gain=-0.8),
        _single,
    ),
    "PlantModel": (lambda: models.PlantModel(friction_angle=1.0, backlash=0.1), _single),
    "CurveAngleModel": (lambda: models.CurveAngleModel(load_stiffness=100.0), _with_angle),
    "AngleDependent": (
        lambda: models.AngleDependent(
            "Backlash",
            {"c_r": [1.0], "c_l": [1.0], "B_r": [0.1, 0.02], "B_l": [0.1, 0.02]},
            laws={"B_r": "linear", "B_l": "linear"},
        ),
        _with_angle,
    ),  # fmt: skip
    "Loaded": (lambda: models.Loaded(Backlash(B_r=0.1, B_l=0.1), gain=0.05), _with_load),
    "Coupled": (
        lambda: models.Coupled([Backlash(B_r=0.1), Backlash(B_l=0.1)], [[0, 0.2], [0.1, 0]]),
        _coupled_model,
    ),
}

COMPENSATORS = {
    "InverseFeedforward": (
        lambda: compensate.InverseFeedforward(BoucWenBacklash(B_r=0.1, B_l=0.15), 0.05),
        _single,
    ),
    "CurveAngleFeedforward": (
        lambda: compensate.CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=2.0),
        _single,
    ),
    "ContinuumFeedforward": (lambda: compensate.ContinuumFeedforward(mode="exact"), _single),
    "LearnedFeedforward": (
        lambda: compensate.LearnedFeedforward(
            compensate.InverseFeedforward(Backlash(B_r=0.1)), 0.01 * np.sin(np.arange(50)), DT
        ),
        _single,
    ),
    "EncoderLoop": (
        lambda: compensate.EncoderLoop(compensate.InverseFeedforward(Backlash(B_r=0.1)), kp=0.5),
        _loop,
    ),
    "TipLoop": (
        lambda: compensate.TipLoop(compensate.InverseFeedforward(Backlash()), kp=0.3, ki=5.0),
        _loop,
    ),
    "AdaptiveController": (
        lambda: compensate.AdaptiveController(Backlash(B_r=0.1, B_l=0.1)),
        _adaptive,
    ),
    "LoadCompensated": (
        lambda: compensate.LoadCompensated(
            models.Loaded(Backlash(B_r=0.1, B_l=0.1), gain=0.05), smoothing=0.02
        ),
        _with_load,
    ),
    "CoupledFeedforward": (
        lambda: compensate.CoupledFeedforward(
            models.Coupled([Backlash(B_r=0.1), Backlash(B_l=0.1)], [[0, 0.2], [0.1, 0]])
        ),
        _two_joints,
    ),
    "IterativeLearning": (_ilc_learner, _trial),
}

PLANTS = {
    "SingleTendonPlant": (lambda: ts.SingleTendonPlant(_route(), **_plant_kwargs()), _plant),
    "PullPullPlant": (
        lambda: ts.PullPullPlant(
            _route(),
            **_plant_kwargs(),
            motor=ts.Motor.position(bandwidth_hz=30.0),
            sensor=ts.Sensor(resolution=1e-4, noise_std=1e-4, seed=3),
        ),
        _plant,
    ),  # fmt: skip
    "ContinuumPlant": (lambda: ts.ContinuumPlant(elements=6), _plant),
    "CoupledPlant": (
        lambda: ts.CoupledPlant(
            [ts.SingleTendonPlant(_route(), **_plant_kwargs()) for _ in range(2)],
            [[0.0, 0.1], [0.2, 0.0]],
        ),
        _two_joints,
    ),
    "Motor": (lambda: ts.Motor.position(bandwidth_hz=30.0), _plant),
    "Sensor": (lambda: ts.Sensor(resolution=1e-3, noise_std=1e-3, seed=7, delay=2e-3), _sensor),
}

CASES = {**MODELS, **COMPENSATORS, **PLANTS}
STREAMING = {k: v for k, v in CASES.items() if k not in ("Coupled", "IterativeLearning")}


def _stream(obj, step, start=0, n=N):
    return np.array([step(obj, i) for i in range(start, start + n)], dtype=float)


def _fresh_and_stepped(name, k=N // 2):
    factory, step = CASES[name]
    obj = factory()
    _stream(obj, step, n=k)
    return obj, step


@pytest.mark.parametrize("name", sorted(CASES))
def test_pickle_gives_an_equal_object_at_rest(name):
    """Pickled, the object loads with its configuration: from rest its outputs are the
    original's exactly (the original also from rest)."""
    factory, step = CASES[name]
    original = factory()
    again = pickle.loads(pickle.dumps(original))
    assert type(again) is type(original)
    np.testing.assert_array_equal(_stream(again, step), _stream(original, step))


@pytest.mark.parametrize("name", sorted(STREAMING))
def test_pickle_mid_stream_arrives_at_rest(name):
    """The documented choice: the streaming state of a running engine is not pickled, so a
    running object pickles to an equal one at rest (as after reset()), not to its state."""
    running, step = _fresh_and_stepped(name)
    again = pickle.loads(pickle.dumps(running))
    fresh = CASES[name][0]()
    np.testing.assert_array_equal(_stream(again, step), _stream(fresh, step))


@pytest.mark.parametrize("name", sorted(CASES))
def test_deepcopy_mid_stream_continues_identically(name):
    running, step = _fresh_and_stepped(name)
    twin = copy.deepcopy(running)
    np.testing.assert_array_equal(_stream(twin, step, N // 2), _stream(running, step, N // 2))


@pytest.mark.parametrize("name", sorted(CASES))
def test_copy_does_not_share_state(name):
    """copy.copy carries the state along but is independent: stepping it leaves the original
    exactly where it was (a reference deep copy, taken at the same moment, tells where)."""
    running, step = _fresh_and_stepped(name)
    shallow, reference = copy.copy(running), copy.deepcopy(running)
    copied = _stream(shallow, step, N // 2)
    original = _stream(running, step, N // 2)
    np.testing.assert_array_equal(original, _stream(reference, step, N // 2))
    np.testing.assert_array_equal(copied, original)


@pytest.mark.parametrize("name", sorted(CASES))
def test_an_unknown_attribute_raises(name):
    obj = CASES[name][0]()
    with pytest.raises(AttributeError, match=f"{type(obj).__name__} has no attribute 'B_rr'"):
        obj.B_rr = 0.5
    assert "B_rr" not in vars(obj)


def test_the_message_names_the_parameters():
    with pytest.raises(AttributeError, match=r"parameters are \['c_r', 'c_l', 'B_r', 'B_l'\]"):
        Backlash().Br = 0.5  # a misspelt parameter: nothing would read it
    model = Backlash()
    model.input_range = (-1.0, 1.0)  # declared attributes stay settable
    model._private = 1  # and private names, for the package's own use
    assert model.input_range == (-1.0, 1.0)


def test_a_fit_pickles_and_deep_copies():
    fit = _a_fit()
    t = DT * np.arange(200)
    x = np.sin(2 * np.pi * 3.0 * t)
    for again in (pickle.loads(pickle.dumps(fit)), copy.deepcopy(fit), copy.copy(fit)):
        assert again.model == fit.model and again.rmse == fit.rmse
        np.testing.assert_array_equal(again.model.simulate(t, x), fit.model.simulate(t, x))
    running = copy.deepcopy(fit)
    _stream(running.model, _single, n=30)
    twin = copy.deepcopy(running)
    np.testing.assert_array_equal(
        _stream(twin.model, _single, 30), _stream(running.model, _single, 30)
    )


def test_a_fit_refuses_an_unknown_attribute_naming_its_fields():
    """fit.paramz = 1 added an attribute nothing reads; now it names the fields, and the
    fields (and private names) stay settable; a guarded Fit still pickles and copies."""
    fit = _a_fit()
    with pytest.raises(
        AttributeError, match=r"Fit has no attribute 'paramz' to set; its attributes are \['model'"
    ) as err:
        fit.paramz = 1
    assert "'rmse'" in str(err.value) and "'input_range'" in str(err.value)
    assert "paramz" not in vars(fit)
    with pytest.raises(AttributeError, match="'summary'"):
        fit.summary = "a method is not a field"
    fit.stopped_on_budget = True  # a field
    fit._calibration_runs = ["run"]  # the package's own private use
    again = pickle.loads(pickle.dumps(fit))
    assert again.stopped_on_budget and again._calibration_runs == ["run"]
    assert copy.deepcopy(fit).rmse == fit.rmse
    with pytest.raises(AttributeError, match="Fit has no attribute 'paramz'"):
        again.paramz = 1
