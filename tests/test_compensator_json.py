"""Compensators round-trip through JSON like models (issue 14 item 2): same commands after
reload, over random settings; strict loading names the offending key."""

import json
import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.compensate import (
    ContinuumFeedforward,
    CurveAngleFeedforward,
    InverseFeedforward,
)
from tendonsheath.models import Backlash, BoucWenBacklash, PrandtlIshlinskii, Scaled


def _trajectory(rng):
    t = np.arange(0.0, 3.0, 1e-3)
    f = rng.uniform(0.2, 1.5)
    return t, rng.uniform(0.3, 1.0) * np.sin(2 * np.pi * f * t) + 0.05 * np.sin(17 * t)


def _limits(rng):
    kind = rng.integers(3)
    if kind == 0:
        return None
    if kind == 1:
        return (-rng.uniform(1, 3), rng.uniform(1, 3))
    return {"max_rate": rng.uniform(5, 50)}


def _random_compensator(rng, k):
    c = dict(c_r=rng.uniform(0.5, 1.5), c_l=rng.uniform(0.5, 1.5))
    b = dict(B_r=rng.uniform(0, 0.2), B_l=rng.uniform(0, 0.2))
    smoothing = rng.uniform(0.01, 0.2)
    which = k % 6
    if which == 0:
        return InverseFeedforward(Backlash(**c, **b), smoothing, _limits(rng))
    if which == 1:
        model = BoucWenBacklash(**c, **b, rho=rng.uniform(5, 30), sigma=0.6, n=1.0)
        return InverseFeedforward(model, smoothing, _limits(rng))
    if which == 2:
        w = rng.uniform(0.1, 1.0, 4)
        model = PrandtlIshlinskii(thresholds=[0.0, 0.05, 0.1, 0.2], weights=list(w))
        return InverseFeedforward(model, smoothing, _limits(rng))
    if which == 3:
        model = Scaled(Backlash(**c, **b), input_offset=0.2, input_scale=1.5, output_gain=-0.8)
        return InverseFeedforward(model, smoothing, _limits(rng))
    if which == 4:
        return CurveAngleFeedforward(
            friction=rng.uniform(0.05, 0.2),
            stiffness=rng.uniform(1e3, 1e5),
            length=rng.uniform(0.2, 2.0),
            pretension=rng.uniform(5, 30),
            load_force=rng.uniform(0, 2),
            curve_angle=rng.uniform(0, 2 * math.pi),
            smoothing=smoothing,
            max_correction_rate=rng.choice([math.inf, 0.5]),
            limits=_limits(rng),
        )
    return ContinuumFeedforward(
        friction=rng.uniform(0.05, 0.2),
        curve_angle=rng.uniform(0.5, 3.0),
        mode=str(rng.choice(["exact", "published"])),
        limits=_limits(rng),
    )


@pytest.mark.parametrize("k", range(24))
def test_commands_are_equal_after_reload(tmp_path, k):
    rng = np.random.default_rng(100 + k)
    ff = _random_compensator(rng, k)
    path = tmp_path / "ff.json"
    ff.to_json(path)
    again = ts.compensate.load(path)
    assert type(again) is type(ff)
    assert again.to_dict() == ff.to_dict()
    assert set(again.params) == set(type(ff)._saved_settings)
    t, y_d = _trajectory(rng)
    u0, u1 = ff.command(t, y_d), again.command(t, y_d)
    assert np.all(np.isfinite(u0))
    np.testing.assert_allclose(u1, u0, rtol=0, atol=1e-12)
    streamed = [again.step(y, dt) for y, dt in zip(y_d, np.diff(t, prepend=t[0]), strict=True)]
    np.testing.assert_allclose(streamed, u0, rtol=0, atol=1e-12)


def test_infinite_settings_are_written_as_null_and_read_back():
    ff = CurveAngleFeedforward(0.1, 1e4, 1.0, 10.0, limits={"max": 2.0})
    data = json.loads(ff.to_json())
    assert data["max_correction_rate"] is None
    assert data["limits"] == {"min": None, "max": 2.0, "max_rate": None}
    assert "Infinity" not in ff.to_json()  # plain JSON: the C++ loader reads it
    again = ts.compensate.load_compensator(data)
    assert again.params["max_correction_rate"] == math.inf
    assert again.params["limits"].min == -math.inf


def _saved():
    return json.loads(InverseFeedforward(Backlash(), 0.05, (-1.0, 1.0)).to_json())


@pytest.mark.parametrize(
    ("change", "message"),
    [
        (lambda d: d.pop("smoothing"), r"\['smoothing'\] missing"),
        (lambda d: d.update(extra=1), r"unknown key\(s\) \['extra'\]"),
        (lambda d: d.update(smoothing=True), r"'smoothing' must be a number"),
        (lambda d: d.update(smoothing=None), r"'smoothing' must be a number"),
        (lambda d: d["limits"].update(low=0), r"unknown key\(s\) \['low'\] in 'limits'"),
        (lambda d: d["limits"].update(max="1"), r"'limits.max' must be a number"),
        (lambda d: d.update(limits=[0, 1]), r"'limits' must be an object"),
        (lambda d: d.update(compensator="Nope"), r"unknown compensator 'Nope'"),
        (lambda d: d.update(format="tendonsheath.model"), r"not a tendonsheath compensator"),
        (lambda d: d.update(version=2), r"unsupported compensator file version 2"),
        (lambda d: d["model"]["params"].pop("B_l"), r"\['B_l'\] missing"),
    ],
)
def test_strict_loading_names_the_key(change, message):
    data = _saved()
    change(data)
    with pytest.raises(ValueError, match=message):
        ts.compensate.load(data)


def test_unreadable_sources_are_one_line_errors(tmp_path):
    with pytest.raises(ValueError, match="compensator file not found"):
        ts.compensate.load(tmp_path / "missing.json")
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(ValueError, match="not valid JSON"):
        ts.compensate.load(bad)
