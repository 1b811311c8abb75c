"""BoucWenBacklash: bounded normalised state and convergence to Backlash."""

import numpy as np
import pytest

from tendonsheath import models


def test_state_stays_in_unit_interval_for_any_input(rng):
    for _ in range(30):
        m = models.BoucWenBacklash(
            c_r=rng.uniform(0.8, 1.2),
            c_l=rng.uniform(0.8, 1.2),
            B_r=rng.uniform(0.01, 0.3),
            B_l=rng.uniform(0.01, 0.3),
            rho=rng.uniform(1.0, 300.0),
            sigma=rng.uniform(0.5, 4.0),
            n=rng.uniform(1.0, 12.0),
            max_substeps=2,
        )
        x = np.cumsum(rng.normal(0.0, 0.3, 3000) * np.where(rng.random(3000) < 0.02, 50.0, 1.0))
        m.reset()
        for xk in x:
            m.step(xk)
            assert abs(m.state()) <= 1.0


def _loop(peak=1.0, n=4001):
    up = np.linspace(-peak, peak, n)
    return np.r_[up, up[::-1][1:], up[1:]]


def test_tends_to_backlash_as_n_grows():
    """Equal slopes: in the limit n -> inf the blend is exactly the dead band (spec D.1)."""
    x = _loop()
    errors = []
    for n in (1, 2, 4, 8, 16, 32):
        bwb = models.BoucWenBacklash(c_r=0.9, c_l=0.9, B_r=0.12, B_l=0.08, n=n)
        ref = models.Backlash(c_r=0.9, c_l=0.9, B_r=0.12, B_l=0.08)
        last = slice(2 * 4000, None)  # the second rising branch, after the first loop
        errors.append(np.max(np.abs(bwb.simulate(None, x)[last] - ref.simulate(None, x)[last])))
    assert all(a > b for a, b in zip(errors, errors[1:], strict=False)), errors
    assert errors[-1] < 0.01 * (0.12 + 0.08)


def _reversal(n):
    """Travel after a reversal at x = 1 (symmetric B = 0.1, sigma = 1, rho = 2/(2B))."""
    bwb = models.BoucWenBacklash(c_r=1.0, c_l=1.0, B_r=0.1, B_l=0.1, n=n)
    x = _loop(peak=1.0, n=20001)
    y = bwb.simulate(None, x)
    xf, yf = x[20000:40000], y[20000:40000]
    band = 0.2
    flat_travel = xf[0] - xf[np.argmax(np.abs(yf - yf[0]) > 0.05 * band)]
    on_left = np.abs(yf - (xf + 0.1)) < 0.01 * band
    transition = xf[0] - xf[np.argmax(on_left)]
    return flat_travel, transition


def test_dead_zone_flatness_and_transition_match_spec_figures():
    """Spec D.1 [V]: n = 8 gives a 0.212 transition against the ideal 0.200; n = 1 is soft."""
    flat8, transition8 = _reversal(8)
    assert 0.19 < flat8 <= transition8
    assert transition8 == pytest.approx(0.212, abs=0.003)
    flat1, transition1 = _reversal(1)
    assert flat1 < 0.05
    assert transition1 > 0.4


def test_steady_branches_are_the_backlash_lines(rng):
    for _ in range(20):
        c_r, c_l = rng.uniform(0.8, 1.2, 2)
        B_r, B_l = rng.uniform(0.02, 0.2, 2)
        m = models.BoucWenBacklash(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l, n=6)
        x = np.r_[np.linspace(0, 2, 4000), np.linspace(2, -2, 8000)]
        y = m.simulate(None, x)
        # far from the reversal w = +-1 to high accuracy
        np.testing.assert_allclose(y[3999], c_r * (2 - B_r), rtol=1e-3)
        np.testing.assert_allclose(y[-1], c_l * (-2 + B_l), rtol=1e-3)
