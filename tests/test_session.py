"""Sessions: the shift check and the short re-calibration (tendonsheath.apps.session), on drives
whose shift is known: a model's own output, moved by an offset, a gain and a dead band."""

from __future__ import annotations

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.apps.session import REFITTABLE, _branch, recalibrate, session_shift

T = np.arange(0.0, 20.0, 0.01)


def _input(rng) -> np.ndarray:
    """A few reversals of random amplitude: a session's first seconds of motion."""
    f = rng.uniform(0.2, 0.5)
    return rng.uniform(0.3, 1.0) * np.sin(2 * np.pi * f * T) + 0.2 * np.sin(2 * np.pi * 1.3 * f * T)


def _backlash(rng) -> ts.models.Backlash:
    return ts.models.Backlash(c_r=rng.uniform(0.6, 1.4), c_l=rng.uniform(0.6, 1.4),
                              B_r=rng.uniform(0.02, 0.1), B_l=rng.uniform(0.02, 0.1))  # fmt: skip


def _shifted(model, x, offset, gain, widen, noise, rng):
    """The drive a session later: dead band widened by ``widen`` (each side), output
    y = offset + gain * model's, and white noise."""
    moved = model.with_params(B_r=model.params["B_r"] + widen, B_l=model.params["B_l"] + widen)
    y = offset + gain * np.asarray(moved.simulate(T, x))
    return y + noise * rng.standard_normal(T.size)


def test_branch_follows_the_direction_of_motion():
    x = np.concatenate([np.linspace(0, 1, 50), np.linspace(1, -1, 100), np.linspace(-1, 0.5, 80)])
    s = _branch(x + 0.001 * np.random.default_rng(0).standard_normal(x.size))
    assert np.all(s[:45] == 1) and np.all(s[60:145] == -1) and np.all(s[165:] == 1)


def test_the_shifts_are_measured_within_their_errors_over_random_drives():
    rng = np.random.default_rng(1)
    misses = []
    for _ in range(40):
        model, x = _backlash(rng), _input(rng)
        offset, gain, widen = rng.uniform(-0.1, 0.1), rng.uniform(0.9, 1.1), rng.uniform(0, 0.03)
        y = _shifted(model, x, offset, gain, widen, 0.002, rng)
        found = session_shift(model, (T, x, y))
        m = np.asarray(model.simulate(T, x))[found_start(x) :].mean()
        truth = {"offset": offset + (gain - 1) * m, "gain": gain - 1, "dead band": widen}
        for name, value in truth.items():
            s = found.shifts[name]
            misses.append(abs(s.value - value) > 3 * s.se)
        assert not found.same_state or abs(offset) < 0.01
    # 120 estimates; 4 standard errors (Newey-West) plus the bias allowance: a handful at most
    assert sum(misses) <= 6, sum(misses)


def found_start(x):
    from tendonsheath.apps.compare import _settle

    return _settle(x)


def test_the_same_drive_is_the_same_state():
    rng = np.random.default_rng(2)
    alarms = 0
    for _ in range(40):
        model, x = _backlash(rng), _input(rng)
        y = np.asarray(model.simulate(T, x)) + 0.003 * rng.standard_normal(T.size)
        alarms += not session_shift(model, (T, x, y)).same_state
    # the noise alone: a term is significant in about 5 % of cases, and material in none
    assert alarms <= 2, alarms


def test_recalibrate_recovers_the_new_session_and_keeps_the_rest():
    rng = np.random.default_rng(3)
    for _ in range(10):
        model, x = _backlash(rng), _input(rng)
        y = _shifted(model, x, rng.uniform(-0.2, 0.2), rng.uniform(0.85, 1.15),
                     rng.uniform(0, 0.04), 0.002, rng)  # fmt: skip
        recal = recalibrate(model, (T, x, y))
        # the refit reaches the noise floor (2e-3), up to what the dead band's change in
        # the normalised inner units leaves; before, the shift dominates
        assert recal.rmse_after < 0.004 < recal.rmse_before, recal.text()
        new = recal.model
        assert isinstance(new, ts.models.Scaled)
        inner = new.inner
        assert inner.params["c_r"] == model.params["c_r"]
        assert inner.params["c_l"] == model.params["c_l"]
        assert inner.params["B_r"] - model.params["B_r"] == pytest.approx(
            inner.params["B_l"] - model.params["B_l"]
        )


def _loaded():
    base = ts.models.Backlash(c_r=1.0, c_l=1.0, B_r=0.05, B_l=0.05)
    return ts.models.Loaded(base, gain=-0.2, slack=0.03, slack_load=0.5, friction=0.02)


