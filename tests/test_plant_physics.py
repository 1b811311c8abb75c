"""The plant against the closed forms of spec A, over many random parameter sets."""

import numpy as np
import pytest

import tendonsheath as ts
from reference import closed_forms as ref
from reference.plant import ReferencePullPull
from tendonsheath import physics


def ramp(plant, q0, q1, dq):
    n = max(int(np.ceil(abs(q1 - q0) / dq)), 1)
    y = None
    for q in np.linspace(q0, q1, n + 1)[1:]:
        y = plant.step(q)
    return y


def random_route(rng, L):
    kind = rng.integers(3)
    theta = rng.uniform(0.2, 4 * np.pi)
    if kind == 0:
        return ts.Route.uniform(L, theta)
    if kind == 1:
        w = rng.dirichlet(np.ones(3))
        f = rng.dirichlet(np.ones(3))
        return ts.Route.arcs([(L * wi, theta * fi) for wi, fi in zip(w, f, strict=True)])
    # curvature concentrated at the distal end (spec A.2 warning)
    return ts.Route.arcs([(0.9 * L, theta / 3), (0.1 * L, 2 * theta / 3)])


@pytest.mark.parametrize("seed", range(30))
def test_full_slip_capstan_ratio_single_tendon(seed):
    rng = np.random.default_rng(seed)
    L = rng.uniform(0.5, 2.0)
    route = random_route(rng, L)
    mu, EA, F = rng.uniform(0.05, 0.2), rng.uniform(5e3, 5e4), rng.uniform(2, 20)
    plant = ts.SingleTendonPlant(
        route=route, friction=mu, stiffness=EA, elements=60, load=ts.loads.ConstantForce(F)
    )
    travel = 3 * F * L * np.exp(mu * route.curve_angle) / EA
    ramp(plant, 0.0, travel, travel / 200)
    T = plant.tensions()
    # measured over the 30 seeds: worst 2.0e-12 (pull) and 1.0e-11 (release) relative,
    # round-off of the tension solve; 1e-10 is 10x above the worst
    assert T[-1] / T[0] == pytest.approx(np.exp(-mu * route.curve_angle), rel=1e-10)
    assert (plant.slip_state() == 1).all()
    # releasing: the ratio inverts
    ramp(plant, travel, -travel, travel / 100)
    T = plant.tensions()
    assert T[-1] / T[0] == pytest.approx(np.exp(mu * route.curve_angle), rel=1e-10)


@pytest.mark.parametrize("seed", range(20))
def test_pull_pull_offsets_match_A7_uniform(seed):
    rng = np.random.default_rng(100 + seed)
    L, theta = rng.uniform(0.5, 2.0), rng.uniform(0.1, 4 * np.pi)
    mu, EA, T0 = rng.uniform(0.05, 0.2), rng.uniform(5e3, 5e4), rng.uniform(2, 40)
    rp, rd = rng.uniform(3e-3, 10e-3, size=2)
    a = mu * theta
    FL = rng.uniform(-0.8, 0.8) * physics.no_slack_limit(T0, mu, theta)
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(L, theta),
        friction=mu,
        stiffness=EA,
        pretension=T0,
        proximal_radius=rp,
        distal_radius=rd,
        elements=200,
        load=ts.loads.ConstantTorque(FL * rd),
    )
    eb = ref.backlash_half_width(L, EA, T0, a)
    eL = ref.load_offset(L, EA, FL, a)
    assert physics.backlash_half_width(L, EA, T0, mu, theta) == pytest.approx(eb)
    assert physics.load_offset(L, EA, FL, mu, theta) == pytest.approx(eL)
    span = 6 * (eb + abs(eL)) / rp
    y = ramp(plant, 0.0, span, eb / rp / 30)
    fwd = span * rp - y * rd
    y = ramp(plant, span, -span, eb / rp / 30)
    bwd = -span * rp - y * rd
    # Measured over the 20 seeds (200 elements): forward worst 3.5e-5 relative, backward
    # worst 1.1e-5 e_b absolute (3.2e-5 relative), dead-zone width worst 5.2e-10 relative
    # (the discretisation error is common to both branches and cancels in the width).
    # Tolerances 3-10x above the worst: 1e-4 relative, 5e-5 e_b, 5e-9 relative.
    assert fwd == pytest.approx(eb + eL, rel=1e-4)
    assert bwd == pytest.approx(-eb + eL, rel=0, abs=5e-5 * eb)
    assert fwd - bwd == pytest.approx(2 * eb, rel=5e-9)
    # the closed form computed by the plant: measured worst 6e-14 (f, relative) and
    # 1.1e-14 e_b (b), round-off; 1e-12 and 1e-13 e_b
    f, b = plant.steady_offsets()
    assert f == pytest.approx(eb + eL, rel=1e-12)
    assert b == pytest.approx(-eb + eL, rel=0, abs=1e-13 * eb)


