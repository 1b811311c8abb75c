"""Known parameters + noise -> identify -> the parameters come back within their standard errors."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.models import (
    Backlash,
    BoucWen,
    BoucWenBacklash,
    CurveAngleModel,
    PrandtlIshlinskii,
)

SEEDS = (11, 12, 13)


def _input(t):
    return np.sin(2 * np.pi * 0.5 * t) * (1 - 0.4 * t / t[-1]) + 0.25 * np.sin(2 * np.pi * 1.3 * t)


def _z_scores(fit, truth: dict) -> list[float]:
    z = []
    for name, se in fit.standard_errors.items():
        got = np.atleast_1d(fit.model.params[name]).astype(float)
        want = np.atleast_1d(truth[name]).astype(float)
        se = np.atleast_1d(se).astype(float)
        keep = se > 0
        assert np.all(np.isfinite(se[keep])), f"{name}: standard error not finite"
        z += list(np.abs(got[keep] - want[keep]) / se[keep])
    return z


CASES = {
    "Backlash": (Backlash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.08), {}),
    "BoucWenBacklash": (
        BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.08, rho=12.0, sigma=1.2, n=4.0),
        {},
    ),
    "BoucWen": (BoucWen(A=1.0, beta=2.0, gamma=1.0, n=1.5, a=0.3, k=1.0), {}),
    "PrandtlIshlinskii": (
        PrandtlIshlinskii.uniform(0.4, 6, weights=[0.6, 0.2, 0.15, 0.1, -0.05, 0.05]),
        {"initial": PrandtlIshlinskii.uniform(1.0, 6)},
    ),
}


@pytest.mark.parametrize("name", list(CASES))
def test_recovery_within_standard_errors(name):
    truth, kwargs = CASES[name]
    t = np.arange(0.0, 6.0, 4e-3)
    x = _input(t)
    z = []
    for seed in SEEDS:
        rng = np.random.default_rng(seed)
        y = truth.simulate(t, x) + 0.005 * rng.standard_normal(t.size)
        fit = ts.identify(type(truth), t, x, y, seed=seed, progress=False, **kwargs)
        assert fit.nrmse < 0.01
        z += _z_scores(fit, truth.params)
    _check_calibrated(z)


def _check_calibrated(z):
    """Standard errors that match the scatter: Gaussian would give 68 % within 1 SE and 95 %
    within 2 SE; the linearised errors of the sharpest nonlinear parameters (BoucWenBacklash
    sigma, n) are somewhat optimistic, hence the margins. Would fail if the reported errors
    were too small by a factor of 2 or more."""
    z = np.asarray(z)
    assert np.mean(z < 1.0) >= 0.4, z
    assert np.mean(z < 2.0) >= 0.8, z
    assert np.max(z) < 5.0, z


def test_curve_angle_model_recovery():
    truth = CurveAngleModel(friction=0.12, stiffness=2.0e3, load=2.0)
    t = np.arange(0.0, 6.0, 5e-3)
    x = 0.6 * np.sin(2 * np.pi * 0.4 * t) + 0.2 * np.sin(2 * np.pi * 0.9 * t)
    z = []
    for seed in SEEDS:
        rng = np.random.default_rng(seed)
        recs = []
        for theta in (np.pi / 2, np.pi, 2 * np.pi):
            y = truth.simulate(t, x, curve_angle=theta)
            recs.append((t, x, y + 0.003 * rng.standard_normal(t.size), theta))
        fit = ts.identify(CurveAngleModel, recordings=recs, seed=seed, progress=False)
        assert set(fit.standard_errors) == {"friction", "stiffness", "load"}
        z += _z_scores(fit, truth.params)
    _check_calibrated(z)


def test_seeded_and_reproducible():
    truth = BoucWenBacklash(B_r=0.1, B_l=0.1, n=3.0)
    t = np.arange(0.0, 4.0, 5e-3)
    x = _input(t)
    y = truth.simulate(t, x) + 0.01 * np.random.default_rng(0).standard_normal(t.size)
    a = ts.identify(BoucWenBacklash, t, x, y, seed=5, progress=False)
    b = ts.identify(BoucWenBacklash, t, x, y, seed=5, progress=False)
    assert a.model.params == b.model.params
    assert a.evaluations == b.evaluations > 0
