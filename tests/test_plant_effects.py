"""The plant's effects beyond the quasi-static capstan pair, each against a closed form or a
limiting case, over random parameter sets.

With friction 0 the sheath nodes carry no Coulomb force, so a pull-pull pair is two chains of
massless springs: the effects then have exact closed forms. The solver is implicit Euler in
time, so where a response is dynamic the test checks the exact discrete recurrence of that
scheme (to rounding) and, separately, that it tends to the continuous solution as dt shrinks.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.plant.loads import TorsionalSpring

RNG_CASES = 8


def _pair(rng, **kw):
    L = rng.uniform(0.6, 1.8)
    r = rng.uniform(4e-3, 12e-3)
    base = dict(
        friction=0.0,
        stiffness=rng.uniform(5e3, 4e4),
        pretension=rng.uniform(5.0, 30.0),
        proximal_radius=r,
        distal_radius=r,
        elements=int(rng.integers(20, 60)),
    )
    base.update(kw)
    return ts.PullPullPlant(ts.Route.uniform(L, rng.uniform(0.0, 2 * math.pi)), **base), L, r


@pytest.mark.parametrize("seed", range(RNG_CASES))
def test_viscous_sheath_lag_at_constant_speed(seed):
    """mu = 0, viscosity c: at constant tendon speed V every interior node of a sheath adds
    c ds V of tension, so the pulled tendon stretches by c V L^2 (N - 1) / (2 N EA) (the
    discrete sum of the continuous c V L^2 / (2 EA)); the output lags by exactly that."""
    rng = np.random.default_rng(seed)
    c = rng.uniform(2.0, 40.0)
    plant, L, r = _pair(rng, sheath_viscosity=c)
    N, EA = plant.elements, plant.stiffness
    speed = rng.uniform(0.2, 2.0) * rng.choice([-1.0, 1.0])  # rad/s at the pulley
    t = np.arange(0.0, 0.5, 1e-3)
    out = plant.simulate(t, speed * t)
    V = speed * r
    lag = c * V * L**2 * (N - 1) / (2 * N * EA)
    measured = (speed * t[-1] - out[-1]) * r
    assert measured == pytest.approx(lag, rel=1e-7)


def test_viscous_friction_makes_the_loop_widen_with_rate():
    """Coulomb plus viscous friction: the hysteresis loop is wider at 5 Hz than at 0.1 Hz; with
    no viscosity the loop does not depend on the rate (rate independence of Coulomb friction)."""
    route = ts.Route.uniform(1.2, math.pi)

    def width(freq, c):
        plant = ts.PullPullPlant(route, elements=40, sheath_viscosity=c)
        t = np.arange(0.0, 3.0 / freq, min(1e-3, 0.002 / freq))
        q = 0.3 * np.sin(2 * np.pi * freq * t)
        y = plant.simulate(t, q)
        last = t >= t[-1] - 1.0 / freq
        return np.ptp((q - y)[last])

    assert width(5.0, 0.0) == pytest.approx(width(0.1, 0.0), rel=1e-6)
    # the viscous share grows with speed: measured 1.34x wider at 5 Hz with c = 20 N s/m^2
    # (0.042 vs 0.031 rad); 1.2x keeps a margin and still fails for a rate-independent loop
    assert width(5.0, 20.0) > 1.2 * width(0.1, 20.0)
    assert width(0.1, 20.0) == pytest.approx(width(0.1, 0.0), rel=0.05)


@pytest.mark.parametrize("seed", range(RNG_CASES))
def test_tendon_creep_is_a_standard_linear_solid(seed):
    """mu = 0, a torsional spring k_L at the joint, SLS tendons (fraction r, time tau): the two
    tendons are one SLS of stiffness K = EA1/L + EA2/L. A step of the input x answers at once
    with y0 = K x/(K + k_L), then creeps to y_inf = K(1-r) x/(K(1-r) + k_L) with time constant
    tau_c = tau (K + k_L)/(K(1-r) + k_L): implicit Euler gives y_k - y_inf = (y0 - y_inf) rho^k
    with rho = 1/(1 + dt/tau_c) exactly."""
    rng = np.random.default_rng(100 + seed)
    frac, tau = rng.uniform(0.05, 0.5), rng.uniform(0.1, 2.0)
    k_theta = rng.uniform(0.05, 2.0)
    plant, L, r = _pair(
        rng,
        relaxation_fraction=frac,
        relaxation_time=tau,
        load=TorsionalSpring(k_theta),
        stiffness2=rng.uniform(5e3, 4e4),
    )
    EA1, EA2 = plant.stiffness, plant.effects["stiffness2"]
    K, kL = EA1 / L + EA2 / L, k_theta / r**2
    q = rng.uniform(0.05, 0.3)
    plant.reset()
    plant.step(0.0, 0.0)
    y0 = plant.step(q, 0.0) * r  # a step in no time: the instantaneous (elastic) answer
    x = q * r
    assert y0 == pytest.approx(K * x / (K + kL), rel=1e-9)
    dt = 1e-3
    y_inf = K * (1 - frac) * x / (K * (1 - frac) + kL)
    tau_c = tau * (K + kL) / (K * (1 - frac) + kL)
    rho = 1.0 / (1.0 + dt / tau_c)
    ys = np.array([plant.step(q, dt) * r for _ in range(400)])
    expected = y_inf + (y0 - y_inf) * rho ** np.arange(1, 401)
    np.testing.assert_allclose(ys - y_inf, expected - y_inf, rtol=1e-7, atol=1e-12 * x)


def test_creep_moves_a_held_output_only_with_relaxation():
    """With friction, a held input after a ramp leaves the output exactly still for elastic
    tendons and creeping for SLS tendons."""
    route = ts.Route.uniform(1.2, math.pi)
    t = np.arange(0.0, 6.0, 1e-3)
    q = np.minimum(t, 1.0) * 0.4
    spring = TorsionalSpring(0.05)
    elastic = ts.PullPullPlant(route, elements=40, load=spring, sheath_viscosity=1e-9)
    creeping = ts.PullPullPlant(
        route, elements=40, load=spring, relaxation_fraction=0.2, relaxation_time=0.5
    )
    held = t >= 1.5
    assert np.ptp(elastic.simulate(t, q)[held]) < 1e-12
    # measured: the output creeps by 2.6e-5 rad after the ramp stops (1e-12 when elastic)
    assert np.ptp(creeping.simulate(t, q)[held]) > 1e-5


@pytest.mark.parametrize("seed", range(RNG_CASES))
def test_distal_joint_dynamics_follow_the_implicit_euler_recurrence(seed):
    """mu = 0: the joint is a mass m = J/r^2 on springs K = 2 EA/L + k_L with damping
    c = c_d/r^2 (tendon level). After a step of the input the error e_k = y_k - y_inf obeys
    (m/h^2 + c/h + K) e_{k+1} = (2 m/h^2 + c/h) e_k - (m/h^2) e_{k-1} exactly."""
    rng = np.random.default_rng(200 + seed)
    J, cd, k_theta = rng.uniform(1e-6, 1e-4), rng.uniform(0.0, 5e-3), rng.uniform(0.0, 1.0)
    plant, L, r = _pair(
        rng, distal_inertia=J, distal_damping=cd, load=TorsionalSpring(k_theta) if k_theta else None
    )
    m, c, K = J / r**2, cd / r**2, 2 * plant.stiffness / L + k_theta / r**2
    h, q = 1e-3, rng.uniform(0.05, 0.3)
    plant.reset()
    plant.step(0.0, 0.0)
    y = np.array([plant.step(q, h) * r for _ in range(300)])
    e = y - (2 * plant.stiffness / L) * q * r / K
    lhs = (m / h**2 + c / h + K) * e[2:]
    rhs = (2 * m / h**2 + c / h) * e[1:-1] - (m / h**2) * e[:-2]
    scale = K * np.abs(e).max()
    np.testing.assert_allclose(lhs, rhs, atol=1e-8 * scale)


def test_distal_joint_rings_at_its_natural_frequency():
    """As dt shrinks the joint oscillates at sqrt(K/m) (undamped, mu = 0): the period of the
    simulated ringing is within 0.5 % of 2 pi sqrt(m/K) at dt = 1e-5 s."""
    L, r, EA, J = 1.0, 5e-3, 1e4, 2e-5
    plant = ts.PullPullPlant(
        ts.Route.uniform(L, 0.0),
        friction=0.0,
        stiffness=EA,
        elements=20,
        distal_radius=r,
        proximal_radius=r,
        distal_inertia=J,
        load=TorsionalSpring(0.3),
    )
    K, m = 2 * EA / L + 0.3 / r**2, J / r**2
    period = 2 * math.pi * math.sqrt(m / K)
    h = 1e-5
    t = np.arange(0.0, 6 * period, h)
    y = plant.simulate(t, np.where(t > 0, 0.1, 0.0))
    e = y - y[-int(period / h) :].mean()
    crossings = t[1:][np.diff(np.sign(e)) > 0]
    assert np.diff(crossings).mean() == pytest.approx(period, rel=5e-3)


@pytest.mark.parametrize("seed", range(RNG_CASES))
def test_unequal_pair_matches_its_closed_form(seed):
    """Sheath 2 with its own friction and tendon 2 with its own EA: full-slip offsets from the
    pair's two equations (distal equilibrium and Delta1 + Delta2 = 0) with g1, G1, g2, G2."""
    rng = np.random.default_rng(300 + seed)
    L, r = rng.uniform(0.8, 1.6), 5e-3
    mu1, mu2 = rng.uniform(0.05, 0.2), rng.uniform(0.05, 0.2)
    EA1, EA2 = rng.uniform(1e4, 4e4), rng.uniform(1e4, 4e4)
    th1, th2 = rng.uniform(0.5, 2 * math.pi), rng.uniform(0.5, 2 * math.pi)
    T0 = rng.uniform(5.0, 20.0)
    plant = ts.PullPullPlant(
        ts.Route.uniform(L, th1),
        route2=ts.Route.uniform(L, th2),
        friction=mu1,
        friction2=mu2,
        stiffness=EA1,
        stiffness2=EA2,
        pretension=T0,
        elements=200,
    )
    a1, a2 = mu1 * th1, mu2 * th2
    g1, G1 = (1 - math.exp(-a1)) / a1, (math.exp(a1) - 1) / a1
    g2, G2 = (1 - math.exp(-a2)) / a2, (math.exp(a2) - 1) / a2

    def offset(forward):
        if (
            forward
        ):  # tendon 1 pulled: T1p e^-a1 = T2p e^a2, L/EA1 (T1p g1 - T0) + L/EA2 (T2p G2 - T0) = 0
            A = [[math.exp(-a1), -math.exp(a2)], [L / EA1 * g1, L / EA2 * G2]]
            T1p, _ = np.linalg.solve(A, [0.0, T0 * L / EA1 + T0 * L / EA2])
            return L / EA1 * (T1p * g1 - T0)
        A = [[math.exp(a1), -math.exp(-a2)], [L / EA1 * G1, L / EA2 * g2]]
        T1p, _ = np.linalg.solve(A, [0.0, T0 * L / EA1 + T0 * L / EA2])
        return L / EA1 * (T1p * G1 - T0)

    e_b = T0 * L / min(EA1, EA2)
    q = np.concatenate([np.linspace(0, 40 * e_b / r, 400), np.linspace(40 * e_b / r, 0, 400)])
    y = plant.simulate(None, q)
    # measured discretisation error at N = 200: below 2e-5 of T0 L/EA
    assert (q[399] - y[399]) * r == pytest.approx(offset(True), abs=1e-4 * e_b)
    assert (q[-1] - y[-1]) * r == pytest.approx(offset(False), abs=1e-4 * e_b)


