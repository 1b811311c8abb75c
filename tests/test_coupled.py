"""Coupled joints (issue 25, step 15 item 2): the Coupled model, identify_coupled on a coupled
physics plant, CoupledFeedforward, CoupledPlant and the Newey-West standard errors."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from scipy.signal import lfilter

import tendonsheath as ts
from tendonsheath.compensate import CoupledFeedforward, InverseFeedforward
from tendonsheath.identify import identify_coupled
from tendonsheath.identify.coupled import _newey_west
from tendonsheath.models import Backlash, BoucWenBacklash, Coupled

C10 = 0.25  # the idler on joint 0's axis over joint 1's distal pulley radius
RIG = dict(pretension=20.0, proximal_radius=15e-3, distal_radius=15e-3, elements=40)
ROUTES = (
    ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2)]),
    ts.Route.arcs([(0.4, 0.0), (0.6, 3 * math.pi / 4)]),
)


def wrist(seed: int) -> ts.CoupledPlant:
    """Two realistic pull-pull drives (outside every model class), joint 1's cable over an
    idler on joint 0's axis, noisy quantised encoders on both joints."""
    plants = [
        ts.PullPullPlant(r, **RIG, **ts.presets.realistic_plant(friction=0.1, stiffness=5e3))
        for r in ROUTES
    ]
    sensors = [ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=seed + k) for k in range(2)]
    return ts.CoupledPlant(plants, [[0.0, 0.0], [C10, 0.0]], sensors=sensors)


@pytest.fixture(scope="module")
def calibrated():
    """A 12 s calibration log of both joints, excited independently, and its fit."""
    t = np.arange(0.0, 12.0, 1e-3)
    x = np.column_stack(
        [
            1.1 * np.sin(2 * np.pi * 0.35 * t) * (1 - 0.5 * np.sin(np.pi * t / 12.0)),
            0.9 * np.sin(2 * np.pi * 0.61 * t + 1.0) * (1 - 0.4 * np.cos(np.pi * t / 12.0)),
        ]
    )
    log = wrist(1).simulate(t, x)
    with warnings.catch_warnings():  # the realistic drives put n at its bound: not checked here
        warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
        return identify_coupled(BoucWenBacklash, t, log.command, log.measured, warmup=1000, seed=0)


def test_coupling_recovered_within_its_standard_error(calibrated):
    fit = calibrated
    c10, se10 = fit.coupling[1, 0], fit.coupling_se[1, 0]
    c01, se01 = fit.coupling[0, 1], fit.coupling_se[0, 1]
    # measured on this log: C[1,0] = 0.25016 +/- 0.00046 (0.35 SE off), C[0,1] = -0.00009 +/-
    # 0.00015 (0.6 SE); over four 12 s designs (excitation frequencies) C[1,0] stayed within
    # 0.9 SE and C[0,1] within 2.4 SE (the misfit of each joint's own model is deterministic,
    # so what the SE covers is how the design samples it): 2 and 3 SE leave that room
    assert abs(c10 - C10) <= 2 * se10, fit.report()
    assert abs(c01) <= 3 * se01, fit.report()  # no cable of joint 0 runs over joint 1
    assert 0 < se10 < 0.005 and 0 < se01 < 0.005, fit.report()
    assert fit.lags[1][0] > 10  # the residuals of a hysteresis fit are autocorrelated
    assert np.isnan(fit.coupling_se[0, 0]) and fit.coupling[0, 0] == 0.0
    assert "C[1,0]" in fit.report()


def test_coupled_compensator_beats_independent_ones_on_a_new_route(calibrated):
    model = calibrated.model
    t = np.arange(0.0, 8.0, 1e-3)
    y_d = np.column_stack(
        [
            0.7 * np.sin(2 * np.pi * 0.4 * t) + 0.1 * np.sin(2 * np.pi * 1.1 * t),
            -0.6 * np.sin(2 * np.pi * 0.3 * t + 0.5) + 0.6 * np.sin(0.5),
        ]
    )
    plant = wrist(7)
    err = {}
    for name, m in (("coupled", model), ("independent", model.with_coupling(np.zeros((2, 2))))):
        u = CoupledFeedforward(m, smoothing=0.03).command(t, y_d)
        e = plant.simulate(t, u).q_out[500:] - y_d[500:]
        err[name] = np.sqrt(np.mean(e**2, axis=0))
    # measured: joint 1 36x better here (benchmarks/coupled.py: 29.5x median, 23.4x min over 5
    # route seeds); 10x leaves margin
    assert err["coupled"][1] < err["independent"][1] / 10, err
    # joint 0 has no coupling (C[0,1] about 1e-4): the two compensators agree there
    assert err["coupled"][0] == pytest.approx(err["independent"][0], rel=0.05), err
    assert err["coupled"][1] < 0.005, err  # 3.4e-3 rad measured


