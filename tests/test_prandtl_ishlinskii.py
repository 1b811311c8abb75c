"""Prandtl-Ishlinskii: play behaviour and the exact inverse."""

import numpy as np
import pytest

from tendonsheath import models


def _random_pi(rng, count):
    r = np.r_[0.0, np.cumsum(rng.uniform(0.01, 0.2, count - 1))]
    w = np.r_[rng.uniform(0.2, 1.0), rng.normal(0.0, 0.3, count - 1)]
    partial = np.cumsum(w)
    for i in range(count):  # keep every partial sum positive
        if partial[i] <= 0.05:
            w[i] += 0.05 - partial[i] + 0.1
            partial = np.cumsum(w)
    return r, w


def test_inverse_of_model_is_identity(rng):
    for trial in range(40):
        r, w = _random_pi(rng, 1 + trial % 15)
        fwd = models.PrandtlIshlinskii(r, w)
        inv = fwd.inverse()
        x = np.cumsum(rng.normal(0, 0.2, 3000)) + rng.normal()
        np.testing.assert_allclose(inv.simulate(None, fwd.simulate(None, x)), x, atol=1e-9, rtol=0)
        y = np.cumsum(rng.normal(0, 0.2, 3000))
        np.testing.assert_allclose(fwd.simulate(None, inv.simulate(None, y)), y, atol=1e-9, rtol=0)


def test_single_play_is_backlash():
    m = models.PrandtlIshlinskii([0.2], [1.0])
    b = models.Backlash(1.0, 1.0, 0.2, 0.2)
    x = np.r_[np.linspace(0, 1, 50), np.linspace(1, -1, 100), np.linspace(-1, 0.5, 80)]
    y_pi = m.simulate(None, x)
    y_b = b.simulate(None, x)
    # both hold inside the band and follow x -+ 0.2 outside; they differ only in the start
    np.testing.assert_allclose(y_pi[60:], y_b[60:], atol=1e-12)


def test_loading_curve_slopes_are_partial_sums():
    r, w = [0.0, 0.1, 0.3], [0.5, 0.3, 0.2]
    m = models.PrandtlIshlinskii(r, w)
    x = np.linspace(0, 1, 1001)
    slope = np.gradient(m.simulate(None, x), x)
    assert slope[50] == pytest.approx(0.5)
    assert slope[200] == pytest.approx(0.8)
    assert slope[600] == pytest.approx(1.0)


def test_inverse_needs_a_zero_threshold():
    models.PrandtlIshlinskii([0.1, 0.2], [1.0, 0.5])
    with pytest.raises(ValueError, match="thresholds\\[0\\] must be 0"):
        models.PrandtlIshlinskii([0.1, 0.2], [1.0, 0.5]).inverse()
    with pytest.raises(ValueError, match="partial sums"):
        models.PrandtlIshlinskii([0.0, 0.2], [0.3, -0.5])
