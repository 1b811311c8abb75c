"""The closed forms of spec A (C++ physics/pull_pull_statics.hpp, reached through
tendonsheath.plant.physics and the CurveAngleModel helpers) against the independent reference in
tests/reference/closed_forms.py (50-digit decimal arithmetic; a 2x2 solve with quadrature shape
integrals), over many random parameter sets and across the series switch."""

import numpy as np
import pytest

import tendonsheath as ts
from reference import closed_forms as ref
from tendonsheath import _core as core
from tendonsheath import physics

ULP = np.finfo(float).eps  # 2.2e-16
SERIES = ("expm1_over", "tanh_half_over", "a_over_sinh")


def rel_err(value, exact):
    value, exact = np.asarray(value, float), np.asarray(exact, float)
    return np.abs(value - exact) / np.abs(exact)


@pytest.mark.parametrize("name", SERIES)
def test_both_branches_agree_across_the_series_switch(name):
    kernel, exact = getattr(core, name), getattr(ref, name)
    sw = core.series_switch
    below = np.array([np.nextafter(sw, 0.0), sw * (1 - 1e-12)])
    above = np.array([sw, sw * (1 + 1e-12)])
    x = np.concatenate([below, above, -below, -above])
    # measured: 1.1e-16 (half an ulp) on either side; bound 1e-15, well inside the 1e-12
    assert rel_err(kernel(x), [exact(v) for v in x]).max() < 1e-15
    # the two branches themselves, one ulp of x apart, give the same value to rounding
    lo, hi = kernel(np.array([np.nextafter(sw, 0.0), sw]))
    assert abs(lo - hi) / abs(hi) < 1e-15


@pytest.mark.parametrize("name", SERIES)
def test_series_helpers_are_exact_to_rounding_from_1e_12_to_20(name):
    kernel, exact = getattr(core, name), getattr(ref, name)
    grid = np.geomspace(1e-12, 20.0, 1500)
    x = np.concatenate([grid, -grid, [0.0]])
    # measured: at most 1.25 ulp over this grid; bound 4 ulp
    assert rel_err(kernel(x), [exact(v) for v in x]).max() < 4 * ULP


def random_uniform_cases(rng, n=300):
    """Parameter sets over the ranges a user meets, friction angles down to 1e-9 rad."""
    theta = np.where(rng.random(n) < 0.3, 10 ** rng.uniform(-9, -2, n), rng.uniform(0, 9.4, n))
    return dict(
        L=rng.uniform(0.2, 3.0, n),
        EA=10 ** rng.uniform(3, 6, n),
        T0=rng.uniform(1.0, 50.0, n),
        mu=rng.uniform(0.01, 0.5, n),
        theta=theta,
        F=rng.uniform(-20.0, 20.0, n),
        k=10 ** rng.uniform(2, 6, n),
    )


def exact_values(fn, *columns):
    return [fn(*row) for row in zip(*columns, strict=True)]


def test_uniform_closed_forms_match_the_reference(rng):
    c = random_uniform_cases(rng)
    a = c["mu"] * c["theta"]
    L, EA, mu, theta = c["L"], c["EA"], c["mu"], c["theta"]
    cases = {
        "backlash_half_width": (
            physics.backlash_half_width(L, EA, c["T0"], mu, theta),
            exact_values(ref.backlash_half_width, L, EA, c["T0"], a),
        ),
        "load_offset": (
            physics.load_offset(L, EA, c["F"], mu, theta),
            exact_values(ref.load_offset, L, EA, c["F"], a),
        ),
        "load_compliance": (
            physics.load_compliance(L, EA, mu, theta),
            exact_values(ref.load_compliance, L, EA, a),
        ),
        "spring_slope": (
            physics.spring_slope(L, EA, mu, theta, c["k"]),
            exact_values(ref.spring_slope, L, EA, c["k"], a),
        ),
        "no_slack_limit": (
            physics.no_slack_limit(c["T0"], mu, theta),
            exact_values(ref.no_slack_limit, c["T0"], a),
        ),
    }
    for name, (value, exact) in cases.items():
        # measured: at most 4.2e-16 (each form is a few roundings); bound 2e-15
        assert rel_err(value, exact).max() < 2e-15, name


def test_closed_forms_broadcast_like_numpy(rng):
    L = rng.uniform(0.5, 2.0, (3, 1))
    theta = rng.uniform(0.0, 6.0, (1, 4))
    eb = physics.backlash_half_width(L, 2.4e4, 10.0, 0.1, theta)
    assert eb.shape == (3, 4)
    for i in range(3):
        for j in range(4):
            exact = ref.backlash_half_width(L[i, 0], 2.4e4, 10.0, 0.1 * theta[0, j])
            assert eb[i, j] == pytest.approx(exact, rel=2e-15, abs=0.0)
    assert np.ndim(physics.no_slack_limit(10.0, 0.1, 1.0)) == 0
    assert physics.tanh_half_over(0.0) == 0.5