@pytest.mark.parametrize("seed", range(5))
def test_coupled_model_and_its_inverse(seed):
    """For random Backlash joints and couplings, simulate solves y = h + C y, predict on its
    own output returns it, and the feedforward's commands make the model follow y_d."""
    rng = np.random.default_rng(seed)
    joints = 3
    # equal slopes: with unequal ones a Backlash's branches cross inside the range (the model
    # itself stops being a backlash there, and no inverse can follow it)
    gains = rng.uniform(0.8, 1.2, joints)
    models = [
        Backlash(c_r=g, c_l=g, B_r=rng.uniform(0.01, 0.1), B_l=rng.uniform(0.01, 0.1))
        for g in gains
    ]
    c = rng.uniform(-0.3, 0.3, (joints, joints))
    np.fill_diagonal(c, 0.0)
    model = Coupled(models, c)
    t = np.arange(0.0, 4.0, 1e-3)
    x = np.column_stack([rng.uniform(0.5, 1) * np.sin(2 * np.pi * f * t) for f in (0.5, 0.7, 1.1)])
    y = model.simulate(t, x)
    h = model.own(t, x)
    np.testing.assert_allclose(y - y @ c.T, h, atol=1e-12)
    np.testing.assert_allclose(model.predict(t, x, y), y, atol=1e-12)
    y_d = np.column_stack([0.5 * np.sin(2 * np.pi * f * t) for f in (0.4, 0.6, 0.9)])
    ff = CoupledFeedforward(model, smoothing=0.002, input_range=None)
    u = ff.command(t, y_d)
    # the smoothed branch switch costs a little at each reversal (measured over these seeds:
    # at most 3.3e-5 rad, RMS 8.7e-7); ignoring the coupling would miss by about 0.1 rad
    e = (model.simulate(t, u) - y_d)[10:]
    assert np.max(np.abs(e)) < 2e-4
    assert np.sqrt(np.mean(e**2)) < 1e-5
    # streaming gives the batch's commands
    ff.reset()
    streamed = np.array([ff.step(y_d[k], 1e-3 if k else 0.0) for k in range(200)])
    np.testing.assert_allclose(streamed, u[:200], atol=1e-9)


def test_coupled_plant_is_its_drives_plus_the_idlers():
    """y = q + K y, with q each drive's own output, and no coupling gives the drives alone."""
    t = np.arange(0.0, 3.0, 1e-3)
    x = np.column_stack([np.sin(2 * np.pi * 0.5 * t), 0.8 * np.sin(2 * np.pi * 0.8 * t)])
    k = np.array([[0.0, -0.1], [0.3, 0.0]])
    run = ts.CoupledPlant([ts.PullPullPlant(r, **RIG) for r in ROUTES], k).simulate(t, x)
    np.testing.assert_allclose(run.q_out, run.drive + run.q_out @ k.T, atol=1e-12)
    alone = ts.PullPullPlant(ROUTES[1], **RIG).simulate(t, x[:, 1])
    np.testing.assert_allclose(run.drive[:, 1], alone, atol=1e-12)
    np.testing.assert_array_equal(run.measured, run.q_out)  # no sensors: exact
    plant = ts.CoupledPlant([ts.PullPullPlant(r, **RIG) for r in ROUTES], k)
    plant.reset()
    streamed = np.array([plant.step(x[i], 1e-3 if i else 0.0) for i in range(300)])
    np.testing.assert_allclose(streamed, run.q_out[:300], atol=1e-9)


def test_newey_west_matches_the_sampling_spread_under_autocorrelation():
    """A regression with AR(1) regressor and errors (rho 0.9): the Newey-West standard error is
    near the spread of the estimates over 300 draws, the i.i.d. formula 3x too small."""
    rng = np.random.default_rng(0)
    n, est, nw = 2000, [], []
    for _ in range(300):
        x = lfilter([1], [1, -0.9], rng.standard_normal(n))
        y = 0.5 + C10 * x + lfilter([1], [1, -0.9], rng.standard_normal(n))
        a = np.column_stack([np.ones(n), x])
        b = np.linalg.lstsq(a, y, rcond=None)[0]
        est.append(b[1])
        nw.append(_newey_west(a, y - a @ b, 1, None)[0][0])
    spread = np.std(est)
    # measured: mean NW SE 0.064 for a spread of 0.069 (NW runs a little low in small samples)
    assert 0.75 * spread < np.mean(nw) < 1.25 * spread
    # white residuals and no lags: the HC0 sandwich (X'X)^-1 X' diag(r^2) X (X'X)^-1
    r = rng.standard_normal(n)
    bread = np.linalg.inv(a.T @ a)
    hc0 = bread @ (a.T * r**2) @ a @ bread
    np.testing.assert_allclose(_newey_west(a, r, 2, 0)[0], np.sqrt(np.diag(hc0)), rtol=1e-10)


