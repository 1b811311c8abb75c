"""HystereticOscillator identified from data of an independent integrator (SciPy's DOP853)."""

import numpy as np
from scipy.integrate import solve_ivp

import tendonsheath as ts

TRUE = dict(m=1.0, c=0.5, k=2.0, alpha=3.0, beta=1.0, gamma=0.6, delta=0.4, nu=1.0)


def _simulate_reference(t, force):
    p = TRUE

    def rhs(s, state):
        y, v, z = state
        u = force(s)
        az = abs(z)
        return [
            v,
            (u - p["c"] * v - p["k"] * y - z) / p["m"],
            p["alpha"] * v
            - p["beta"]
            * (p["gamma"] * abs(v) * az ** (p["nu"] - 1) * z + p["delta"] * v * az ** p["nu"]),
        ]

    sol = solve_ivp(
        rhs,
        (t[0], t[-1]),
        [0.0, 0.0, 0.0],
        t_eval=t,
        method="DOP853",
        rtol=1e-10,
        atol=1e-12,
        max_step=0.02,
    )
    assert sol.success
    return sol.y[0]


def _force(f1, f2, amp):
    return lambda s: (
        amp
        * (
            np.sin(2 * np.pi * f1 * s) * (0.6 + 0.4 * np.sin(2 * np.pi * 0.07 * s))
            + 0.4 * np.sin(2 * np.pi * f2 * s)
        )
    )


def test_oscillator_recovers_parameters_and_predicts_a_new_input():
    t = np.arange(0.0, 20.0, 0.01)
    u = _force(0.3, 0.77, 4.0)
    y = _simulate_reference(t, u)
    rng = np.random.default_rng(0)
    y_noisy = y + 0.002 * np.ptp(y) * rng.standard_normal(t.size)

    fit = ts.identify(ts.models.HystereticOscillator, t, u(t), y_noisy, maxiter=25, progress=False)
    assert fit.fixed == {"beta": 1.0}
    for name, se in fit.standard_errors.items():
        got = fit.model.params[name]
        assert abs(got - TRUE[name]) < max(4 * se, 0.02 * abs(TRUE[name])), (name, got, se)
        assert abs(got - TRUE[name]) < 0.05 * abs(TRUE[name]) + 1e-3, (name, got)

    t2 = np.arange(0.0, 15.0, 0.01)
    u2 = _force(0.2, 0.5, 3.0)
    y2 = _simulate_reference(t2, u2)
    val = fit.validate(t2, u2(t2), y2)
    assert val["nrmse"] < 0.01, val
