"""GeneralizedPrandtlIshlinskii beyond its training inputs: the envelopes follow their tangent
lines (continuous, increasing, the C++ core's numbers), and identify sets the range."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.identify.extrapolation import bounded_to_training
from tendonsheath.models import Chain, GeneralizedPrandtlIshlinskii, Polynomial, Scaled


def _random_gpi(rng, span=(-0.6, 0.6)) -> GeneralizedPrandtlIshlinskii:
    def env():
        return (
            0.3 + 2 * rng.random(),
            0.2 + 4 * rng.random(),
            rng.random() - 0.5,
            rng.random() - 0.5,
        )

    return GeneralizedPrandtlIshlinskii(
        env(),
        env(),
        [0.0, 0.05 + 0.1 * rng.random(), 0.2 + 0.1 * rng.random()],
        [0.3 + rng.random(), 0.4 * rng.random(), 0.4 * rng.random()],
        envelope_range=span,
    )


def test_envelopes_follow_their_tangents_as_the_core_does():
    rng = np.random.default_rng(5)
    for _ in range(50):
        lo = -1.5 * rng.random()
        hi = lo + 0.2 + 1.5 * rng.random()
        m = _random_gpi(rng, (lo, hi))
        plain = m.with_params(envelope_range=None)
        x = np.linspace(lo - 5 * (hi - lo), hi + 5 * (hi - lo), 2001)
        up, down = m.envelopes(x)
        up0, down0 = plain.envelopes(x)
        params = m.params_struct()
        for got, plain_got, env in ((up, up0, params.rising), (down, down0, params.falling)):
            assert env.lo == lo and env.hi == hi
            np.testing.assert_allclose(got, [env(v) for v in x], rtol=1e-13, atol=1e-14)
            assert np.all(np.diff(got) >= 0)  # never decreasing
            inside = (x >= lo) & (x <= hi)
            np.testing.assert_array_equal(got[inside], plain_got[inside])
            # continuous, with a continuous slope, at both ends
            for end in (lo, hi):
                h = 1e-6 * (hi - lo)
                e = [env(end - h), env(end), env(end + h)]
                assert abs(e[2] - e[0]) <= 3 * h * env.slope_at(end) + 1e-13
                assert (e[2] - e[1]) / h == pytest.approx((e[1] - e[0]) / h, rel=1e-4, abs=1e-9)
            # linear beyond: a zero second difference past hi
            past = got[x > hi]
            np.testing.assert_allclose(
                np.diff(past, 2), 0.0, atol=1e-12 * (1 + np.max(np.abs(past)))
            )


def test_the_operator_keeps_rising_past_the_range_where_the_tanh_saturates():
    rng = np.random.default_rng(8)
    for _ in range(20):
        m = _random_gpi(rng)
        plain = m.with_params(envelope_range=None)
        x = np.r_[np.linspace(0.0, 0.6, 50), np.linspace(0.6, 3.0, 200)[1:]]
        y, y0 = np.asarray(m.simulate(None, x)), np.asarray(plain.simulate(None, x))
        inside = x <= 0.6
        np.testing.assert_array_equal(y[inside], y0[inside])
        assert np.all(np.diff(y) >= 0)
        p = m.params
        slope = 0.5 * sum(
            p[f"{s}_a"] * p[f"{s}_b"] / np.cosh(p[f"{s}_b"] * (0.6 - p[f"{s}_c"])) ** 2
            for s in ("rising", "falling")
        )
        # the centre play alone rises by its tangent slope times the stroke past the range
        assert y[-1] - y[inside][-1] >= 0.999 * p["weights"][0] * slope * 2.4
        assert y[-1] > y0[-1]


def test_envelope_range_saves_loads_and_is_checked():
    m = _random_gpi(np.random.default_rng(1), (-0.4, 0.9))
    back = ts.models.HysteresisModel.from_dict(json.loads(m.to_json()))
    assert back.options == {"envelope_range": [-0.4, 0.9]} and back == m
    assert GeneralizedPrandtlIshlinskii().options == {}  # none: files stay as before
    for bad in ((1.0, 1.0), (0.0, np.inf), (2.0, 1.0), (1.0,), "ab"):
        with pytest.raises(ValueError, match="envelope_range"):
            GeneralizedPrandtlIshlinskii(envelope_range=bad)


def test_identify_sets_the_training_input_range():
    warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
    t = np.linspace(0.0, 10.0, 600)
    x = 1500.0 + 400.0 * np.sin(2 * np.pi * 0.3 * t)  # motor steps: normalised, mapped back
    y = 3.0 * np.asarray(ts.models.BoucWenBacklash().simulate(t, (x - 1500.0) / 400.0)) + 10.0
    fit = ts.identify(GeneralizedPrandtlIshlinskii, t, x, y, maxiter=8, progress=False)
    model = fit.model
    if isinstance(model, Scaled):  # the inner model's range, in its own units
        c, s = model.map["input_offset"], model.map["input_scale"]
        lo, hi = model.inner.options["envelope_range"]
        assert [c + s * lo, c + s * hi] == pytest.approx([x.min(), x.max()], rel=1e-12)
    else:
        assert model.options["envelope_range"] == pytest.approx([x.min(), x.max()], rel=1e-12)
    # inside the training range, the same predictions as the tanh alone
    unbounded = bounded_to_training(model, -np.inf, np.inf)  # no range: returned as it is
    assert unbounded is model
    pred = np.asarray(model.simulate(t, x))
    np.testing.assert_allclose(pred, fit.predictions[0], rtol=0, atol=1e-9 * np.ptp(y))


def test_bounded_to_training_walks_chains_and_scaled_models():
    g = GeneralizedPrandtlIshlinskii()
    chain = bounded_to_training(Chain(g, Polynomial(2)), -2.0, 4.0)
    assert chain.first.options["envelope_range"] == [-2.0, 4.0]
    scaled = bounded_to_training(Scaled(g, 1.0, 3.0, 0.0, 1.0), -2.0, 4.0)
    assert scaled.inner.options["envelope_range"] == [-1.0, 1.0]
    bl = ts.models.Backlash()
    assert bounded_to_training(bl, 0.0, 1.0) is bl
    assert core.Envelope().lo == -np.inf