def random_arcs(rng):
    """2 to 4 arcs, each bent 0.1 to 2 rad (so a = mu Theta >= 0.004 keeps the cancellation in
    T1p g - T0 small)."""
    pieces = [(rng.uniform(0.1, 1.0), rng.uniform(0.1, 2.0)) for _ in range(rng.integers(2, 5))]
    return ts.Route.arcs(pieces)


def test_two_sheath_offsets_match_the_reference_solve(rng):
    worst = 0.0
    for _ in range(100):
        r1, r2 = random_arcs(rng), random_arcs(rng)
        mu, EA, T0 = rng.uniform(0.02, 0.4), 10 ** rng.uniform(3, 5), rng.uniform(1.0, 30.0)
        limit = physics.no_slack_limit(T0, mu, min(r1.curve_angle, r2.curve_angle))
        F = rng.uniform(-0.5, 0.5) * limit
        got = physics.pull_pull_offsets(r1, EA, T0, mu, F, r2)
        exact = ref.pull_pull_offsets(r1, EA, T0, mu, F, r2)
        worst = max(worst, np.max(np.abs(np.subtract(got, exact))) / np.max(np.abs(exact)))
    # measured: 7.6e-15 of the larger offset; bound 1e-12 (the quadrature and the solve add
    # their own rounding, amplified by up to 1/a in T1p g - T0)
    assert worst < 1e-12


def test_uniform_route_offsets_are_the_tanh_forms(rng):
    for _ in range(50):
        L, EA, T0, mu = rng.uniform(0.3, 2.0), 10 ** rng.uniform(3, 5), rng.uniform(1, 30), 0.2
        theta = rng.uniform(0.05, 6.0)
        F = rng.uniform(-0.5, 0.5) * physics.no_slack_limit(T0, mu, theta)
        fwd, bwd = physics.pull_pull_offsets(ts.Route.uniform(L, theta), EA, T0, mu, F)
        e_b = physics.backlash_half_width(L, EA, T0, mu, theta)
        e_L = physics.load_offset(L, EA, F, mu, theta)
        # A7 from A5/A6: the general solve loses ~eps/a to cancellation (a >= 0.01 here)
        assert fwd == pytest.approx(e_b + e_L, rel=1e-11, abs=1e-11 * e_b)
        assert bwd == pytest.approx(-e_b + e_L, rel=1e-11, abs=1e-11 * e_b)


def test_one_shape_statics_are_the_two_sheath_ones_with_equal_sheaths(rng):
    statics = core.PullPullStatics()
    for _ in range(200):
        statics.friction = rng.uniform(0.0, 0.5)
        statics.compliance = 10 ** rng.uniform(-6, -3)
        statics.pretension = rng.uniform(0.0, 50.0)
        sh = core.uniform_shape(statics.friction, rng.uniform(0.0, 10.0))
        F = rng.uniform(-20.0, 20.0)
        assert statics.forward_elongation(sh, F) == statics.forward_elongation(sh, sh, 1.0, F)
        assert statics.backward_elongation(sh, F) == statics.backward_elongation(sh, sh, 1.0, F)


def test_curve_angle_model_helpers_are_the_physics_closed_forms(rng):
    for _ in range(50):
        p = dict(
            friction=rng.uniform(0.0, 0.4),
            stiffness=10 ** rng.uniform(3, 5),
            pretension=rng.uniform(1, 30),
            length=rng.uniform(0.3, 2),
            load_force=rng.uniform(-2, 2),
            load_stiffness=10 ** rng.uniform(1, 4),
            proximal_radius=rng.uniform(2e-3, 1e-2),
        )
        model = ts.models.CurveAngleModel(**p)
        theta = rng.uniform(-6.0, 6.0, 7)
        a = p["friction"] * np.abs(theta)
        rp = p["proximal_radius"]
        L, EA = p["length"], p["stiffness"]
        eb = [ref.backlash_half_width(L, EA, p["pretension"], x) / rp for x in a]
        eL = [ref.load_offset(L, EA, p["load_force"], x) / rp for x in a]
        c = [ref.spring_slope(L, EA, p["load_stiffness"], x) for x in a]
        assert rel_err(model.backlash_half_width(theta), eb).max() < 4e-15
        assert np.all(np.abs(model.load_offset(theta) - eL) <= 4e-15 * np.abs(eL))
        assert rel_err(model.slope(theta), c).max() < 4e-15
        assert model.backlash_half_width(theta[0]) == model.backlash_half_width(theta)[0]