@pytest.mark.parametrize("seed", range(15))
def test_pull_pull_offsets_match_g_G_nonuniform(seed):
    rng = np.random.default_rng(200 + seed)
    L = rng.uniform(0.5, 2.0)
    route1 = random_route(rng, L)
    route2 = random_route(rng, L) if seed % 3 == 0 else route1
    mu, EA, T0 = rng.uniform(0.05, 0.2), rng.uniform(5e3, 5e4), rng.uniform(5, 40)
    theta = max(route1.curve_angle, route2.curve_angle)
    FL = rng.uniform(-0.5, 0.5) * physics.no_slack_limit(T0, mu, theta)
    # 800 elements: a route with 2/3 of its angle in the distal 10 % (seed 9) puts a
    # discretisation error O(1/N^2) of 3.8e-3 dz on the forward offset at 200 elements,
    # 1.1e-3 dz at 400, 2.9e-4 dz at 800 (the sweep of 15 seeds takes 0.2 s)
    plant = ts.PullPullPlant(
        route=route1,
        route2=route2,
        friction=mu,
        stiffness=EA,
        pretension=T0,
        elements=800,
        load=ts.loads.ConstantTorque(FL * 5e-3),
    )
    f, b = plant.steady_offsets()
    dz = f - b
    span = 6 * (abs(f) + abs(b)) / 5e-3
    y = ramp(plant, 0.0, span, dz / 5e-3 / 60)
    sim_f = span * 5e-3 - y * 5e-3
    y = ramp(plant, span, -span, dz / 5e-3 / 60)
    sim_b = -span * 5e-3 - y * 5e-3
    # measured at 800 elements over the 15 seeds: worst 2.9e-4 dz (forward), 2.7e-5 dz
    # (backward), 3.2e-4 dz (width), all at seed 9; the next worst is 3.2e-5 dz.
    # 1e-3 dz is 3x above the worst.
    assert sim_f == pytest.approx(f, rel=0, abs=1e-3 * dz)
    assert sim_b == pytest.approx(b, rel=0, abs=1e-3 * dz)
    assert sim_f - sim_b == pytest.approx(dz, rel=1e-3)
    assert not plant.slack()


def test_error_falls_as_N_grows():
    route = ts.Route.arcs([(0.9, 1.0), (0.1, 2.0)])
    kw = dict(friction=0.15, stiffness=2e3, pretension=20.0, load=ts.loads.ConstantTorque(0.02))
    errors = []
    for n in (10, 25, 50, 100, 200):
        plant = ts.PullPullPlant(route=route, elements=n, **kw)
        f, b = plant.steady_offsets()
        y = ramp(plant, 0.0, 8 * f / 5e-3, f / 5e-3 / 40)
        errors.append(abs((8 * f - y * 5e-3) / f - 1))
    # measured: 2.8e-2, 5.6e-3, 1.1e-3, 2.8e-4, 7.1e-5 for N = 10 ... 200 (second order:
    # 20x the elements gives 395x less error). Bounds 4x above the measured figures.
    assert errors[-1] < 3e-4
    assert all(e2 < e1 for e1, e2 in zip(errors, errors[1:], strict=False))
    assert errors[-1] < errors[0] / 100


