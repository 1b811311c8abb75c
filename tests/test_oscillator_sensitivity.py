"""Forward sensitivities of the HystereticOscillator (the tangent-linear RK4 scheme used by
the simulation-error stage of the identification) against central finite differences of the
simulation itself, over random parameters (softening and hardening loops, nu = 1 and > 1)."""

import numpy as np
import pytest

from tendonsheath import _core as core
from tendonsheath import models
from tendonsheath._util.sampling import fft_upsample

NAMES = ("m", "c", "k", "alpha", "beta", "gamma", "delta", "nu")


def _random_params(rng, softening: bool, nu: float) -> dict:
    gamma = rng.uniform(0.4, 1.2)
    total = -rng.uniform(0.1, 0.4) if softening else rng.uniform(0.1, 0.8)
    return dict(
        m=2.0 * rng.uniform(0.7, 1.4),
        c=10.0 * rng.uniform(0.5, 2.0),
        k=5e4 * rng.uniform(0.5, 1.5),
        alpha=5e4 * rng.uniform(0.5, 1.5),
        beta=1e3 * rng.uniform(0.5, 2.0),
        gamma=gamma,
        delta=total - gamma,
        nu=nu,
    )


def _input(rng, n=600, fs=750.0):
    """A random-phase multisine of 5-150 Hz over exactly one record (periodic)."""
    f = np.fft.rfftfreq(n, 1 / fs)
    lines = np.nonzero((f >= 5) & (f <= 150))[0]
    X = np.zeros(f.size, dtype=complex)
    X[lines] = np.exp(2j * np.pi * rng.uniform(size=lines.size))
    x = np.fft.irfft(X, n)
    return 50.0 * x / np.std(x), 1 / fs


@pytest.mark.parametrize("softening", [True, False])
def test_sensitivities_match_central_differences(rng, softening):
    for trial in range(4):
        nu = 1.0 if trial % 2 == 0 else rng.uniform(1.2, 2.0)
        p = _random_params(rng, softening, nu)
        x, dt = _input(rng)
        fine = 8
        xf = fft_upsample(x, fine)
        model = models.HystereticOscillator(**p)
        y, S = core.oscillator_sensitivity_dense(model.params_struct(), dt, x.size, xf, fine)
        y_sim = model.simulate_dense(dt, x.size, xf, fine)
        np.testing.assert_allclose(y, y_sim, rtol=0, atol=1e-12 * np.ptp(y_sim))
        for j, name in enumerate(NAMES):
            forward = name == "nu" and nu == 1.0  # nu >= 1: one-sided there
            h = (1e-8 if forward else 1e-7) * (abs(p[name]) if name != "nu" else 1.0)
            lo = p[name] if forward else p[name] - h
            up = model.with_params(**{name: p[name] + h}).simulate_dense(dt, x.size, xf, fine)
            dn = model.with_params(**{name: lo}).simulate_dense(dt, x.size, xf, fine)
            fd = (up - dn) / (p[name] + h - lo)
            scale = np.max(np.abs(fd))
            assert scale > 0, name
            # central differences agree to <= 2e-7 (their error falls as h^2 down to rounding:
            # the sensitivities are exact); forward ones (first order) less closely
            tol = 1e-4 if forward else 1e-5
            err = np.max(np.abs(S[:, j] - fd)) / scale
            assert err < tol, (name, nu, softening, err)


def test_sensitivity_rejects_bad_grid():
    model = models.HystereticOscillator()
    with pytest.raises(ValueError, match="n \\* fine"):
        core.oscillator_sensitivity_dense(model.params_struct(), 0.01, 10, np.zeros(7), 2)
