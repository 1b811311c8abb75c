"""Regression tests for the real-time audit's minimal cases (Step 10 reproducers): each failed
before its fix. The fixes are in the mechanisms (bounds validated or clamped and flagged, a
non-finite solution never committed, stable integrators), not in special cases."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core


def test_pi_inverse_stays_finite_and_exact_after_extreme_targets():
    """Item 1: step(1e308), step(-1e308) overflowed the play sums (-inf, then NaN forever)."""
    model = ts.models.PrandtlIshlinskii.uniform(0.4, 8)
    inv = model.inverse()
    for target in (1e308, -1e308, 1.7e308, -math.inf, math.nan, -1e308):
        assert math.isfinite(inv.step(target))
    # after the extremes the plays come back exactly: a sweep beyond every threshold wipes
    # the memory of both operators, and from there forward(inverse(y)) == y
    wipe = np.concatenate([np.linspace(0.0, 3.0, 60), np.linspace(3.0, -3.0, 120)])
    targets = np.concatenate([wipe, 0.3 * np.sin(np.linspace(0, 6 * np.pi, 300))])
    xs = [inv.step(float(y)) for y in targets]
    fwd = model
    fwd.reset()
    ys = np.array([fwd.step(x) for x in xs])
    assert np.all(np.isfinite(ys))
    np.testing.assert_allclose(ys[wipe.size :], targets[wipe.size :], atol=1e-9)


@pytest.mark.parametrize("first", [0.0, None])
def test_friction_chain_never_commits_a_non_finite_solution(first):
    """Item 2: SingleTendonPlant step(0); step(1e307) and PullPullPlant step(1e307) returned
    NaN / inf and stayed non-finite: a NaN solution had no 'violations' and was committed."""
    single = ts.SingleTendonPlant(ts.Route.uniform(1.0, 1.0))
    pair = ts.PullPullPlant(ts.Route.uniform(1.0, 1.0))
    for plant in (single, pair):
        plant.reset()
        if first is not None:
            plant.step(first)
        y = plant.step(1e307)
        assert math.isfinite(y)
        assert plant.input_clamped()
        assert ts.Status.INPUT_CLAMPED in plant.status()  # in-band
        plant.step(math.nan)
        assert plant.status() & ts.Status.HELD_NONFINITE_INPUT
        ys = [plant.step(v) for v in np.linspace(0.0, 0.01, 50)]
        assert np.all(np.isfinite(ys)) and np.all(np.isfinite(plant.tensions()))
        assert not plant.input_clamped()


@pytest.mark.filterwarnings("ignore::tendonsheath.SlackWarning")
def test_huge_node_friction_angles_leave_no_zero_pivot():
    """Item 3: per-node angles >= 381 rad (or a huge friction) made tanh(mu dtheta / 2) round to
    exactly 1 and the tridiagonal solve hit an exact zero pivot (NaN outputs). Such a sheath
    locks and one tendon goes slack (warned): the point is that the numbers stay finite."""
    # the audit's cases: per-node angles of 381 rad (N - 1 nodes), sines of 0.5 and 2 rad
    for friction, elements, amplitude in ((0.1, 100, 0.5), (1.0, 40, 2.0), (10.0, 100, 2.0)):
        total = 381.0 * (elements - 1)
        plant = ts.ContinuumPlant(
            ts.Route.uniform(1.0, total), friction=friction, elements=elements
        )
        y = plant.simulate(None, amplitude * np.sin(np.linspace(0, 4 * np.pi, 400)))
        assert np.all(np.isfinite(y)), (friction, elements, amplitude)


def test_motor_stays_finite_and_settles_after_a_huge_step():
    """Item 4: step(0); step(1e6, dt=1e300) poisoned the position motor (NaN for ever after)."""
    for motor in (
        ts.Motor.position(10.0, 0.7),
        ts.Motor.torque(0.01, 0.2),
        ts.Motor.torque(0.01, 0.0),
    ):
        engine = motor.engine()  # the bare C++ motor
        engine.step(0.0, 0.0)
        q = engine.step(1e6, 1e300)
        assert math.isfinite(q) and engine.clamped()
        later = [engine.step(0.1, 1e-3) for _ in range(100)]
        assert np.all(np.isfinite(later))
    servo = ts.Motor.position(10.0, 0.7).engine()
    servo.step(0.0, 0.0)
    assert servo.step(1.0, 1e300) == pytest.approx(1.0, abs=1e-9)  # a lag settles at its command


def test_curve_angle_feedforwards_do_not_freeze_at_large_friction_angles():
    """Item 5: mu Theta >= 37.43 divided by zero in uniform_shape and froze the command. Up to
    the accepted limit (mu Theta <= 50) the command follows the reference; beyond it the
    constructor names the parameter and its largest value, and a streamed angle is clamped."""
    y_d = np.linspace(0.0, 0.5, 20)
    ff = ts.compensate.CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=450.0)  # mu Theta 45
    u = [ff.step(float(y), 1e-3) for y in y_d]
    assert np.all(np.isfinite(u)) and np.all(np.diff(u) > 0)
    with pytest.raises(ValueError, match=r"curve_angle must be <= 500 rad"):
        ts.compensate.CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, curve_angle=600.0)
    ff = ts.compensate.CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0)
    ff.set_curve_angle(1e4)
    assert ff.angle_clamped()
    u = []
    for y in y_d:
        u.append(ff.step(float(y), 1e-3))
        assert ff.status() == ts.Status.INPUT_CLAMPED  # in-band, each cycle
    assert np.all(np.isfinite(u)) and np.all(np.diff(u) > 0)
    ff.set_curve_angle(math.pi)
    ff.step(0.6, 1e-3)
    assert ff.status() == ts.Status.OK
    with pytest.raises(ValueError, match=r"curve_angle must be <= 500 rad"):
        ts.compensate.ContinuumFeedforward(friction=0.1, curve_angle=1e3)


def test_adaptive_controller_recovers_from_a_long_cycle():
    """Item 6: one cycle with dt >= 4 s and a measurement change made the derivative filter NaN,
    and the controller then returned exactly 0 torque for ever."""
    bwb = ts.models.BoucWenBacklash(c_r=1.0, c_l=1.0, B_r=0.1, B_l=0.1, n=6)
    ctrl = ts.compensate.AdaptiveController.from_model(bwb, inertia=0.01, viscous=0.2)
    ctrl.reset()
    ctrl.step(0.0, 0.0, 0.0, 1e-3)
    ctrl.step(0.1, 0.01, 0.0, 5.0)
    torques = [ctrl.step(0.2, 0.02 + 1e-4 * k, 0.0, 1e-3) for k in range(200)]
    assert np.all(np.isfinite(torques))
    assert np.ptp(torques) > 0.0 and abs(torques[-1]) > 0.0
    # in-band: a lost measurement is the fallback, a torque at its limit is saturated
    engine = ctrl
    engine.step(0.2, math.nan, 0.0, 1e-3)
    assert ts.Status.FALLBACK in ts.Status(engine.status())
    engine.step(math.nan, 0.02, 0.0, 1e-3)
    assert ts.Status.HELD_NONFINITE_INPUT in ts.Status(engine.status())
    limited = ts.compensate.AdaptiveController.from_model(
        bwb, inertia=0.01, viscous=0.2, max_torque=1e-3
    )
    limited.step(0.0, 0.0, 0.0, 1e-3)
    limited.step(1.0, 0.0, 0.0, 1e-3)
    assert ts.Status(limited.status()) == ts.Status.SATURATED


def test_chain_options_have_upper_bounds():
    """Item 8: max_iterations = max_substeps = INT_MAX passed validation and overflowed the solve
    budget (signed overflow); the message names the parameter and the largest value."""
    for name in ("max_iterations", "max_substeps", "extra_iterations"):
        options = core.ChainOptions()
        setattr(options, name, 2**31 - 1)
        params = core.PullPullParams()
        params.options = options
        with pytest.raises(ValueError, match=rf"{name} must be .*100000\]"):
            route = ts.Route.uniform(1.0, 1.0)
            core.PullPullPlant(params, route, route)


def test_gpi_inverse_commands_stay_in_the_envelopes_range():
    """Item 7: an unreachable target commanded about 1e8 rad, and an envelope gain b = 1e-300
    (accepted) about 4e307. The command now stops where the envelopes saturate (flagged), and
    validation names b and the smallest gain it accepts."""
    model = ts.models.GeneralizedPrandtlIshlinskii(
        rising=(1.0, 1.0, 0.0, 0.0),
        falling=(1.0, 1.0, 0.0, 0.0),
        thresholds=[0.0, 0.2],
        weights=[1.0, 0.5],
    )
    inv = model.inverse()
    for target in (0.3, 100.0, -100.0, 1e300):
        x = inv.step(target)
        assert abs(x) <= 40.0 + 1e-9, (target, x)  # c +- 40/b with c = 0, b = 1
    assert inv.input_clamped()
    inv.step(0.1)
    assert not inv.input_clamped()
    with pytest.raises(ValueError, match=r"rising.b must be >= 1e-09"):
        ts.models.GeneralizedPrandtlIshlinskii(
            rising=(1.0, 1e-300, 0.0, 0.0),
            falling=(1.0, 1.0, 0.0, 0.0),
            thresholds=[0.0],
            weights=[1.0],
        )


# -- issue 16, item 10: the smaller defects ------------------------------------------------


def test_bouc_wen_has_one_name_per_parameter_and_its_old_files_load():
    """A is the amplitude, alpha the linear share (it was `a`, beside `A`): a file written
    before the rename still loads; the old keyword a= is gone (0.x)."""
    names = ts.models.BoucWen.param_names
    assert "alpha" in names and "a" not in names
    rng = np.random.default_rng(3)
    x = np.cumsum(rng.normal(0.0, 0.05, 500))
    for alpha in (0.0, 0.25, 0.9):
        new = ts.models.BoucWen(A=1.2, beta=1.0, gamma=0.2, n=1.5, alpha=alpha, k=0.7)
        assert new.params["alpha"] == alpha
        # y = alpha x + (1 - alpha) k z: alpha is the slope of the linear path
        z = ts.models.BoucWen(A=1.2, beta=1.0, gamma=0.2, n=1.5, alpha=0.0, k=1.0).simulate(None, x)
        np.testing.assert_allclose(new.simulate(None, x), alpha * x + (1 - alpha) * 0.7 * z)
        data = new.to_dict()
        data["params"]["a"] = data["params"].pop("alpha")  # a file written before the rename
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            assert ts.load_model(data) == new
            assert ts.models.BoucWen.from_dict(data) == new
    with pytest.raises(TypeError, match=r"unknown parameter\(s\) \['a'\]"):
        ts.models.BoucWen(a=0.3)
    with pytest.raises(ValueError, match=r"BoucWen: alpha must be in \[0, 1\]"):
        ts.models.BoucWen(alpha=1.5)


def test_backlash_inverse_feedforward_names_itself_in_errors():
    ff = core.BacklashInverseFeedforward(core.BacklashInverseParams())
    t = np.array([0.0, 0.1, 0.1])
    with pytest.raises(ValueError, match=r"^BacklashInverseFeedforward: time is not strictly"):
        ff.command(t, np.zeros(3))
    lim = core.CommandLimits()
    lim.min, lim.max = 1.0, 0.0
    with pytest.raises(ValueError, match=r"^PrandtlIshlinskiiFeedforward: command limits"):
        pi = core.PrandtlIshlinskiiParams()
        pi.thresholds, pi.weights = [0.0, 0.1], [0.6, 0.4]
        core.PrandtlIshlinskiiFeedforward(pi, lim)
    p = core.BacklashInverseParams()
    p.limits = lim
    with pytest.raises(ValueError, match=r"^BacklashInverseFeedforward: command limits"):
        core.BacklashInverseFeedforward(p)


def test_plants_flag_a_step_the_chain_did_not_take():
    """The plants keep FrictionChain::step's result: a held input is flagged in-band, and the
    output stays the last one, in streaming and per sample."""
    for plant in (
        ts.SingleTendonPlant(route=ts.Route.uniform(1.0, 2.0), elements=20),
        ts.PullPullPlant(route=ts.Route.uniform(1.0, 2.0), elements=20),
        ts.ContinuumPlant(elements=20),
    ):
        y = plant.step(0.01, 1e-3)
        assert plant.status() == ts.Status.OK
        assert plant.step(math.inf, 1e-3) == y
        assert plant.status() == ts.Status.HELD_NONFINITE_INPUT
        assert plant.last_converged()