@pytest.mark.parametrize("seed", range(10))
def test_dead_zone_is_flat_and_has_the_A7_width(seed):
    rng = np.random.default_rng(300 + seed)
    L, theta = rng.uniform(0.5, 2.0), rng.uniform(0.5, 4 * np.pi)
    mu, EA, T0 = rng.uniform(0.05, 0.2), rng.uniform(5e3, 5e4), rng.uniform(2, 40)
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(L, theta), friction=mu, stiffness=EA, pretension=T0, elements=200
    )
    eb = physics.backlash_half_width(L, EA, T0, mu, theta) / 5e-3  # input rad
    top = 4 * eb
    ramp(plant, 0.0, top, eb / 40)
    y_top = plant.output()
    dq = eb / 2000
    q = top
    while abs(plant.step(q - dq) - y_top) < 1e-9 * eb:
        q -= dq
    # The width 2 e_b is exactly 4000 probe steps dq; the probe finds it to 4e-13 relative
    # over the 10 seeds. Half a probe step (1.25e-4 relative) is the resolution: a dead zone
    # off by one step fails.
    assert top - q == pytest.approx(2 * eb, rel=0, abs=0.5 * dq)


@pytest.mark.parametrize("seed", range(10))
def test_spring_load_branch_slope(seed):
    rng = np.random.default_rng(400 + seed)
    L, theta = rng.uniform(0.5, 2.0), rng.uniform(0.5, 4 * np.pi)
    mu, EA, T0 = rng.uniform(0.05, 0.2), rng.uniform(5e3, 5e4), rng.uniform(10, 40)
    rp, rd = 5e-3, rng.uniform(3e-3, 10e-3)
    eb_m = physics.backlash_half_width(L, EA, T0, mu, theta)
    # tendon-level stiffness k_e (N/m); the load F_L = k_e x_out stays below the no-slack
    # limit up to an input of 10 e_b
    ke = rng.uniform(0.1, 0.5) * physics.no_slack_limit(T0, mu, theta) / (10 * eb_m)
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(L, theta),
        friction=mu,
        stiffness=EA,
        pretension=T0,
        proximal_radius=rp,
        distal_radius=rd,
        elements=100,
        load=ts.loads.TorsionalSpring(ke * rd**2),
    )
    c = physics.spring_slope(L, EA, mu, theta, ke)
    eb = eb_m / rp
    q1 = 10 * eb
    y0 = ramp(plant, 0.0, 0.5 * q1, eb / 40)
    y1 = ramp(plant, 0.5 * q1, q1, eb / 40)
    slope = (y1 - y0) * rd / (0.5 * q1 * rp)
    # measured over the 10 seeds: worst 2.5e-6 relative; 1e-5 is 4x above
    assert slope == pytest.approx(c, rel=1e-5)
    assert not plant.slack()


@pytest.mark.parametrize("case", ["mu0", "theta0"])
def test_no_hysteresis_without_friction(case):
    mu, theta = (0.0, 2 * np.pi) if case == "mu0" else (0.15, 0.0)
    L, EA, FL, rd = 1.2, 2.4e4, 3.0, 5e-3
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(L, theta),
        friction=mu,
        elements=50,
        load=ts.loads.ConstantTorque(FL * rd),
    )
    q = np.r_[np.linspace(0, 0.2, 101), np.linspace(0.2, -0.2, 201), np.linspace(-0.2, 0.2, 201)]
    y = plant.simulate(None, q)
    # output = input - F_L L / (2 EA) on every branch (the a -> 0 limit of A7)
    np.testing.assert_allclose(y * rd, q * 5e-3 - FL * L / (2 * EA), atol=1e-12)


