"""identify(time_budget=) on every path: the search and the least squares stop, the Fit says
so (stopped_on_budget, message) and holds a valid model; without a budget nothing says so."""

import numpy as np
import pytest

import tendonsheath as ts


def _data():
    t = np.arange(0.0, 8.0, 0.002)
    x = np.sin(2 * np.pi * 0.5 * t) * (1.0 - 0.05 * t)
    truth = ts.models.BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.1, rho=15, sigma=1.5, n=6)
    y = truth.simulate(t, x) + 0.003 * np.random.default_rng(0).standard_normal(t.size)
    return t, x, y


@pytest.mark.filterwarnings("ignore::tendonsheath.IdentifiabilityWarning")
@pytest.mark.parametrize(
    "model",
    [
        ts.models.BoucWenBacklash,
        ts.models.Backlash,
        ts.models.Chain(ts.models.BoucWenBacklash(), ts.models.Polynomial(3)),
    ],
    ids=["separable", "normalised", "chain"],
)
def test_budget_stops_the_fit_and_says_so(model):
    t, x, y = _data()
    full = ts.identify(model, t, x, y, progress=False, maxiter=40)
    assert not full.stopped_on_budget and "time budget" not in full.message
    short = ts.identify(model, t, x, y, progress=False, maxiter=40, time_budget=1e-4)
    assert short.stopped_on_budget
    assert "time budget" in short.message
    assert short.evaluations < full.evaluations  # it did stop early
    assert np.isfinite(short.rmse)
    assert short.to_dict()["stopped_on_budget"] is True
    assert "stopped by the time budget" in short.summary()


@pytest.mark.parametrize("bad", [0, -1.0, float("nan")])
def test_bad_budget_is_a_clear_error(bad):
    t, x, y = _data()
    with pytest.raises(ValueError, match="time_budget"):
        ts.identify(ts.models.Backlash, t, x, y, progress=False, time_budget=bad)
