"""HystereticOscillator: linear-limit resonance, step convergence, input interpolation."""

import numpy as np
import pytest

from tendonsheath import models


def _zero_crossing_frequency(t, y):
    s = np.signbit(y)
    idx = np.nonzero(s[1:] != s[:-1])[0]
    # linear interpolation of each crossing
    tc = t[idx] - y[idx] * (t[idx + 1] - t[idx]) / (y[idx + 1] - y[idx])
    return 1.0 / (2.0 * np.mean(np.diff(tc)))


def test_small_amplitude_resonance_is_sqrt_k_plus_alpha_over_m(rng):
    for _ in range(10):
        m, k, alpha = rng.uniform(0.2, 3.0), rng.uniform(0.5, 20.0), rng.uniform(0.5, 20.0)
        wn = np.sqrt((k + alpha) / m)
        c = 2 * 0.002 * m * wn  # 0.2 % damping
        osc = models.HystereticOscillator(
            m=m, c=c, k=k, alpha=alpha, beta=1.0, gamma=0.5, delta=0.5, nu=1.0
        )
        t = np.linspace(0.0, 40 * 2 * np.pi / wn, 40001)
        pulse = 1e-6 * (t < 0.05 * 2 * np.pi / wn)  # tiny impulse: z stays ~ alpha y
        y = osc.simulate(t, pulse)
        free = t > 0.2 * 2 * np.pi / wn
        f = _zero_crossing_frequency(t[free], y[free])
        f_expected = wn / (2 * np.pi) * np.sqrt(1 - 0.002**2)
        assert f == pytest.approx(f_expected, rel=2e-3)


def test_halving_the_step_changes_the_answer_by_less_than_1e_6():
    t = np.linspace(0.0, 20.0, 2001)
    u = 2.0 * np.sin(2 * np.pi * 0.4 * t) + np.sin(2 * np.pi * 1.3 * t)
    kwargs = dict(m=1.0, c=0.4, k=3.0, alpha=2.0, beta=1.5, gamma=0.6, delta=0.3, nu=1.5)
    y4 = models.HystereticOscillator(**kwargs, substeps=4).simulate(t, u)
    y8 = models.HystereticOscillator(**kwargs, substeps=8).simulate(t, u)
    y16 = models.HystereticOscillator(**kwargs, substeps=16).simulate(t, u)
    span = np.ptp(y16)
    assert np.max(np.abs(y8 - y4)) < 1e-6 * span
    # and keeps shrinking (the |y'| term is not smooth, so the order is below RK4's four)
    assert np.max(np.abs(y16 - y8)) < np.max(np.abs(y8 - y4)) / 2


def test_linear_interpolation_matches_a_densely_sampled_input_better_than_hold():
    kwargs = dict(m=1.0, c=0.5, k=2.0, alpha=1.0, beta=1.0, gamma=0.5, delta=0.5)
    fine_t = np.linspace(0.0, 10.0, 100001)
    fine_u = np.sin(2 * np.pi * 0.7 * fine_t)
    ref = models.HystereticOscillator(**kwargs).simulate(fine_t, fine_u)[::100]
    t, u = fine_t[::100], fine_u[::100]  # 143 samples per period
    lin = models.HystereticOscillator(**kwargs, input_interpolation="linear").simulate(t, u)
    hold = models.HystereticOscillator(**kwargs, input_interpolation="hold").simulate(t, u)
    err_lin, err_hold = np.max(np.abs(lin - ref)), np.max(np.abs(hold - ref))
    assert err_lin < 1e-3 * np.ptp(ref)
    assert err_lin < err_hold / 10


def test_static_equilibrium_of_the_linear_oscillator():
    """beta = 0: z = alpha y, so a constant force settles at u / (k + alpha)."""
    osc = models.HystereticOscillator(m=1.0, c=2.0, k=1.5, alpha=0.5, beta=0.0)
    t = np.linspace(0, 60, 6001)
    y = osc.simulate(t, np.full_like(t, 3.0))
    assert y[-1] == pytest.approx(3.0 / 2.0, rel=1e-6)
