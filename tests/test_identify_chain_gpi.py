"""Identification of Chain(first, Polynomial) and GeneralizedPrandtlIshlinskii."""

import numpy as np
import pytest
from _realdata_helpers import plant_log

import tendonsheath as ts
from tendonsheath.models import (
    BoucWenBacklash,
    Chain,
    GeneralizedPrandtlIshlinskii,
    Polynomial,
)


def _rmse(a, b):
    return float(np.sqrt(np.mean((np.asarray(a) - np.asarray(b)) ** 2)))


def test_chain_recovers_a_known_chain_and_predicts_new_input():
    t = np.linspace(0, 8, 600)
    x = 0.8 * np.sin(2 * np.pi * 0.25 * t) * (1 - 0.3 * (t > 4))
    truth = Chain(
        BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.08, rho=12.0, n=3.0),
        Polynomial(coefficients=[0.02, 0.9, -0.3, -0.4]),
    )
    y = truth.simulate(t, x)
    fit = ts.identify(Chain(BoucWenBacklash(), Polynomial(3)), t, x, y, maxiter=40, progress=False)
    assert isinstance(fit.model, Chain) and isinstance(fit.model.second, Polynomial)
    assert fit.nrmse < 0.005
    assert fit.model.params["first.c_r"] == 1.0  # held: the polynomial carries the scale
    # (the coefficients themselves trade off against the backlash's offset: check outputs)
    x2 = 0.6 * np.sin(2 * np.pi * 0.4 * t + 0.3)
    assert _rmse(fit.predict(t, x2), truth.simulate(t, x2)) < 0.01 * np.ptp(y)
    again = ts.load_model(fit.model.to_json())
    assert np.allclose(again.simulate(t, x2), fit.predict(t, x2))


def test_chain_beats_its_first_model_on_a_saturating_plant():
    t, x, y = plant_log(n=500)
    k = 250
    chain = ts.identify(
        Chain(BoucWenBacklash(), Polynomial(3)), t[:k], x[:k], y[:k], maxiter=30, progress=False
    )
    alone = ts.identify(BoucWenBacklash, t[:k], x[:k], y[:k], maxiter=30, progress=False)
    e_chain = _rmse(chain.predict(t, x)[k:], y[k:])
    e_alone = _rmse(alone.predict(t, x)[k:], y[k:])
    assert e_chain < 0.5 * e_alone
    assert e_chain < 0.02 * np.ptp(y)


def test_chain_odd_polynomial_and_errors():
    t, x, y = plant_log(n=300, saturate=False)
    fit = ts.identify(
        Chain(BoucWenBacklash(), Polynomial(3, odd=True)), t, x, y, maxiter=15, progress=False
    )
    assert len(fit.model.params["second.coefficients"]) == 2 and fit.nrmse < 0.02
    with pytest.raises(ValueError, match="second model must be a Polynomial"):
        ts.identify(Chain(BoucWenBacklash(), BoucWenBacklash()), t, x, y, progress=False)
    with pytest.raises(ValueError, match="first model is GeneralizedPrandtlIshlinskii"):
        ts.identify(Chain(GeneralizedPrandtlIshlinskii(), Polynomial(2)), t, x, y, progress=False)


def test_gpi_fits_an_asymmetric_saturated_plant_loop_and_stays_invertible():
    t, x, y = plant_log(n=500)
    k = 250
    fit = ts.identify(GeneralizedPrandtlIshlinskii, t[:k], x[:k], y[:k], maxiter=40, progress=False)
    p = fit.model.params
    assert len(p["thresholds"]) == 10 and p["thresholds"][0] == 0.0
    assert min(p["weights"]) >= 0.0 and p["weights"][0] > 0.0  # bounded least squares
    assert p["rising_a"] == 1.0
    pred = fit.predict(t, x)
    assert _rmse(pred[k:], y[k:]) < 0.02 * np.ptp(y)
    # an affine map is much worse on the same loop
    A = np.column_stack([np.ones(k), x[:k]])
    b, a = np.linalg.lstsq(A, y[:k], rcond=None)[0]
    assert _rmse(pred[k:], y[k:]) < 0.3 * _rmse(a * x[k:] + b, y[k:])
    # the identified operator is invertible: inverse(forward(x)) == x inside its range
    u = fit.model.inverse().simulate(t, pred)
    assert _rmse(u, x) < 1e-3 * np.ptp(x)


def test_gpi_recovers_the_output_of_a_known_gpi():
    t = np.linspace(0, 6, 500)
    x = 1.2 * np.sin(2 * np.pi * t / 3)
    truth = GeneralizedPrandtlIshlinskii(
        rising=(1.0, 1.5, 0.1, 0.0),
        falling=(0.8, 1.2, -0.1, 0.05),
        thresholds=np.arange(10) / 10 * 0.6,
        weights=[0.8, 0.3, 0.2, 0.1, 0.1, 0.05, 0.05, 0.02, 0.0, 0.0],
    )
    y = truth.simulate(t, x)
    fit = ts.identify(GeneralizedPrandtlIshlinskii, t, x, y, maxiter=60, progress=False)
    assert fit.nrmse < 0.01
    x2 = 0.9 * np.sin(2 * np.pi * t / 2 + 0.5)
    assert _rmse(fit.predict(t, x2), truth.simulate(t, x2)) < 0.03 * np.ptp(y)


def test_gpi_refuses_angle_laws_and_fixed_parameters():
    t, x, y = plant_log(n=100)
    with pytest.raises(ValueError, match="cannot depend on the curve angle"):
        ts.identify(
            GeneralizedPrandtlIshlinskii,
            recordings=[(t, x, y, 1.0)],
            depends_on_angle={"rising_b": "linear"},
            progress=False,
        )
    with pytest.raises(ValueError, match="fixed parameters are not supported"):
        ts.identify(GeneralizedPrandtlIshlinskii, t, x, y, fixed={"rising_b": 1.0}, progress=False)