def test_rate_independence_without_motor():
    plant = ts.PullPullPlant(route=ts.Route.arcs([(0.8, 1.0), (0.4, 4.0)]), elements=100)
    t_slow = np.arange(0, 20.0, 1e-3)  # 0.05 Hz, one period at 1 kHz
    t_fast = np.arange(0, 0.2, 1e-3)  # 5 Hz, one period at 1 kHz
    y_slow = plant.simulate(t_slow, 0.5 * np.sin(2 * np.pi * 0.05 * t_slow))
    y_fast = plant.simulate(t_fast, 0.5 * np.sin(2 * np.pi * 5.0 * t_fast))
    eb = plant.backlash_half_width() / 5e-3
    np.testing.assert_allclose(y_slow[::100], y_fast, atol=1e-9 * eb)
    assert np.ptp(y_fast) > 0.5  # it did move


def test_memory_effect_raise_holds_lower_creeps():
    low, high = ts.Route.uniform(1.2, np.pi / 2), ts.Route.uniform(1.2, 2 * np.pi)
    plant = ts.PullPullPlant(route=low, elements=100)
    ramp(plant, 0.0, 0.5, 0.001)
    y0 = plant.step(0.5)
    plant.set_route(high)
    assert plant.step(0.5) == y0  # raising Theta at rest does not move the output
    plant = ts.PullPullPlant(route=high, elements=100)
    ramp(plant, 0.0, 0.5, 0.001)
    y_high = plant.step(0.5)
    plant.set_route(low)
    y_low = plant.step(0.5)
    assert y_low > y_high  # creeps forward ...
    f, _ = plant.steady_offsets()
    # ... to the new forward offset: measured 2.6e-11 relative; 1e-9
    assert 0.5 - y_low == pytest.approx(f / 5e-3, rel=1e-9)


def test_continuum_plant_spring_slope_and_force():
    plant = ts.ContinuumPlant(elements=100)
    assert plant.route.curve_angle == pytest.approx(np.pi)
    k = plant.spring_stiffness
    assert k == pytest.approx(4e-4 / (2e-3**2 * 0.03))
    c = physics.spring_slope(1.0, 2.4e4, 0.1, np.pi, k)
    y0 = ramp(plant, 0.0, 0.3, 1e-3)
    y1 = ramp(plant, 0.3, 0.6, 1e-3)
    # measured 2.9e-7 relative; 2e-6 is 7x above
    assert (y1 - y0) * 2e-3 / (0.3 * 5e-3) == pytest.approx(c, rel=2e-6)
    assert plant.tendon_force() == pytest.approx(y1 / 0.03 * 4e-4 / 2e-3)


def test_cpp_plant_equals_plain_numpy_reference():
    r1 = ts.Route.arcs([(0.8, 1.0), (0.4, 3.0)])
    r2 = ts.Route.uniform(1.2, 2.0)
    kw = dict(friction=0.12, stiffness=2e4, pretension=8.0, elements=16)
    k = np.arange(900)
    q = 0.4 * np.sin(2 * np.pi * k / 300) + 0.1 * np.sin(2 * np.pi * k / 110)
    for fast in (True, False):
        plant = ts.PullPullPlant(
            route=r1, load=ts.loads.TorsionalSpring(2e-3, preload=0.01), fast_path=fast, **kw
        )
        ref = ReferencePullPull(r1, load_torque=0.01, load_stiffness=2e-3, **kw)
        ref.reset()
        y_ref, y = [], []
        plant.reset()
        for i, qi in enumerate(q):
            if i == 500:
                plant.set_route(r2)
                ref.set_route(r2)
            y.append(plant.step(qi))
            y_ref.append(ref.step(qi))
        np.testing.assert_allclose(y, y_ref, atol=1e-11)
