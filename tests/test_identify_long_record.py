"""Long records: the global search runs on windows of the record, the refinement on all of it."""

from __future__ import annotations

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.identify.data import Recording, search_windows


def _record(n, seed=0):
    t = np.arange(n) / 1000.0
    x = np.sin(2 * np.pi * 0.2 * t) * (0.6 + 0.4 * np.sin(2 * np.pi * 0.01 * t))
    x += 0.2 * np.sin(2 * np.pi * 0.73 * t)
    truth = ts.models.BoucWenBacklash(c_r=1.0, c_l=0.95, B_r=0.1, B_l=0.08, n=6)
    return t, x, truth.simulate(t, x) + np.random.default_rng(seed).normal(0, 1e-3, n), truth


def test_windows_cover_each_recording_evenly_within_the_budget():
    recs = [Recording(None, np.arange(n, dtype=float), np.zeros(n)) for n in (100_000, 50_000)]
    windows, warm = search_windows(recs, warmup=10, budget=16_000, windows=8)
    assert len(windows) == 16
    length = 16_000 // 16
    assert warm == max(10, length // 5)
    assert all(w.n == length + warm for w in windows)
    starts = [int(w.x[0]) for w in windows[:8]]
    assert starts[0] == 0 and starts[-1] == 100_000 - (length + warm)  # first and last samples
    assert np.allclose(np.diff(starts), np.diff(starts)[0], atol=1)  # evenly spaced
    same, w = search_windows(recs, warmup=10, budget=10**6)
    assert same is recs and w == 10


def test_windowed_search_finds_the_same_fit_as_the_whole_record():
    """A 120 000-sample record searched on at most 20 000 samples gives the fit of the
    search on everything: both at the noise level (1e-3) and the same parameters to 1e-3."""
    t, x, y, truth = _record(120_000)
    kw = dict(progress=False, maxiter=30, popsize=10, seed=1)
    windowed = ts.identify(ts.models.BoucWenBacklash, t, x, y, search_samples=20_000, **kw)
    whole = ts.identify(ts.models.BoucWenBacklash, t, x, y, search_samples=None, **kw)
    # the search runs on thinned records (rate-independent: every 20th sample and the
    # turning points) within the 20 000 samples; search_samples=None searches everything
    assert "global search on" in windowed.method and "global search on" not in whole.method
    # measured: 1.0003e-3 both; the fits differ by < 1e-4 in every parameter
    assert windowed.rmse < 1.01e-3
    assert windowed.rmse == pytest.approx(whole.rmse, rel=1e-3)
    for name in ("c_r", "c_l", "B_r", "B_l"):
        assert windowed.model.params[name] == pytest.approx(truth.params[name], abs=2e-3)
