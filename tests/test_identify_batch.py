"""The batched C++ evaluation agrees with plain simulation, and Fit's extras work."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.models import Backlash, BoucWenBacklash, HystereticOscillator


def _recordings(model, n=800, count=2, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for i in range(count):
        t = np.arange(n) * 0.01
        x = np.sin(2 * np.pi * (0.3 + 0.2 * i) * t) * (1 + 0.3 * i)
        y = model.simulate(t, x) + 0.01 * rng.standard_normal(n)
        out.append((t, x, y))
    return out


def _pack(recs, warmup):
    t = np.concatenate([r[0] for r in recs])
    x = np.concatenate([r[1] for r in recs])
    y = np.concatenate([r[2] for r in recs])
    return core.RecordingSet(t, x, y, None, [r[1].size for r in recs], [warmup] * len(recs))


@pytest.mark.parametrize("workers", [1, 2, 0])
def test_population_cost_equals_python_sse(workers):
    truth = BoucWenBacklash(B_r=0.1, B_l=0.05, n=3.0)
    recs = _recordings(truth)
    rs = _pack(recs, warmup=50)
    rng = np.random.default_rng(1)
    pop = []
    for _ in range(7):
        p = dict(truth.params)
        p.update(c_r=rng.uniform(0.8, 1.2), B_r=rng.uniform(0, 0.2), rho=rng.uniform(5, 30))
        pop.append(p)
    rows = np.array([[p[k] for k in BoucWenBacklash.param_names] * len(recs) for p in pop])
    costs = core.population_cost_BoucWenBacklash(truth.params_struct(), rows, rs, workers)
    for p, c in zip(pop, costs, strict=True):
        m = BoucWenBacklash(**p)
        want = sum(np.sum((y[50:] - m.simulate(t, x)[50:]) ** 2) for t, x, y in recs)
        assert c == pytest.approx(want, rel=1e-12)
    sims = core.population_simulate_BoucWenBacklash(truth.params_struct(), rows, rs, workers)
    m = BoucWenBacklash(**pop[3])
    assert np.array_equal(sims[3], np.concatenate([m.simulate(t, x) for t, x, _ in recs]))


def test_invalid_members_cost_infinity_and_rate_dependent_uses_time():
    truth = Backlash()
    rs = _pack(_recordings(truth), 0)
    rows = np.array([[1.0, 1.0, 0.1, 0.1] * 2, [-1.0, 1.0, 0.1, 0.1] * 2])
    costs = core.population_cost_Backlash(truth.params_struct(), rows, rs, 2)
    assert np.isfinite(costs[0]) and np.isinf(costs[1])
    osc = HystereticOscillator(m=1.0, c=0.3, k=2.0, alpha=1.0)
    recs = _recordings(osc, n=300)
    rs = _pack(recs, 0)
    row = np.array([[osc.params[k] for k in HystereticOscillator.param_names] * 2])
    sim = core.population_simulate_HystereticOscillator(osc.params_struct(), row, rs, 1)[0]
    assert np.allclose(sim[:300], osc.simulate(recs[0][0], recs[0][1]), rtol=0, atol=1e-14)


def test_separable_cost_is_the_least_squares_residual():
    truth = BoucWenBacklash(c_r=1.1, c_l=0.9, B_r=0.1, B_l=0.05, rho=15.0, n=3.0)
    recs = _recordings(truth)
    rs = _pack(recs, 20)
    v = np.array([[15.0, 1.0, 3.0], [9.0, 2.0, 5.0]])
    costs = core.separable_cost_BoucWenBacklash(truth.params_struct(), v, rs, 2)
    y = np.concatenate([r[2][20:] for r in recs])
    mask = np.concatenate([np.arange(r[1].size) >= 20 for r in recs])
    for row, cost in zip(v, costs, strict=True):
        F = core.features_BoucWenBacklash(truth.params_struct(), row, rs)[mask]
        theta, *_ = np.linalg.lstsq(F, y, rcond=None)
        assert cost == pytest.approx(np.sum((y - F @ theta) ** 2), rel=1e-6)


def test_fit_report_summary_and_json(tmp_path):
    """Fit's extras; the data come from the fitted class (self-class: not evidence of fit
    quality on a mechanism)."""
    truth = BoucWenBacklash(B_r=0.1, B_l=0.08)
    recs = _recordings(truth, n=600)
    fit = ts.identify(BoucWenBacklash, recordings=recs, warmup=30, progress=False)
    assert isinstance(fit, ts.Fit)
    assert len(fit.per_recording) == 2 and fit.n_samples == 2 * (600 - 30)
    assert 0 < fit.nrmse < 0.02 and fit.fit_percent > 95
    assert fit.evaluations > 100 and fit.seconds > 0
    assert "rmse" in fit.summary() and "B_r" in fit.summary()
    path = fit.report(tmp_path / "fit.png")
    assert path.stat().st_size > 10_000
    assert ts.load_model(fit.model.to_json()) == fit.model
    # fit % by its definition
    y = np.concatenate([r[2][30:] for r in recs])
    y_hat = np.concatenate([p[30:] for p in fit.predictions])
    want = 100 * (1 - np.linalg.norm(y - y_hat) / np.linalg.norm(y - y.mean()))
    assert fit.fit_percent == pytest.approx(want)


def test_progress_bar_does_not_break_a_fit():
    truth = Backlash(B_r=0.1, B_l=0.1)
    (t, x, y), *_ = _recordings(truth, n=400, count=1)
    fit = ts.identify(Backlash, t, x, y, progress=True, maxiter=5)
    assert fit.generations <= 5
