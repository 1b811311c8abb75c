"""Backlash whose branch lines cross (c_r != c_l): the band is clamped to zero width past the
crossing, so the output is continuous, Lipschitz in the input, and unchanged elsewhere."""

from __future__ import annotations

import numpy as np
import pytest

import tendonsheath as ts


def test_a_tiny_reversal_past_the_crossing_moves_the_output_by_a_tiny_amount():
    """The audit's case: c_r = 1.2, c_l = 0.8 (crossing at x* = 0.5); a 1e-6 reversal at x = 1
    moved the output by 0.30 before."""
    model = ts.models.Backlash(c_r=1.2, c_l=0.8, B_r=0.1, B_l=0.1)
    x = np.concatenate([np.linspace(0.0, 1.0, 200), [1.0 - 1e-6]])
    y = model.simulate(None, x)
    assert abs(y[-1] - y[-2]) <= 1.2e-6
    assert y[-2] == pytest.approx(0.5 * (1.2 * 0.9 + 0.8 * 1.1))  # the lines' mean past x*


@pytest.mark.parametrize("seed", range(10))
def test_output_is_lipschitz_for_any_parameters_and_input(seed):
    rng = np.random.default_rng(seed)
    c_r, c_l = rng.uniform(0.5, 1.5, 2)
    B_r, B_l = rng.uniform(0.0, 0.3, 2)
    model = ts.models.Backlash(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l)
    x = np.cumsum(rng.normal(0.0, 0.05, 5000)) * rng.uniform(1, 20)  # crosses x* often
    y = model.simulate(None, x)
    # measured: the largest |dy/dx| equals max(c_r, c_l) to rounding (|y| up to ~100 here)
    bound = max(c_r, c_l) * np.abs(np.diff(x)) + 1e-13 * (1.0 + np.abs(y[1:]))
    assert np.all(np.abs(np.diff(y)) <= bound)


@pytest.mark.parametrize("seed", range(10))
def test_unchanged_where_the_lines_do_not_cross(seed):
    """Before the crossing the clamp form is the classic backlash: compared with a plain
    direction-based implementation on inputs that stay below x*."""
    rng = np.random.default_rng(100 + seed)
    c_r, c_l = rng.uniform(0.8, 1.2, 2)
    B_r, B_l = rng.uniform(0.05, 0.3, 2)
    cross = (c_r * B_r + c_l * B_l) / (c_r - c_l) if c_r != c_l else np.inf
    span = 0.9 * abs(cross) if np.isfinite(cross) else 2.0
    x = np.clip(np.cumsum(rng.normal(0.0, 0.02, 3000)), -span, span)
    if np.isfinite(cross):  # keep to the side where the band is open
        x = np.minimum(x, 0.9 * cross) if cross > 0 else np.maximum(x, 0.9 * cross)
    y = ts.models.Backlash(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l).simulate(None, x)
    ref = np.empty_like(x)
    ref[0] = 0.5 * (c_r * (x[0] - B_r) + c_l * (x[0] + B_l))
    for k in range(1, x.size):
        right, left = c_r * (x[k] - B_r), c_l * (x[k] + B_l)
        ref[k] = ref[k - 1]
        if x[k] > x[k - 1] and right > ref[k]:
            ref[k] = right
        elif x[k] < x[k - 1] and left < ref[k]:
            ref[k] = left
    np.testing.assert_allclose(y, ref, rtol=0, atol=1e-15)
