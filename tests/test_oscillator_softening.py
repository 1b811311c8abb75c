"""Issue 18 item 1: softening Bouc-Wen oscillators (beta (gamma + delta) < 0) are accepted;
z is bounded over a displacement range (closed form for nu = 1), and a simulation whose
hysteretic force diverges raises a clear ValueError instead of being rejected up front."""

import warnings

import numpy as np
import pytest

from tendonsheath import models
from tendonsheath.models.hysteretic_oscillator import UnboundedStateWarning

BENCH = dict(m=2.0, c=10.0, k=5e4, alpha=5e4, beta=1e3, gamma=0.8, delta=-1.1, nu=1.0)


def test_softening_benchmark_system_is_accepted_and_simulates():
    osc = models.HystereticOscillator(**BENCH)  # raised "gamma + delta must be > 0" before
    t = np.arange(0.0, 4.0, 1 / 750)
    u = 50.0 * np.sin(2 * np.pi * 7.0 * t)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnboundedStateWarning)  # bounded over this range
        y = osc.simulate(t, u)
    assert np.all(np.isfinite(y)) and np.ptp(y) > 0
    assert np.isfinite(osc.z_bound(np.ptp(y)))


def test_z_bound_matches_the_loading_curve_of_a_softening_loop(rng):
    """nu = 1, b = beta (gamma + delta) < 0 and gamma > delta: loading from rest over a
    displacement Y gives z = alpha / |b| (exp(|b| Y) - 1), and unloading contracts, so
    that is the bound; a simulation's |z| stays below the bound of its displacement range."""
    for _ in range(10):
        alpha = rng.uniform(0.5, 3.0)
        gamma = rng.uniform(0.3, 1.0)
        delta = -gamma - rng.uniform(0.05, 0.5)
        beta = rng.uniform(0.5, 2.0)
        osc = models.HystereticOscillator(
            m=1.0, c=0.5, k=1.0, alpha=alpha, beta=beta, gamma=gamma, delta=delta
        )
        b = -beta * (gamma + delta)
        Y = rng.uniform(0.2, 2.0)
        assert osc.z_bound(Y) == pytest.approx(alpha / b * np.expm1(b * Y), rel=1e-6)
        t = np.linspace(0.0, 60.0, 6001)
        u = rng.uniform(0.3, 1.5) * np.sin(2 * np.pi * 0.15 * t)
        osc.reset()
        z = []
        for k in range(t.size):
            osc.step(u[k], 0.0 if k == 0 else t[k] - t[k - 1])
            z.append(osc.hysteretic_force())
        y = osc.simulate(t, u)
        assert np.max(np.abs(z)) <= osc.z_bound(np.ptp(y)) * (1 + 1e-9)


def test_hardening_bound_is_the_ultimate_state():
    """beta (gamma + delta) > 0 and gamma >= delta, nu = 1: |z| <= z_u = alpha / (beta
    (gamma + delta)), approached for a long excursion."""
    osc = models.HystereticOscillator(alpha=2.0, beta=1.0, gamma=0.7, delta=0.3)
    assert osc.z_bound(100.0) == pytest.approx(2.0, rel=1e-9)
    assert osc.z_bound(0.1) < 2.0 * 0.1 * 1.0001


def test_divergence_raises_a_clear_error_and_streaming_stays_finite():
    """nu = 2, gamma = 0, delta < 0: dz/dy = alpha + |beta delta| z^2 escapes in finite
    displacement (pi / sqrt(4 alpha |beta delta|) ... here 2.2 from rest)."""
    osc = models.HystereticOscillator(m=1, c=0.1, k=1, alpha=1, beta=1, gamma=0.0, delta=-0.5, nu=2)
    assert np.isinf(osc.z_bound(5.0))
    t = np.arange(0.0, 30.0, 0.01)
    u = 20.0 * np.sin(t)
    with pytest.raises(ValueError, match="diverged.*gamma \\+ delta"):
        osc.simulate(t, u)
    osc.reset()
    ys = [osc.step(u[k], 0.0 if k == 0 else 0.01) for k in range(t.size)]
    assert np.all(np.isfinite(ys))
    assert osc.diverged() and osc.diverged_at() > 0
    # a small excitation stays bounded: no error, and no warning while the range is safe
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnboundedStateWarning)
        osc.simulate(t, 0.2 * np.sin(t))
    # a range beyond the escape distance warns even when this run did not diverge yet
    with pytest.warns(UnboundedStateWarning, match="bounded"):
        osc.simulate(t[:400], 2.5 * np.sin(t[:400]))
