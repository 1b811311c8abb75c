"""Backlash: exact dead band and branch slopes over random parameters."""

import numpy as np

from tendonsheath import models


def test_dead_band_is_flat_and_branches_have_their_slopes(rng):
    for _ in range(50):
        c_r, c_l = rng.uniform(0.7, 1.3, 2)
        B_r, B_l = rng.uniform(0.0, 0.3, 2)
        m = models.Backlash(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l)
        peak = 1.0
        if c_r != c_l:  # stay inside where unequal branches cross (x* on either side)
            peak = min(peak, 0.5 * abs((c_l * B_l + c_r * B_r) / (c_r - c_l)))
        up = np.linspace(-peak, peak, 2001)
        down = np.linspace(peak, -peak, 2001)
        x = np.r_[up, down[1:]]
        y = m.simulate(None, x)
        yu, yd = y[: up.size], y[up.size - 1 :]
        # rising: after the band is crossed the output is on c_r (x - B_r)
        on_right = yu > yu[0] + 1e-12
        np.testing.assert_allclose(yu[on_right], c_r * (up[on_right] - B_r), atol=1e-12)
        # falling from the peak: flat until the left branch is met, then on it
        x_meet = yd[0] / c_l - B_l
        inside = down > x_meet
        assert np.all(yd[inside] == yd[0])
        np.testing.assert_allclose(yd[~inside], c_l * (down[~inside] + B_l), atol=1e-12)
        # dead-band width in x for equal slopes is B_r + B_l
        if abs(c_r - c_l) < 1e-15:
            assert abs((peak - x_meet) - (B_r + B_l)) < 1e-12


def test_starts_in_the_middle_of_the_band():
    m = models.Backlash(c_r=1.0, c_l=1.0, B_r=0.2, B_l=0.1)
    y = m.simulate(None, [0.3, 0.3])
    assert y[0] == 0.5 * ((0.3 - 0.2) + (0.3 + 0.1))
