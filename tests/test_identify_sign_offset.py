"""Step 9: any sign, any offset, any units (issue 12 item 4, issue 18 items 2 and 5)."""

import warnings

import numpy as np
from _realdata_helpers import plant_log

import tendonsheath as ts
from tendonsheath.identify.problem import bounded_lsq


def test_bounded_weight_solve_on_a_negative_gain_is_clean_and_exact():
    """Issue 18 item 5: the GPI weight solve (weights >= 0, a free offset) on a record whose
    output falls as the input rises used SciPy's trust-region reflective lsq_linear, whose
    reflected step multiplied an infinite stride by zero: "invalid value encountered in
    multiply". The active-set solve gives the KKT optimum with no warning."""
    rng = np.random.default_rng(3)
    F = np.column_stack([rng.normal(size=(300, 6)) + 2.0, np.ones(300)])
    y = -F[:, :6] @ rng.uniform(0.5, 1.0, 6) + 3.0  # negative gain: all weight bounds active
    lo = np.r_[1e-9, np.zeros(5), -np.inf]
    hi = np.full(7, np.inf)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        theta = bounded_lsq(F, y, lo, hi)
    assert np.all(theta[:6] >= lo[:6] - 1e-12)
    # KKT: the gradient vanishes on the free offset and pushes inward on active bounds
    g = F.T @ (F @ theta - y)
    assert abs(g[6]) < 1e-6 * np.abs(g).max()
    active = theta[:6] <= lo[:6] + 1e-9
    assert np.all(g[:6][active] >= -1e-6 * np.abs(g).max())
    assert np.allclose(g[:6][~active], 0.0, atol=1e-6 * np.abs(g).max())


def test_gpi_identify_on_a_negated_record_gives_no_runtime_warning():
    t, x, y = plant_log(n=500, amplitude=0.8, saturate=False)  # warned before the fix
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        fit = ts.identify(
            ts.models.GeneralizedPrandtlIshlinskii,
            t,
            x,
            -y,
            maxiter=15,
            popsize=10,
            progress=False,
        )
    assert np.isfinite(fit.rmse)