def test_round_trip_and_bad_inputs(tmp_path):
    model = Coupled([Backlash(), Backlash(B_r=0.02, B_l=0.03)], [[0, 0.1], [0.25, 0]])
    back = Coupled.load(model.to_json(tmp_path / "coupled.json"))
    np.testing.assert_array_equal(back.coupling, model.coupling)
    assert [m.params for m in back.models] == [m.params for m in model.models]
    with pytest.raises(ValueError, match="diagonal"):
        Coupled([Backlash(), Backlash()], [[0.1, 0], [0, 0]])
    with pytest.raises(ValueError, match="singular"):
        Coupled([Backlash(), Backlash()], [[0, 1], [1, 0]])
    with pytest.raises(ValueError, match="2 x 2"):
        Coupled([Backlash(), Backlash()], [0.25])
    with pytest.raises(TypeError, match="joint 1"):
        Coupled([Backlash(), "backlash"], np.zeros((2, 2)))
    with pytest.raises(ValueError, match=r"shape \(n, 2\)"):
        model.simulate(None, np.zeros(10))
    with pytest.raises(ValueError, match="not a"):
        Coupled.from_dict({"format": "tendonsheath.model"})
    t = np.arange(100) * 1e-3
    with pytest.raises(ValueError, match="couple's diagonal"):
        identify_coupled(Backlash, t, np.zeros((100, 2)), np.zeros((100, 2)), couple=np.eye(2) > 0)
    with pytest.raises(ValueError, match="y must have shape"):
        identify_coupled(Backlash, t, np.zeros((100, 2)), np.zeros((100, 3)))
    with pytest.raises(ValueError, match="model classes"):
        identify_coupled([Backlash], t, np.zeros((100, 2)), np.zeros((100, 2)))
    with pytest.raises(TypeError, match="Coupled"):
        CoupledFeedforward(Backlash())
    with pytest.raises(ValueError, match="2 angles"):
        CoupledFeedforward(model).step([0.0, 0.1, 0.2], 1e-3)
    ff = CoupledFeedforward(model)
    held = [ff.step([0.1 * k, -0.05 * k], 1e-3)[0] for k in range(5)][-1]
    u = ff.step([math.nan, 0.3], 1e-3)  # a non-finite angle holds its joint only
    assert u[0] == held and math.isfinite(u[1])
    assert ff.status() & ts.Status.HELD_NONFINITE_INPUT
    with pytest.raises(TypeError, match="Sensor"):
        ts.CoupledPlant([ts.PullPullPlant(r, **RIG) for r in ROUTES], np.zeros((2, 2)), [1, 2])
    assert isinstance(CoupledFeedforward(model).joints[0], InverseFeedforward)


def test_coupled_runs_return_a_simulation_result_with_every_joints_flags():
    """Coupled.simulate and CoupledFeedforward.command give one SimulationResult (n, J) as
    every simulate and command does: its t, input and each sample's flags of all joints."""
    models = [Backlash(B_r=0.05, B_l=0.05), BoucWenBacklash(B_r=0.02, B_l=0.02)]
    model = Coupled(models, [[0.0, 0.0], [0.2, 0.0]])
    t = np.arange(0.0, 1.0, 1e-3)
    x = np.column_stack([np.sin(2 * np.pi * t), 0.5 * np.cos(2 * np.pi * t)])
    y = model.simulate(t, x)
    assert isinstance(y, ts.SimulationResult) and y.shape == (t.size, 2)
    np.testing.assert_array_equal(y.t, t)
    np.testing.assert_array_equal(y.input, x)
    own = [m.simulate(t, x[:, i]).status for i, m in enumerate(models)]
    assert y.status.dtype == np.uint8
    np.testing.assert_array_equal(y.status, own[0] | own[1])
    # commands beyond the limits are saturated: those cycles say so
    ff = CoupledFeedforward(model, input_range=None, limits=(-0.3, 0.3))
    y_d = np.column_stack([0.3 * np.sin(2 * np.pi * t), 0.2 * np.sin(4 * np.pi * t)])
    u = ff.command(t, y_d)
    assert isinstance(u, ts.SimulationResult) and u.shape == (t.size, 2)
    np.testing.assert_array_equal(u.input, y_d)
    saturated = (u.status & ts.Status.SATURATED) != 0
    assert u.status.shape == (t.size,) and 0 < saturated.sum() < t.size
    np.testing.assert_array_equal(saturated, np.any(np.abs(u) >= 0.3, axis=1))
    # streaming gives the same flags, cycle by cycle
    ff.reset()
    flags = []
    for k in range(t.size):
        ff.step(y_d[k], 1e-3 if k else 0.0)
        flags.append(int(ff.status()))
    np.testing.assert_array_equal(u.status, flags)
