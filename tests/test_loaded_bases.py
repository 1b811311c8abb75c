"""Loaded(base) for every hysteresis base ``identify`` supports, on a simulated loaded plant
outside every model class (tests/_loaded_plant.py: a pull-pull pair with capstan friction,
viscosity, creep, an unequal pair and a dynamic joint under constant and spring loads): the
load term improves the held-out rmse by a stated factor, the weights of a (generalized)
Prandtl-Ishlinskii base stay >= 0 (its inverse exists) and the fit is deterministic."""

import warnings

import numpy as np
import pytest
from _loaded_plant import TRAIN, loaded_runs

import tendonsheath as ts

#: short searches (the staged fit needs only the base's basin) and four plays for the
#: weighted bases (each candidate simulates the base once per weight); the hysteretic
#: oscillator is a force-driven model that its staged path refuses for a position input
SEARCH = {"seed": 0, "progress": False, "maxiter": 15, "popsize": 8}
OPTIONS = {
    "PrandtlIshlinskii": {"initial": ts.models.PrandtlIshlinskii.uniform(1.0, 4)},
    "GeneralizedPrandtlIshlinskii": {
        "initial": ts.models.GeneralizedPrandtlIshlinskii(
            thresholds=[0.0, 0.25, 0.5, 0.75], weights=[1.0, 1.0, 1.0, 1.0]
        )
    },
    "HystereticOscillator": {"strategy": "search"},
}
BASES = {
    "Backlash": lambda: ts.models.Backlash,
    "BoucWen": lambda: ts.models.BoucWen,
    "BoucWenBacklash": lambda: ts.models.BoucWenBacklash,
    "PrandtlIshlinskii": lambda: ts.models.PrandtlIshlinskii,
    "GeneralizedPrandtlIshlinskii": lambda: ts.models.GeneralizedPrandtlIshlinskii,
    "HystereticOscillator": lambda: ts.models.HystereticOscillator,
    "Chain": lambda: ts.models.Chain(ts.models.BoucWenBacklash(), ts.models.Polynomial(3)),
}
#: how many times lower the held-out rmse must be with the load than without: measured
#: 4.6-5.5 for every base (0.018-0.019 rad against 0.086-0.100), so 3 leaves a margin; the
#: hysteretic oscillator, a force-driven model on a position-driven drive, gains only 1.25
#: (0.108 against 0.136 rad: its search does not find the drive's loop), so it is held to
#: doing better than without the load
FACTORS = {"HystereticOscillator": 1.0}


@pytest.fixture(scope="module")
def runs():
    return loaded_runs(0, seconds=4.0, rate=20.0, elements=12)


def _held_out_rmse(runs, predict) -> float:
    err = [predict(g) - g.y for k, g in runs.items() if k not in TRAIN]
    return float(np.sqrt(np.mean(np.concatenate(err) ** 2)))


def _fit(runs, name, loaded: bool):
    cls = BASES[name]()
    train = [runs[k] for k in TRAIN]
    kw = {**SEARCH, **OPTIONS.get(name, {})}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if loaded:
            return ts.identify(ts.models.Loaded(cls), recordings=train, **kw)
        return ts.identify(cls, recordings=[(g.t, g.x, g.y) for g in train], **kw)


@pytest.mark.parametrize("name", list(BASES))
def test_the_load_term_improves_every_base_on_held_out_loads(runs, name):
    """Trained on three constant loads and a spring, predicting two other constant loads and
    two other springs: the Loaded model's rmse is under a third of the base's without the
    load (the oscillator: lower than without it); a weighted base's weights are >= 0, so its
    inverse exists; a second fit is the same model."""
    fit = _fit(runs, name, loaded=True)
    alone = _fit(runs, name, loaded=False).model
    m = fit.model
    loaded = _held_out_rmse(runs, lambda g: m.simulate(g.t, g.x, load=g.load))
    plain = _held_out_rmse(runs, lambda g: alone.simulate(g.t, g.x))
    print(f"{name}: held-out rmse {loaded:.4f} with the load, {plain:.4f} without")
    assert loaded < plain / FACTORS.get(name, 3.0), (loaded, plain)
    base = m.base.inner if isinstance(m.base, ts.models.Scaled) else m.base
    if "weights" in base.params:
        assert min(base.params["weights"]) >= 0.0
        assert base.params["weights"][0] > 0.0
        ts.compensate.LoadCompensated(m)  # the inverse exists
    assert _fit(runs, name, loaded=True).model == m  # deterministic


@pytest.mark.parametrize("seed", range(3))
def test_weights_offset_and_gain_solved_exactly_for_a_weighted_base(seed):
    """On a Loaded(Scaled(PrandtlIshlinskii)) of drawn non-negative weights (one of them 0),
    the linear stage recovers the weights, the output offset and the stretch gain to 1e-6
    (the regressors are exact: the output is linear in them), whatever weights it starts from."""
    from importlib import import_module

    problem_module = import_module("tendonsheath.identify.loaded_problem")
    make_recordings = import_module("tendonsheath.identify.data").make_recordings
    rng = np.random.default_rng(seed)
    weights = rng.uniform(0.1, 1.0, 5)
    weights[rng.integers(1, 5)] = 0.0
    pi = ts.models.PrandtlIshlinskii(np.linspace(0.0, 0.4, 5), weights)
    truth = ts.models.Loaded(
        ts.models.Scaled(pi, output_offset=rng.uniform(-1, 1), output_gain=-2.0),
        gain=rng.uniform(-3, 3),
        slack=0.05,
        slack_load=0.5,
        friction=0.1,
    )
    t = np.arange(400) * 0.01
    x = np.sin(2 * np.pi * 0.7 * t) + 0.3 * np.sin(2 * np.pi * 2.1 * t)
    load = rng.uniform(-1, 1) + 0.5 * np.sin(2 * np.pi * 0.3 * t)
    y = np.asarray(truth.simulate(t, x, load=load))
    start = truth.base.with_params(**{"inner.weights": [1.0] * 5, "output_offset": 0.0})
    recs = make_recordings(recordings=[(t, x, y)])
    problem = problem_module.Problem(start, recs, [load], 0, {}, joint=False)
    model = problem.model(problem.start(truth.terms))
    # the normal equations square the condition: 1e-8 measured, 1e-6 leaves a margin
    np.testing.assert_allclose(model.base.params["inner.weights"], weights, atol=1e-6)
    assert model.base.params["output_offset"] == pytest.approx(truth.base.params["output_offset"])
    assert model.terms["gain"] == pytest.approx(truth.terms["gain"])
