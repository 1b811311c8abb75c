"""The Newey-West bandwidth of recordings at different rates is a time, converted to lags in
each recording at its own rate (identify_coupled's ``nw_lag_s``; automatic: Andrews' rule
pooled in seconds). Judged against the closed-form standard error of a least-squares slope
whose residual is an AR(1) process in time (its correlation time the same in both
recordings, so its lag-1 correlation is exp(-period / tau) in each)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.signal import lfilter

from tendonsheath.identify import identify_coupled
from tendonsheath.identify.newey_west import andrews_lags, andrews_seconds, newey_west
from tendonsheath.models import Backlash

TAU = 0.1  # s: the residual's correlation time
# recording A: 2 s at 1 kHz, B: 40 s at 100 Hz (more samples than A: a bandwidth in samples
# pooled over both leans to B's short correlation in samples, and is too short for A)
PERIODS, DURATIONS = (1e-3, 1e-2), (2.0, 40.0)
SEEDS = 20


def _regressors() -> list[np.ndarray]:
    return [
        1.0 + 0.8 * np.sin(2 * np.pi * 0.4 * np.arange(0.0, d, p))
        for p, d in zip(PERIODS, DURATIONS, strict=True)
    ]


def _rhos() -> list[float]:
    return [math.exp(-p / TAU) for p in PERIODS]


def _true_se(zs: list[np.ndarray]) -> float:
    """sqrt(z' Sigma z) / z'z, Sigma the unit-variance AR(1) covariance within each recording
    (zero across them): sum_ij z_i z_j rho^|i-j| = z'z + 2 sum_i z_i sum_{j<i} rho^(i-j) z_j."""
    num = 0.0
    for z, rho in zip(zs, _rhos(), strict=True):
        num += z @ z + 2 * z @ lfilter([0.0, rho], [1.0, -rho], z)
    return math.sqrt(num) / sum(z @ z for z in zs)


def _errors(rng, zs) -> np.ndarray:
    """Stationary unit-variance AR(1) residuals, each recording at its own lag-1 correlation."""
    parts = []
    for z, rho in zip(zs, _rhos(), strict=True):
        w = rng.normal(0.0, math.sqrt(1 - rho**2), z.size)
        w[0] = rng.normal()
        parts.append(lfilter([1.0], [1.0, -rho], w))
    return np.concatenate(parts)


def _rms_se(**bandwidth) -> tuple[float, list[int]]:
    """The RMS over seeds of the slope's Newey-West SE (the mean variance) and the lags."""
    zs = _regressors()
    z = np.concatenate(zs)
    blocks = [v.size for v in zs]
    variances = []
    for seed in range(SEEDS):
        e = _errors(np.random.default_rng(seed), zs)
        r = e - (z @ e) / (z @ z) * z
        se, lags, _ = newey_west(z[:, None], r, 1, blocks=blocks, **bandwidth)
        variances.append(se[0] ** 2)
    return math.sqrt(float(np.mean(variances))), lags


def test_a_bandwidth_in_seconds_gives_the_right_se_where_one_in_samples_does_not():
    truth = _true_se(_regressors())
    # 0.5 s (5 tau): 500 lags at 1 kHz, 50 at 100 Hz; the same 50 lags in both recordings
    # cover only 0.05 s (half of tau) of A, whose scores dominate the slope's variance
    seconds, lags = _rms_se(lags=None, periods=PERIODS, lag_s=0.5)
    assert lags == [500, 50]
    samples, lags = _rms_se(lags=50)
    assert lags == [50, 50]
    # measured 0.82 and 0.55 of the truth (a Bartlett kernel of 5 tau is biased low by about
    # tau / bandwidth in variance, and the residuals are estimated): 0.75 and 0.68 leave room
    assert 0.75 * truth < seconds < 1.05 * truth, (seconds, truth)
    assert samples < 0.68 * truth, (samples, truth)
    # automatic: Andrews' rule pooled in seconds (measured 0.84 of the truth, 910 and 91
    # lags with seed 19) against the rule in samples pooled over both (0.71, 130 lags in each)
    pooled, lags = _rms_se(lags=None, periods=PERIODS)
    assert 8 < lags[0] / lags[1] <= 10.1  # one time: ten times the lags at ten times the rate
    shared, _ = _rms_se(lags=None)
    assert pooled > 0.78 * truth and shared < 0.78 * truth, (pooled, shared, truth)


def test_andrews_in_seconds_is_andrews_rule_for_one_recording():
    """One recording: the pooled rule in seconds is Andrews' in samples times the period."""
    rng = np.random.default_rng(4)
    scores = lfilter([1.0], [1.0, -0.9], rng.normal(size=(3000, 2)), axis=0)
    for period in (1e-3, 2.5e-3):
        seconds = andrews_seconds(scores, [(0, 3000)], [period])
        assert math.ceil(seconds / period - 1e-9) == andrews_lags(scores), period


T = np.arange(200) * 1e-3
X = np.column_stack([np.sin(10 * T), np.cos(7 * T)])


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"nw_lag_s": 0.0}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": -0.1}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": math.nan}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": math.inf}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": "0.1"}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": True}, "nw_lag_s must be a finite number of seconds > 0"),
        ({"nw_lag_s": 0.1, "lags": 5}, "as lags .samples. or as nw_lag_s .seconds., not both"),
    ],
)
def test_bad_bandwidths_are_one_line_errors(kwargs, match):
    with pytest.raises(ValueError, match=match) as info:
        identify_coupled(Backlash, recordings=[(T, X, X), (T, X, X)], **kwargs)
    assert "\n" not in str(info.value)


def test_a_bandwidth_in_seconds_needs_times():
    with pytest.raises(ValueError, match="nw_lag_s .seconds. needs the sample times t"):
        identify_coupled(Backlash, recordings=[(None, X, X)], nw_lag_s=0.1)
