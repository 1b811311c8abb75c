"""Plant API: bad input, streaming == batch, slack, route changes, results, plots."""

import warnings

import numpy as np
import pytest

import tendonsheath as ts

ROUTE = ts.Route.uniform(1.2, 2 * np.pi)


def sine(n=3000, amp=0.4, f=0.5, dt=1e-3):
    t = np.arange(n) * dt
    return t, amp * np.sin(2 * np.pi * f * t)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (dict(friction=-0.1), "friction must be >= 0"),
        (dict(friction=float("nan")), "friction"),
        (dict(stiffness=0.0), "stiffness must be > 0"),
        (dict(stiffness=-2.0), "stiffness must be > 0"),
        (dict(pretension=0.0), "pretension must be > 0"),
        (dict(proximal_radius=-1e-3), "proximal_radius must be > 0"),
        (dict(distal_radius=0.0), "distal_radius must be > 0"),
        (dict(elements=1), "elements must be >= 2"),
    ],
)
def test_pull_pull_rejects_bad_parameters(kwargs, message):
    with pytest.raises(ValueError, match=message):
        ts.PullPullPlant(route=ROUTE, **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        (dict(elements=2.5), "elements must be an integer"),
        (dict(load=ts.loads.ConstantForce(3.0)), "load must be None, ConstantTorque"),
        (dict(motor="fast"), "motor must be"),
    ],
)
def test_pull_pull_rejects_wrong_types_with_a_type_error(kwargs, message):
    with pytest.raises(TypeError, match=message):
        ts.PullPullPlant(route=ROUTE, **kwargs)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: ts.loads.TorsionalSpring(-1.0), "k must be >= 0"),
        (lambda: ts.loads.SpringDamper(1.0, -0.1), "c must be >= 0"),
        (lambda: ts.loads.ConstantTorque(float("inf")), "tau must be finite"),
        (lambda: ts.loads.ConstantForce(0.0), "F must be > 0"),
        (lambda: ts.loads.LinearSpring(-5.0), "k must be > 0"),
        (lambda: ts.SingleTendonPlant(ROUTE, friction=-1), "friction must be >= 0"),
        (lambda: ts.SingleTendonPlant(ROUTE, elements=0), "elements must be >= 2"),
        (lambda: ts.ContinuumPlant(bending_stiffness=-1.0), "bending_stiffness must be > 0"),
        (lambda: ts.ContinuumPlant(tendon_offset=0.0), "tendon_offset must be > 0"),
    ],
)
def test_other_bad_input(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_a_route_of_the_wrong_type_is_a_type_error():
    with pytest.raises(TypeError, match="must be a tendonsheath.Route"):
        ts.PullPullPlant(route="semicircle")


def test_non_finite_commands_and_time_are_rejected_in_batch():
    plant = ts.PullPullPlant(route=ROUTE, elements=20)
    t, q = sine(100)
    q[17] = np.nan
    with pytest.raises(ValueError, match=r"x\[17\] is not finite"):
        plant.simulate(t, q)
    _, q = sine(100)
    t2 = t.copy()
    t2[5] = t2[4]
    with pytest.raises(ValueError, match="strictly increasing"):
        plant.simulate(t2, q)
    with pytest.raises(ValueError, match="different lengths"):
        plant.simulate(t[:50], q)
    with pytest.raises(ValueError, match="t is required"):
        ts.PullPullPlant(route=ROUTE, motor=ts.Motor.position()).simulate(None, q)


def test_streaming_holds_on_non_finite_input():
    plant = ts.PullPullPlant(route=ROUTE, elements=20)
    y = plant.step(0.3)
    assert plant.step(float("nan")) == y
    assert plant.step(float("inf")) == y
    assert np.isfinite(plant.step(0.2))


@pytest.mark.parametrize("kind", ["pull_pull", "continuum", "single"])
def test_streaming_equals_batch(kind):
    t, q = sine(2500)
    if kind == "pull_pull":
        plant = ts.PullPullPlant(route=ROUTE, elements=40, load=ts.loads.SpringDamper(0.01, 1e-4))
    elif kind == "continuum":
        plant = ts.ContinuumPlant(elements=40)
    else:
        plant = ts.SingleTendonPlant(
            route=ROUTE, elements=40, load=ts.loads.SpringPreload(500.0, 5.0)
        )
        q = 2e-3 * (1 + np.sin(2 * np.pi * 0.5 * t))
    y_batch = plant.simulate(t, q)
    plant.reset()
    y_stream = [plant.step(q[0], 0.0)] + [
        plant.step(q[k], t[k] - t[k - 1]) for k in range(1, len(q))
    ]
    np.testing.assert_array_equal(y_batch, y_stream)
    T = plant.tensions()
    S = plant.slip_state()
    rows = 1 if kind == "single" else 2
    assert T.shape == ((40,) if rows == 1 else (2, 40))
    assert S.shape == ((39,) if rows == 1 else (2, 39))
    assert set(np.unique(S)) <= {-1, 0, 1}


def test_simulate_does_not_disturb_streaming_state():
    plant = ts.PullPullPlant(route=ROUTE, elements=20)
    plant.step(0.3)
    before = plant.tensions().copy()
    plant.simulate(*sine(500))
    np.testing.assert_array_equal(plant.tensions(), before)


def test_slack_is_flagged_and_warned_with_time():
    plant = ts.PullPullPlant(
        route=ROUTE, elements=30, pretension=2.0, load=ts.loads.ConstantTorque(20 * 5e-3)
    )
    t = np.arange(400) * 1e-3
    q = np.linspace(0, 1.0, 400)
    with pytest.warns(ts.SlackWarning, match=r"first at t = 0 s"):
        res = plant.simulate(t, q)
    assert isinstance(res, ts.SimulationResult)
    assert res.any_slack and res.first_slack_index == 0
    assert not res.success and "slack" in res.message
    assert res.slack.dtype == bool and res.slack.shape == q.shape
    # a load that becomes too large only late: the first slack time is reported
    plant = ts.PullPullPlant(route=ROUTE, elements=30, load=ts.loads.TorsionalSpring(0.05))
    q = np.linspace(0, 3.0, 400)
    with pytest.warns(ts.SlackWarning) as record:
        res = plant.simulate(t, q)
    k = res.first_slack_index
    assert k is not None and k > 0 and not res.slack[:k].any()
    assert f"t = {t[k]:.6g} s" in str(record[0].message)


def test_no_warning_without_slack():
    plant = ts.PullPullPlant(route=ROUTE, elements=30)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        res = plant.simulate(*sine(1000))
    assert not res.any_slack and res.success and res.message == ""
    assert res.nonconverged == 0
    np.testing.assert_array_equal(res.q_in, res.command)
    np.testing.assert_array_equal(res.measured, res.q_out)
    assert res.tensions.shape == (2, 30)


def test_set_route_changes_the_response_and_checks_length():
    plant = ts.PullPullPlant(route=ts.Route.uniform(1.2, 0.5), elements=50)
    t, q = sine(2000)
    y_low = plant.simulate(t, q)
    plant.set_route(ts.Route.uniform(1.2, 3 * np.pi))
    y_high = plant.simulate(t, q)
    assert np.abs(y_high - q).max() > 2 * np.abs(y_low - q).max()
    with pytest.raises(ValueError, match="may bend, not change length"):
        plant.set_route(ts.Route.uniform(1.0, 1.0))
    with pytest.raises(TypeError, match="must be a tendonsheath.Route"):
        plant.set_route(None)


def test_route_schedule_equals_streaming_set_route():
    a, b = ts.Route.uniform(1.2, np.pi / 2), ts.Route.arcs([(0.6, 0.5), (0.6, 5.0)])
    calls = []

    def routes(tk):
        calls.append(tk)
        return a if tk < 1.0 or tk >= 2.0 else b

    t, q = sine(3000)
    plant = ts.PullPullPlant(route=a, elements=40)
    y = plant.simulate(t, q, routes=routes)
    assert len(calls) == len(t)
    plant.reset()
    ys = []
    for k in range(len(t)):
        plant.set_route(routes(t[k]))
        ys.append(plant.step(q[k], 0.0 if k == 0 else 1e-3))
    np.testing.assert_allclose(y, ys, rtol=0, atol=1e-13)
    # a pair of routes per sheath is accepted too
    y2 = plant.simulate(t, q, routes=lambda tk: (a, b if tk > 1 else a))
    assert not np.allclose(y2, y)
    with pytest.raises(ValueError, match="routes must be None or a callable"):
        plant.simulate(t, q, routes=a)
    with pytest.raises(ValueError, match="may bend, not change length"):
        plant.simulate(t, q, routes=lambda tk: ts.Route.uniform(2.0, 1.0))


def test_closed_form_helpers_on_the_plant():
    plant = ts.PullPullPlant(
        route=ROUTE,
        friction=0.1,
        stiffness=2.4e4,
        pretension=10.0,
        distal_radius=3e-3,
        load=ts.loads.ConstantTorque(5.0 * 3e-3),
    )
    cf = plant.closed_form()
    # spec A.4 worked example: e_b = 0.152 mm, e_L = 0.121 mm, dead zone 0.10 rad at r_d=3 mm
    assert cf["backlash_half_width"] == pytest.approx(0.152e-3, rel=2e-3)
    assert cf["load_offset"] == pytest.approx(0.121e-3, rel=2e-3)
    assert cf["dead_zone"] / 3e-3 == pytest.approx(0.10, rel=0.02)
    single = ts.SingleTendonPlant(route=ROUTE, load=ts.loads.ConstantForce(5.0))
    a = 0.1 * 2 * np.pi
    assert single.closed_form()["dead_zone"] == pytest.approx(
        4 * 5.0 * 1.2 * np.sinh(a / 2) ** 2 / (2.4e4 * a)
    )


def test_tension_profile_plot(tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    from tendonsheath.plots import plot_tension_profile

    plant = ts.PullPullPlant(route=ts.Route.arcs([(0.6, 0.5), (0.6, 4.0)]), elements=50)
    for q in np.linspace(0, 0.3, 50):
        plant.step(q)
    for q in np.linspace(0.3, 0.28, 5):
        plant.step(q)
    ax = plant.plot_tensions()
    assert len(ax.lines) >= 2
    ax.figure.savefig(tmp_path / "tensions.png")
    assert (tmp_path / "tensions.png").stat().st_size > 1000
    single = ts.SingleTendonPlant(route=ROUTE, elements=20)
    plot_tension_profile(single)