def test_recalibrated_loaded_model_refits_its_load_gain_where_the_load_varies():
    model, x = _loaded(), _input(np.random.default_rng(4))
    load = 0.5 + 0.4 * np.sin(2 * np.pi * 0.07 * T)
    moved = model.with_params(slack=0.05, gain=-0.25)  # re-tensioned: another stretch
    y = 0.1 + 1.05 * np.asarray(moved.simulate(T, x, load=load))
    recal = recalibrate(model, ts.io.Log(t=T, x=x, y=y, load=load), refit=REFITTABLE)
    assert recal.rmse_after < 1e-3 * recal.rmse_before, recal.text()
    new = recal.model
    assert isinstance(new, ts.models.Loaded) and isinstance(new.base, ts.models.Scaled)
    assert set(recal.refitted) == {"base.output_offset", "base.output_gain", "gain", "slack"}
    # the output gain scales the base only: the stretch's share of it lands in the load gain
    assert new.terms["gain"] == pytest.approx(-0.25 * 1.05, rel=1e-3)
    assert new.terms["slack"] == pytest.approx(0.05, rel=1e-3)
    for term in ("slack_load", "friction"):
        assert new.terms[term] == model.terms[term]
    ff = ts.compensate.LoadCompensated(new)
    assert np.all(np.isfinite(ff.command(T, y, load=load)))


def test_a_constant_load_keeps_the_load_gain_and_says_so():
    model, x = _loaded(), _input(np.random.default_rng(5))
    load = np.full(T.size, 0.3)
    y = 0.1 + np.asarray(model.with_params(slack=0.05).simulate(T, x, load=load))
    assert recalibrate(model, (T, x, y), load=load).notes == []  # the default: no load gain
    recal = recalibrate(model, (T, x, y), load=load, refit=REFITTABLE)
    assert recal.notes == ["load gain: kept (the load does not vary in the logs)"]
    assert recal.model.terms["gain"] == model.terms["gain"]
    assert recal.rmse_after < 0.01 * recal.rmse_before


def test_a_model_without_a_dead_band_says_so():
    rng = np.random.default_rng(5)
    x = _input(rng)
    model = ts.models.PrandtlIshlinskii(thresholds=[0.0, 0.1, 0.2], weights=[0.8, 0.2, 0.1])
    y = 0.05 + np.asarray(model.simulate(T, x))
    recal = recalibrate(model, (T, x, y))
    assert recal.notes == ["dead band: kept (PrandtlIshlinskii has no dead-band parameter)"]
    assert recal.rmse_after < 1e-6 < recal.rmse_before


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda m, d: recalibrate(m, d, refit=("offset", "zero")), "refit: one or more of"),
        (lambda m, d: recalibrate(m, d, refit=()), "refit: one or more of"),
        (lambda m, d: session_shift(m, []), "give a log"),
        (lambda m, d: session_shift(m, [d, d], load=np.ones(T.size)), "load= goes with one log"),
        (lambda m, d: session_shift(m, (T, np.ones(T.size), d[2])), "must move both ways"),
        (lambda m, d: recalibrate(m, (T, np.ones(T.size), d[2])), "must move both ways"),
        (
            lambda m, d: session_shift(ts.models.Loaded(m), d),
            "this model takes a measured load",
        ),
        (lambda m, d: session_shift(ts.models.Loaded(m), d, load=[1.0]), "load: 2000 finite"),
    ],
)
def test_bad_calls_are_named(call, message):
    model = ts.models.Backlash()
    x = np.sin(T)
    with pytest.raises(ValueError, match=message):
        call(model, (T, x, np.asarray(model.simulate(T, x))))


def test_a_load_gain_the_logs_cannot_determine_is_kept_and_named():
    model, rng = _loaded(), np.random.default_rng(6)
    logs = []
    for level in (0.3, 0.3005):  # two loads, too close to tell the stretch apart from noise
        x, load = _input(rng), np.full(T.size, level)
        y = np.asarray(model.simulate(T, x, load=load)) + 0.01 + 0.003 * rng.standard_normal(T.size)
        logs.append(ts.io.Log(t=T, x=x, y=y, load=load))
    recal = recalibrate(model, logs, refit=REFITTABLE)
    assert recal.model.terms["gain"] == model.terms["gain"]
    assert "gain" not in recal.refitted
    assert recal.notes[-1].startswith("load gain: kept (the logs' load varies too little")


def test_a_reference_sets_how_far_the_models_own_logs_stray():
    rng = np.random.default_rng(7)
    model = _backlash(rng)
    # the model's session: runs whose offset strays by up to 0.02 (a load it does not model)
    own = []
    for stray in (-0.02, 0.0, 0.015):
        x = _input(rng)
        own.append((T, x, _shifted(model, x, stray, 1.0, 0.0, 0.002, rng)))
    x = _input(rng)
    same = (T, x, _shifted(model, x, 0.01, 1.0, 0.0, 0.002, rng))
    moved = (T, x, _shifted(model, x, 0.06, 1.0, 0.0, 0.002, rng))
    assert not session_shift(model, same).same_state  # without a reference: a shift
    checked = session_shift(model, same, reference=own)
    assert checked.shifts["offset"].tolerance == pytest.approx(0.02, abs=1e-3)
    assert checked.same_state, checked.text()
    assert not session_shift(model, moved, reference=own).same_state
