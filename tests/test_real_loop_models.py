"""Models for real loops: polynomial output map, chains, generalized Prandtl-Ishlinskii."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import models


def test_polynomial_matches_numpy(rng):
    for _ in range(20):
        coeffs = rng.normal(size=rng.integers(1, 6))
        u = rng.normal(size=200)
        full = models.Polynomial(coefficients=coeffs)
        np.testing.assert_allclose(
            full.simulate(None, u), np.polynomial.polynomial.polyval(u, coeffs)
        )
        odd = models.Polynomial(coefficients=coeffs, odd=True)
        expanded = np.zeros(2 * coeffs.size)
        expanded[1::2] = coeffs
        np.testing.assert_allclose(
            odd.simulate(None, u), np.polynomial.polynomial.polyval(u, expanded)
        )
        np.testing.assert_allclose(odd.basis(u) @ coeffs, odd.simulate(None, u))
    assert models.Polynomial(3).degree == 3
    assert models.Polynomial(5, odd=True).params["coefficients"] == [1.0, 0.0, 0.0]


def test_chain_is_the_composition():
    first = models.BoucWenBacklash(B_r=0.1, B_l=0.15, n=6)
    second = models.Polynomial(coefficients=[0.02, 1.1, 0.0, -0.3])
    chain = models.Chain(first, second)
    t = np.linspace(0, 5, 2001)
    x = 0.8 * np.sin(2 * np.pi * 0.5 * t)
    np.testing.assert_array_equal(chain.simulate(t, x), second.simulate(None, first.simulate(t, x)))
    changed = chain.with_params(**{"first.n": 9.0, "second.coefficients": [0.0, 1.0]})
    assert changed.first.params["n"] == 9.0 and changed.second.degree == 1
    with pytest.raises(TypeError, match="first.<name>"):
        chain.with_params(n=3)


def _random_gpi(rng):
    rising = (
        rng.uniform(0.8, 2.0),
        rng.uniform(0.5, 3.0),
        rng.uniform(-0.2, 0.2),
        rng.uniform(-0.2, 0.2),
    )
    falling = (
        rng.uniform(0.8, 2.0),
        rng.uniform(0.5, 3.0),
        rng.uniform(-0.2, 0.2),
        rng.uniform(-0.2, 0.2),
    )
    count = rng.integers(1, 8)
    thresholds = np.r_[0.0, np.cumsum(rng.uniform(0.02, 0.2, count - 1))]
    weights = np.r_[rng.uniform(0.3, 1.0), rng.uniform(0.0, 0.4, count - 1)]
    return models.GeneralizedPrandtlIshlinskii(rising, falling, thresholds, weights)


def test_generalized_pi_inverse_is_exact(rng):
    for _ in range(30):
        gpi = _random_gpi(rng)
        x = np.clip(np.cumsum(rng.normal(0, 0.05, 2000)), -0.8, 0.8)
        np.testing.assert_allclose(
            gpi.inverse().simulate(None, gpi.simulate(None, x)), x, atol=1e-9
        )


def test_generalized_pi_saturates_and_can_be_asymmetric():
    gpi = models.GeneralizedPrandtlIshlinskii(
        rising=(1.0, 2.0, 0.2, 0.0),
        falling=(0.6, 2.0, -0.2, 0.0),
        thresholds=[0, 0.1],
        weights=[1, 0.5],
    )
    x = np.r_[np.linspace(0, 4, 400), np.linspace(4, -4, 800)]
    y = gpi.simulate(None, x)
    top, bottom = y.max(), y.min()
    # saturated: centre line (1.0 + 0.6)/2 = 0.8, the r = 0.1 play at the rising envelope
    # 1.0 - 0.1 going up and at the falling one -0.6 + 0.1 coming down
    assert top == pytest.approx(0.8 + 0.5 * 0.9, rel=1e-3)
    assert bottom == pytest.approx(-0.8 - 0.5 * 0.5, rel=1e-3)
    assert np.max(np.abs(np.diff(y[-50:]))) < 1e-3  # flat in saturation


def test_generalized_pi_validation():
    with pytest.raises(ValueError, match="rising.a"):
        models.GeneralizedPrandtlIshlinskii(rising=(-1.0, 1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="thresholds\\[0\\] must be 0"):
        models.GeneralizedPrandtlIshlinskii(thresholds=[0.1, 0.2], weights=[1.0, 0.1])
    with pytest.raises(ValueError, match="weights\\[1\\]"):
        models.GeneralizedPrandtlIshlinskii(thresholds=[0.0, 0.2], weights=[1.0, -0.1])
    assert (
        ts.load_model(models.GeneralizedPrandtlIshlinskii().to_json())
        == models.GeneralizedPrandtlIshlinskii()
    )
