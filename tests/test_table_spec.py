"""A model with no identification spec of its own is identified from its parameter table
(identify/specs.py TableSpec): the bounds follow from each parameter's unit and range."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.identify import specs
from tendonsheath.identify.specs import BacklashSpec, Scale, TableSpec, spec_for


def _scale(rng):
    return Scale(
        x_range=float(rng.uniform(0.01, 10.0)),
        y_range=float(rng.uniform(0.01, 10.0)),
        slope=float(rng.uniform(0.05, 20.0)),
        duration=None,
        sample_time=None,
    )


def test_table_bounds_of_backlash_equal_its_own_spec_over_random_scales():
    # Backlash's units (output/input slopes, input-unit bands) give its hand-written bounds
    rng = np.random.default_rng(7)
    table, own = TableSpec(ts.models.Backlash), BacklashSpec()
    for _ in range(50):
        s = _scale(rng)
        mine, theirs = table.bounds(s, {}), own.bounds(s, {})
        assert mine.keys() == theirs.keys()
        for name in mine:
            assert mine[name] == pytest.approx(theirs[name]), name
    assert table.log_names == frozenset()


def test_table_bounds_follow_the_units_and_stay_inside_the_valid_range():
    rng = np.random.default_rng(8)
    spec = TableSpec(ts.models.BoucWenBacklash)
    rows = {f["name"]: f for f in ts.models.BoucWenBacklash._core_params.fields()}
    for _ in range(50):
        s = _scale(rng)
        b = spec.bounds(s, {})
        assert b["rho"] == pytest.approx((0.5 / s.x_range, 500.0 / s.x_range))
        assert b["B_r"] == pytest.approx((0.0, 0.5 * s.x_range))
        for name, (lo, hi) in b.items():
            assert rows[name]["lo"] <= lo < hi <= rows[name]["hi"], name
    assert b["sigma"] == (0.5, 10.0)  # a decade above the default 1, clipped at its bound 0.5
    assert spec.log_names == {"rho", "sigma", "n"}


def test_a_model_without_a_spec_is_identified_from_its_table(monkeypatch):
    monkeypatch.delitem(specs.SPECS, ts.models.Backlash)
    assert isinstance(spec_for(ts.models.Backlash), TableSpec)
    true = ts.models.Backlash(c_r=1.3, c_l=0.9, B_r=0.04, B_l=0.07)
    t = np.linspace(0.0, 20.0, 4001)
    x = 0.6 * np.sin(2 * np.pi * 0.25 * t) * (1.0 - 0.6 * t / t[-1])
    y = np.asarray(true.simulate(t, x))
    fit = ts.identify(ts.models.Backlash, t, x, y, seed=1)
    # noise-free data of the model's own class: the search finds it (rmse 1e-4 of the span
    # leaves room over the optimiser's tolerance)
    assert fit.rmse < 1e-4 * np.ptp(y)
    for name, value in true.params.items():
        assert fit.model.params[name] == pytest.approx(value, rel=1e-2, abs=1e-3), name


def test_a_table_of_non_numbers_needs_a_spec_of_its_own(monkeypatch):
    monkeypatch.delitem(specs.SPECS, ts.models.PrandtlIshlinskii)
    with pytest.raises(ValueError, match="'thresholds' is not a number"):
        spec_for(ts.models.PrandtlIshlinskii)