def test_motor_coulomb_friction_torque_kind():
    """Torque motor with Coulomb friction tau_c: a torque below tau_c never moves it; above, it
    reaches the speed (tau - tau_c)/b."""
    still = ts.Motor.torque(inertia=1e-3, viscous=0.05, coulomb_friction=0.2)
    t = np.arange(0.0, 2.0, 1e-3)
    assert np.all(still.simulate(t, np.full(t.size, 0.19)) == 0.0)
    moving = ts.Motor.torque(inertia=1e-3, viscous=0.05, coulomb_friction=0.2)
    q = moving.simulate(t, np.full(t.size, 0.5))
    assert np.diff(q)[-1] / 1e-3 == pytest.approx((0.5 - 0.2) / 0.05, rel=1e-6)


@pytest.mark.parametrize("seed", range(RNG_CASES))
def test_position_servo_ramp_error_with_friction(seed):
    """A position servo of reflected inertia J following a ramp of speed v lags by
    2 zeta v/w + (tau_c + b_m v)/(J w^2) at steady state (q'' = 0), to within v dt: the
    command is a staircase (held over each 1 ms sample) that leads the ramp by up to v dt."""
    rng = np.random.default_rng(400 + seed)
    f, zeta = rng.uniform(5.0, 60.0), rng.uniform(0.5, 1.0)
    J, tau_c, b = rng.uniform(1e-5, 1e-3), rng.uniform(0.0, 0.05), rng.uniform(0.0, 1e-2)
    v = rng.uniform(0.05, 1.0)
    motor = ts.Motor.position(f, zeta, inertia=J, coulomb_friction=tau_c, viscous_friction=b)
    t = np.arange(0.0, 20.0 / f + 2.0, 1e-3)
    q = motor.simulate(t, v * t)
    w = 2 * math.pi * f
    expected = 2 * zeta * v / w + (tau_c + b * v) / (J * w**2)
    assert v * t[-1] - q[-1] == pytest.approx(expected, abs=v * 1e-3)


