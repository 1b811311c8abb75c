"""Bad input to identify(): a clear ValueError."""

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.models import BoucWenBacklash, CurveAngleModel, HystereticOscillator

T = np.arange(0.0, 2.0, 0.01)
X = np.sin(2 * np.pi * T)
Y = 0.9 * X


@pytest.mark.parametrize(
    ("args", "kwargs", "pattern"),
    [
        ((T, np.ones_like(T), Y), {}, "input is constant"),
        ((T, X, np.zeros_like(T)), {}, "output is constant"),
        ((T[:10], X[:10], Y[:10]), {}, "too few samples"),
        ((T, X, Y), {"warmup": 500}, "warm-up"),
        ((T, np.where(T > 1, np.nan, X), Y), {}, r"input x has a non-finite value .* sample 101"),
        ((T, X, Y[:-1]), {}, "different lengths"),
        ((T[::-1], X, Y), {}, "not strictly increasing"),
        ((T, X, Y), {"fixed": {"bogus": 1.0}}, "unknown parameter"),
        ((T, X, Y), {"depends_on_angle": {"B_r": "cubic"}}, "'constant', 'linear' or 'tanh'"),
        ((T, X, Y), {"depends_on_angle": {"B_r": "tanh"}}, "curve angle"),
        ((T, X, Y), {"bounds": {"rho": (5.0, 1.0)}}, "lower < upper"),
    ],
)
def test_bad_input(args, kwargs, pattern):
    with pytest.raises(ValueError, match=pattern):
        ts.identify(BoucWenBacklash, *args, progress=False, **kwargs)


def test_model_specific_requirements():
    with pytest.raises(ValueError, match="rate-dependent"):
        ts.identify(HystereticOscillator, None, X, Y, progress=False)
    with pytest.raises(ValueError, match="curve angle"):
        ts.identify(CurveAngleModel, T, X, Y, progress=False)
    with pytest.raises(ValueError, match="unknown model"):
        ts.identify("Nonsense", T, X, Y, progress=False)
    with pytest.raises(ValueError, match="x and y"):
        ts.identify(BoucWenBacklash, T, X, progress=False)
