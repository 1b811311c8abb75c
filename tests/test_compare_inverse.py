"""compare_models' offline inverse error: checked against a direct computation, shown in the
table, and telling a model that predicts well from one that compensates well."""

import math

import numpy as np
import pytest
from _realdata_helpers import plant_log

import tendonsheath as ts
from tendonsheath.apps.inverse_error import desired_from_record, offline_inverse
from tendonsheath.compensate import InverseFeedforward
from tendonsheath.models import Backlash

FAST = {"maxiter": 15, "popsize": 10}


@pytest.fixture(scope="module")
def comparison():
    t, x, y = plant_log(n=400)
    cmp = ts.compare_models([(t, x, y)], models=["backlash", "bwb+poly3"], validate=0.4, **FAST)
    return cmp, (t, x, y)


def test_the_inverse_column_equals_a_direct_computation(comparison):
    """One split: the held-out last 40 %, the training fit's inverse run over the recording;
    the column is the rmse of its commands against the recorded input there."""
    cmp, (t, x, y) = comparison
    start = int(np.searchsorted(t, t[0] + 0.6 * (t[-1] - t[0])))
    for name in ("Backlash", "BoucWenBacklash+poly3"):
        model = cmp.fits[name].model
        desired = desired_from_record(t, y)
        rate = np.max(np.abs(np.diff(desired)) / np.diff(t))
        ff = InverseFeedforward(model, smoothing=0.03 * rate)
        commands = ff.command(t, desired)
        e = (commands - x)[start:]
        row = cmp.row(name)
        assert row["inv_rmse"] == pytest.approx(math.sqrt(np.mean(e * e)), rel=1e-12)
        assert row["inv_nrmse"] == pytest.approx(row["inv_rmse"] / np.ptp(x[start:]), rel=1e-12)
    affine = cmp.row("affine")
    b, a = np.polyfit(x[:start], y[:start], 1)[::-1]
    e = ((desired_from_record(t, y) - b) / a - x)[start:]
    assert affine["inv_rmse"] == pytest.approx(math.sqrt(np.mean(e * e)), rel=1e-9)
    assert affine["inv_ratio_to_affine"] == 1.0


def test_the_table_prints_the_inverse_column(comparison):
    cmp, _ = comparison
    text = cmp.text()
    assert "inv nrmse" in text and "inverse:" in text
    for row in cmp.table:
        assert math.isfinite(row["inv_nrmse"]) and 0.0 <= row["inv_out_of_range"] <= 1.0


def test_a_backlash_inverse_recovers_the_input_of_its_own_output():
    """Self-class: a Backlash's offline inverse on that Backlash's noise-free output gives the
    input back, up to the smoothing of the reversals (the column's floor)."""
    t = np.arange(0.0, 20.0, 1e-2)
    x = 0.8 * np.sin(2 * np.pi * 0.1 * t)
    model = Backlash(B_r=0.1, B_l=0.1)
    y = np.asarray(model.simulate(t, x))
    commands, flags = offline_inverse(model, t, y)
    # away from the reversals' dead zone and from the ends of the zero-phase filter
    moving = (np.abs(np.gradient(y, t)) > 0.05) & (t > 2.0) & (t < 18.0)
    # measured 0.019: the low-pass rounds the output's corners where it leaves the dead zone
    assert np.max(np.abs(commands - x)[moving]) < 0.03
    assert not np.any(flags)  # no range given: nothing held


def test_an_inverse_that_leaves_the_range_is_flagged():
    """A model identified on a narrow input range, asked for outputs far beyond it, holds its
    commands at the range and says so in the share of cycles it flags."""
    t = np.arange(0.0, 10.0, 1e-2)
    model = Backlash(B_r=0.05, B_l=0.05)
    model.input_range = (-0.2, 0.2)
    y = 1.0 * np.sin(2 * np.pi * 0.2 * t)
    commands, flags = offline_inverse(model, t, y)
    assert np.max(np.abs(commands)) <= 0.2 + 0.1 * 0.4 + 1e-12
    assert np.mean((flags & ts.Status.OUT_OF_RANGE) != 0) > 0.3
