"""Behaviour every hysteresis model shares: streaming, persistence, bad input."""

import json

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import models
from tendonsheath.models._bound import model_kinds

ALL_MODELS = [
    models.Backlash(c_r=1.1, c_l=0.9, B_r=0.12, B_l=0.08),
    models.BoucWenBacklash(c_r=1.0, c_l=0.95, B_r=0.1, B_l=0.15, n=6, sigma=1.5),
    models.BoucWen(A=1.2, beta=1.5, gamma=-0.5, n=2.0, alpha=0.2, k=0.8),
    models.PrandtlIshlinskii([0.0, 0.1, 0.3], [0.6, 0.3, -0.1]),
    models.PrandtlIshlinskiiInverse([0.0, 0.1, 0.3], [0.6, 0.3, 0.2]),
    models.HystereticOscillator(m=0.5, c=0.3, k=2.0, alpha=1.5, beta=2.0, gamma=0.7, delta=0.2),
    models.Polynomial(coefficients=[0.1, 0.9, -0.2, 0.05]),
    models.Chain(models.BoucWenBacklash(n=5), models.Polynomial(3, odd=True)),
    models.GeneralizedPrandtlIshlinskii(
        rising=(1.2, 1.5, 0.1, -0.1), falling=(1.0, 2.0, -0.1, 0.0)
    ),
    models.GeneralizedPrandtlIshlinskiiInverse(rising=(1.2, 1.5, 0.0, 0.0)),
]
# every other model of the core's list (model_list.hpp), with its defaults, but those that
# take a second input (their own tests: test_curve_angle_model.py)
_SHOWN = {type(m).__name__ for m in ALL_MODELS} | {"CurveAngleModel"}
ALL_MODELS += [getattr(models, k["kind"])() for k in model_kinds() if k["kind"] not in _SHOWN]
RATE_INDEPENDENT = [m for m in ALL_MODELS if m.rate_independent]


def _signal(n=3000, seed=0):
    r = np.random.default_rng(seed)
    t = np.cumsum(r.uniform(0.5e-3, 1.5e-3, n))
    x = np.cumsum(r.normal(0.0, 0.02, n)) + 0.5 * np.sin(2 * np.pi * 0.5 * t)
    return t, x


@pytest.mark.parametrize("model", ALL_MODELS, ids=lambda m: type(m).__name__)
def test_streaming_equals_batch(model):
    t, x = _signal()
    batch = model.simulate(t, x)
    model.reset()
    dts = np.r_[0.0, np.diff(t)]
    stream = np.array([model.step(xk, dk) for xk, dk in zip(x, dts, strict=True)])
    np.testing.assert_array_equal(stream, batch)
    # simulate() does not disturb the streaming state
    twin = ts.load_model(model.to_json())
    twin.reset()
    for xk, dk in zip(x, dts, strict=True):
        twin.step(xk, dk)
    model.simulate(t, x[::-1].copy())
    assert model.step(x[0], 1e-3) == twin.step(x[0], 1e-3)


@pytest.mark.parametrize("model", ALL_MODELS, ids=lambda m: type(m).__name__)
def test_json_round_trip_is_exact(model, tmp_path):
    path = tmp_path / "m.json"
    model.to_json(path)
    data = json.loads(path.read_text())
    assert data["format"] == "tendonsheath.model"
    assert data["version"] == 1
    loaded = ts.load_model(path)
    assert type(loaded) is type(model)
    assert loaded.params == model.params
    assert loaded.options == model.options
    t, x = _signal(500)
    np.testing.assert_array_equal(loaded.simulate(t, x), model.simulate(t, x))
    assert ts.load_model(model.to_json()) == model


def test_load_model_rejects_bad_files(tmp_path):
    with pytest.raises(ValueError, match="version"):
        ts.load_model({"format": "tendonsheath.model", "version": 99, "model": "Backlash"})
    with pytest.raises(ValueError, match="unknown model"):
        ts.load_model({"format": "tendonsheath.model", "version": 1, "model": "Nope"})
    with pytest.raises(ValueError, match="not a tendonsheath model"):
        ts.load_model({"hello": 1})
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="not valid JSON"):
        ts.load_model(bad)
    with pytest.raises(ValueError, match="not found"):
        ts.load_model(tmp_path / "missing.json")


