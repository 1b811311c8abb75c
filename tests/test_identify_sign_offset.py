"""Step 9: any sign, any offset, any units (issue 12 item 4, issue 18 items 2 and 5)."""

import warnings

import numpy as np
import pytest
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


STEPS = (1017.0, 2202.0)  # a drive logged in motor steps (issue 18 item 2)
CLASSES = [
    ts.models.Backlash,
    ts.models.BoucWenBacklash,
    ts.models.PrandtlIshlinskii,
    ts.models.GeneralizedPrandtlIshlinskii,
]


@pytest.fixture(scope="module")
def transformed():
    """Plant data (rad in, rad out) and the same data as a user's logger writes it: input in
    motor steps 1017-2202, output in degrees, negated and offset by 35 deg."""
    t, q, y = plant_log(n=400, amplitude=0.8)
    k = (STEPS[1] - STEPS[0]) / np.ptp(q)
    x = STEPS[0] + k * (q - q.min())
    scale = -np.degrees(1.0)
    return (t, q, y), (t, x, 35.0 + scale * y), abs(scale)


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_negated_offset_scaled_fit_matches_the_untransformed_fit(cls, transformed, tmp_path):
    (t, q, y), (_, x, y_raw), scale = transformed
    opts = {"maxiter": 30, "popsize": 10, "progress": False}
    plain = ts.identify(cls, t, q, y, **opts)
    fit = ts.identify(cls, t, x, y_raw, **opts)
    # measured: ratio 1.000 for all four; without normalisation (normalize=False) 9.3x
    # (Backlash), 1.4x (BoucWenBacklash), 17x (PI) and 111x (GPI) the untransformed rmse
    assert fit.rmse / scale <= 1.05 * plain.rmse + 1e-9
    path = tmp_path / "model.json"
    fit.model.to_json(path)
    again = ts.load_model(path)
    assert np.allclose(again.simulate(t, x), fit.predictions[0], rtol=0, atol=1e-9 * scale)
    assert np.allclose(fit.model.simulate(t, x), fit.predictions[0])


def test_positive_gain_fits_keep_their_class(transformed):
    """Where the raw-unit parameters exist (positive gain, dead bands >= 0), the normalised
    fit is mapped back into the class itself, so compensators and users see a Backlash."""
    (t, q, y), _, _ = transformed
    for cls in (ts.models.Backlash, ts.models.BoucWenBacklash):
        fit = ts.identify(cls, t, q, y, maxiter=20, popsize=10, progress=False)
        assert type(fit.model) is cls, fit.method


def test_negative_gain_gives_a_scaled_model_that_inverts(transformed):
    (t, _, _), (_, x, y_raw), scale = transformed
    fit = ts.identify(ts.models.Backlash, t, x, y_raw, maxiter=20, popsize=10, progress=False)
    model = fit.model
    assert isinstance(model, ts.models.Scaled) and model.map["output_gain"] < 0
    assert set(fit.standard_errors) <= set(model.params)
    # the inverse feedforward of the Scaled model: the model driven by the command tracks
    y_d = 35.0 - 30.0 * np.sin(2 * np.pi * 0.25 * t)
    ff = ts.compensate.InverseFeedforward(model, smoothing=1.0)
    u = ff.command(t, y_d)
    assert STEPS[0] - 400 < u.min() and u.max() < STEPS[1] + 400  # raw motor steps
    err = model.simulate(t, u) - y_d
    assert np.sqrt(np.mean(err[50:] ** 2)) < 0.05 * 30.0
    ff.reset()
    stream = [ff.step(v, t[1] - t[0]) for v in y_d]
    assert np.allclose(stream, u)


def test_scaled_model_validation_and_json():
    inner = ts.models.Backlash(c_r=1.0, c_l=1.0, B_r=0.1, B_l=0.1)
    with pytest.raises(ValueError, match="input_scale must be > 0"):
        ts.models.Scaled(inner, input_scale=0.0)
    with pytest.raises(ValueError, match="output_gain must be finite and not 0"):
        ts.models.Scaled(inner, output_gain=0.0)
    m = ts.models.Scaled(inner, 10.0, 2.0, 5.0, -3.0)
    x = np.linspace(6.0, 14.0, 50)
    assert np.allclose(m.simulate(None, x), 5.0 - 3.0 * inner.simulate(None, (x - 10.0) / 2.0))
    assert ts.load_model(m.to_json()) == m
    assert m.with_params(output_gain=2.0).map["output_gain"] == 2.0
