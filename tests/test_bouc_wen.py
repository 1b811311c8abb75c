"""Classic Bouc-Wen: bounded state and the ultimate hysteretic value."""

import numpy as np

from tendonsheath import models


def test_state_bounded_by_ultimate_value(rng):
    for _ in range(30):
        beta = rng.uniform(0.2, 3.0)
        gamma = rng.uniform(-beta, beta)
        A, n = rng.uniform(0.5, 2.0), rng.uniform(1.0, 5.0)
        m = models.BoucWen(A=A, beta=beta, gamma=gamma, n=n, alpha=0.0, k=1.0)
        z_u = (A / (beta + gamma)) ** (1 / n)
        x = np.cumsum(rng.normal(0, 0.5, 2000))
        z = m.simulate(None, x)  # a = 0, k = 1: the output is z
        assert np.max(np.abs(z)) <= z_u * (1 + 1e-12)


def test_monotone_loading_approaches_ultimate_value(rng):
    for _ in range(10):
        beta = rng.uniform(0.5, 2.0)
        gamma = rng.uniform(-0.5 * beta, beta)
        A, n = rng.uniform(0.5, 2.0), rng.uniform(1.0, 3.0)
        m = models.BoucWen(A=A, beta=beta, gamma=gamma, n=n, alpha=0.0, k=1.0)
        z = m.simulate(None, np.linspace(0, 50.0, 5000))
        z_u = (A / (beta + gamma)) ** (1 / n)
        assert abs(z[-1] - z_u) < 1e-3 * z_u


def test_n1_loading_curve_matches_closed_form():
    """n = 1, z >= 0 while loading from 0: dz/dx = A - (beta + gamma) z."""
    A, beta, gamma = 1.3, 0.9, 0.4
    m = models.BoucWen(A=A, beta=beta, gamma=gamma, n=1.0, alpha=0.0, k=1.0)
    x = np.linspace(0, 3, 301)
    z = m.simulate(None, x)
    exact = A / (beta + gamma) * (1 - np.exp(-(beta + gamma) * x))
    np.testing.assert_allclose(z, exact, atol=1e-8)


def test_output_mix():
    m = models.BoucWen(A=1.0, beta=1.0, gamma=0.0, n=1.0, alpha=0.25, k=2.0)
    x = np.linspace(0, 1, 101)
    exact_z = 1 - np.exp(-x)
    np.testing.assert_allclose(m.simulate(None, x), 0.25 * x + 0.75 * 2.0 * exact_z, atol=1e-8)


def test_output_at_the_samples_does_not_depend_on_the_path_between_them(rng):
    """Why BoucWen has no input_interpolation option: feeding the linear ramps between the
    samples (8 points each, and any time step) gives the same outputs at the samples (RK4
    in x: equal to its own accuracy; measured 1e-9 of the range)."""
    for _ in range(5):
        m = models.BoucWen(
            A=1.0,
            beta=rng.uniform(0.5, 2.0),
            gamma=rng.uniform(-0.4, 0.4),
            n=rng.uniform(1.0, 3.0),
            alpha=rng.uniform(0.1, 0.9),
            max_step=0.002,  # RK4 fine enough that its own error is far below the check
            max_substeps=4096,
        )
        x = np.cumsum(rng.normal(0.0, 0.2, 300))
        t = np.arange(x.size) * 0.01
        fine = 8
        tf = np.arange((x.size - 1) * fine + 1) * (0.01 / fine)
        y = m.simulate(t, x)
        yf = m.simulate(tf * 3.7, np.interp(tf, t, x))[::fine]
        assert np.max(np.abs(yf - y)) < 1e-6 * np.ptp(y)