@pytest.mark.parametrize("model", ALL_MODELS, ids=lambda m: type(m).__name__)
def test_bad_input_gets_a_clear_error(model):
    t = np.linspace(0.0, 1.0, 11)
    x = np.sin(t)
    with pytest.raises(ValueError, match=r"x\[3\] is not finite"):
        model.simulate(t, np.where(np.arange(11) == 3, np.nan, x))
    with pytest.raises(ValueError, match=r"not finite"):
        model.simulate(t, np.where(np.arange(11) == 5, np.inf, x))
    with pytest.raises(ValueError, match="strictly increasing"):
        model.simulate(np.r_[t[:5], t[4], t[6:]], x)
    with pytest.raises(ValueError, match="time t\\[2\\] is not finite"):
        model.simulate(np.where(np.arange(11) == 2, np.nan, t), x)
    with pytest.raises(ValueError, match="different lengths"):
        model.simulate(t[:-1], x)
    with pytest.raises(ValueError, match="empty"):
        model.simulate([], [])
    with pytest.raises(ValueError, match="1-D"):
        model.simulate(None if model.rate_independent else t, np.ones((3, 2)))
    with pytest.raises(ValueError, match="numbers"):
        model.simulate(t, ["a"] * 11)


@pytest.mark.parametrize(
    "cls, bad",
    [
        (models.Backlash, {"c_r": -1.0}),
        (models.Backlash, {"B_l": np.nan}),
        (models.BoucWenBacklash, {"sigma": 0.1}),
        (models.BoucWenBacklash, {"n": 0.5}),
        (models.BoucWenBacklash, {"rho": -3.0}),
        (models.BoucWen, {"gamma": 2.0}),
        (models.BoucWen, {"alpha": 1.5}),
        (models.HystereticOscillator, {"m": 0.0}),
        (models.HystereticOscillator, {"nu": 0.5}),
        (models.HystereticOscillator, {"substeps": 0}),
    ],
)
def test_out_of_range_parameters_are_named(cls, bad):
    name = next(iter(bad))
    with pytest.raises(ValueError, match=name):
        cls(**bad)


def test_unknown_parameter_and_wrong_type():
    with pytest.raises(ValueError, match="unknown parameter"):
        models.BoucWenBacklash.from_dict(
            {
                "format": "tendonsheath.model",
                "version": 1,
                "model": "BoucWenBacklash",
                "params": {"foo": 1.0},
            }
        )
    with pytest.raises(ValueError, match="input_interpolation"):
        models.HystereticOscillator(input_interpolation="cubic")
    with pytest.raises(ValueError, match="same length"):
        models.PrandtlIshlinskii([0.0, 0.1], [1.0])
    with pytest.raises(ValueError, match="strictly increasing"):
        models.PrandtlIshlinskii([0.0, 0.2, 0.1], [1.0, 0.1, 0.1])


def test_rate_dependent_model_needs_time():
    with pytest.raises(ValueError, match="t is required"):
        models.HystereticOscillator().simulate(None, [0.0, 1.0])


@pytest.mark.parametrize("model", RATE_INDEPENDENT, ids=lambda m: type(m).__name__)
def test_rate_independence_same_loop_at_01_and_10_hz(model):
    """The same input path traversed 100x faster gives the same loop."""
    cycles, per_cycle = 3, 400
    phase = np.linspace(0.0, 2 * np.pi * cycles, cycles * per_cycle)
    x = 0.8 * np.sin(phase)
    slow = model.simulate(phase / (2 * np.pi * 0.1), x)
    fast = model.simulate(phase / (2 * np.pi * 10.0), x)
    np.testing.assert_array_equal(slow, fast)
    # and a finer sampling of the same path traces the same loop
    fine_phase = np.linspace(0.0, 2 * np.pi * cycles, cycles * per_cycle * 8)
    fine = model.simulate(fine_phase, 0.8 * np.sin(fine_phase))
    coarse_on_fine = np.interp(fine_phase, phase, slow)
    last = fine_phase > 2 * np.pi * (cycles - 1)
    span = np.ptp(slow)
    assert np.max(np.abs(fine[last] - coarse_on_fine[last])) < 0.02 * span


def test_with_params_changes_only_what_is_asked():
    m = models.BoucWenBacklash(B_r=0.1, B_l=0.2, n=5)
    m2 = m.with_params(n=9)
    assert m2.params["n"] == 9 and m2.params["B_l"] == 0.2 and m.params["n"] == 5