def test_gear_backlash_is_a_play_between_shaft_and_pulley():
    """The pulley angle is the play operator of the shaft angle with width g, exactly."""
    g = 0.02
    plant = ts.PullPullPlant(
        ts.Route.uniform(1.0, 1.0), motor=ts.Motor.position(40.0, 0.9, gear_backlash=g)
    )
    t = np.arange(0.0, 3.0, 1e-3)
    sim = plant.simulate(t, 0.1 * np.sin(2 * np.pi * 1.3 * t) + 0.03 * np.sin(2 * np.pi * 7 * t))
    play = np.empty_like(sim.q_motor)
    p = sim.q_motor[0]
    for k, qm in enumerate(sim.q_motor):
        p = min(max(p, qm - g / 2), qm + g / 2)
        play[k] = p
    np.testing.assert_array_equal(sim.q_in, play)
    assert np.abs(sim.q_in - sim.q_motor).max() == pytest.approx(g / 2)


def test_effects_are_validated_with_their_names():
    route = ts.Route.uniform(1.0, 1.0)
    for kw, name in [
        ({"sheath_viscosity": -1.0}, "sheath_viscosity"),
        ({"relaxation_fraction": 1.0}, "relaxation_fraction"),
        ({"relaxation_time": 0.0}, "relaxation_time"),
        ({"distal_inertia": -1e-6}, "distal_inertia"),
        ({"friction2": -0.5}, "friction2"),
        ({"stiffness2": 0.0}, "stiffness2"),
    ]:
        with pytest.raises(ValueError, match=name):
            ts.PullPullPlant(route, **kw)
    with pytest.raises(TypeError, match="sheath_viscosity"):
        ts.PullPullPlant(route, sheath_viscosity="high")
    with pytest.raises(ValueError, match="Motor.position: .*inertia"):
        ts.Motor.position(10.0, 0.7, coulomb_friction=0.1)
    with pytest.raises(ValueError, match="gear_backlash"):
        ts.Motor.position(10.0, 0.7, gear_backlash=-0.1)


def test_realistic_preset_is_finite_and_bounded_under_random_input():
    """All effects on, a random command with route changes: finite outputs, every increment
    converged, no slack."""
    rng = np.random.default_rng(7)
    plant = ts.PullPullPlant(
        ts.Route.uniform(1.5, math.pi),
        pretension=20.0,
        proximal_radius=15e-3,
        distal_radius=15e-3,
        elements=40,
        **ts.presets.realistic_plant(friction=0.1, stiffness=5e3),
        motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
    )
    t = np.arange(0.0, 10.0, 1e-3)
    cmd = np.cumsum(rng.normal(0.0, 0.01, t.size)).clip(-1.5, 1.5)
    routes = [ts.Route.uniform(1.5, a) for a in rng.uniform(0.5, 2 * math.pi, 5)]
    sim = plant.simulate(t, cmd, routes=lambda tk: routes[int(tk // 2)])
    assert np.isfinite(sim.q_out).all()
    assert sim.nonconverged == 0
    assert not sim.any_slack


def test_preset_rejects_unknown_overrides():
    with pytest.raises(TypeError, match="unknown override"):
        ts.presets.realistic_plant(viscosity=3.0)
