import math

import numpy as np
import pytest

import tendonsheath as ts


def test_uniform_route_properties_and_vectorised_angle():
    r = ts.Route.uniform(length=1.2, curve_angle=2 * np.pi)
    assert r.length == pytest.approx(1.2)
    assert r.curve_angle == pytest.approx(2 * np.pi)
    s = np.linspace(0, 1.2, 7)
    np.testing.assert_allclose(r.angle_at(s), 2 * np.pi * s / 1.2, atol=1e-14)
    assert r.angle_at(0.6) == pytest.approx(np.pi)
    assert r.angle_at(np.array([[0.0, 0.3], [0.9, 5.0]])).shape == (2, 2)


def test_arcs_accumulate_absolute_bends():
    r = ts.Route.arcs([(0.6, 0.0), (0.4, np.pi / 2), (0.2, -1.0)])
    assert r.length == pytest.approx(1.2)
    assert r.curve_angle == pytest.approx(np.pi / 2 + 1.0)
    assert r.angle_at(0.5) == 0.0
    assert r.angle_at(0.8) == pytest.approx(np.pi / 4)


@pytest.mark.parametrize("n", [2, 3, 10, 101, 400])
def test_element_and_node_angles_sum_to_total(n):
    rng = np.random.default_rng(n)
    pieces = [(rng.uniform(0.05, 0.5), rng.uniform(-2, 2)) for _ in range(5)]
    r = ts.Route.arcs(pieces)
    assert r.element_angles(n).sum() == pytest.approx(r.curve_angle, rel=1e-12)
    nodes = r.node_angles(n)
    assert nodes.shape == (n - 1,)
    assert nodes.sum() == pytest.approx(r.curve_angle, rel=1e-12)
    assert (nodes >= 0).all()


def test_polyline_turning_angles_and_circle_limit():
    xyz = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 2, 1]]
    r = ts.Route.from_points(xyz)
    assert r.length == pytest.approx(2 + math.sqrt(2))
    assert r.curve_angle == pytest.approx(np.pi / 2 + np.pi / 4)
    # a finely sampled helix-free circle of radius R over a half turn: Theta -> pi
    phi = np.linspace(0, np.pi, 2001)
    R = 0.3
    circle = np.c_[R * np.cos(phi), R * np.sin(phi), np.zeros_like(phi)]
    rc = ts.Route.from_points(circle)
    assert rc.curve_angle == pytest.approx(np.pi, rel=1e-3)
    assert rc.length == pytest.approx(np.pi * R, rel=1e-5)
    # a 3-D coil: each full turn adds about 2 pi
    t = np.linspace(0, 4 * np.pi, 4001)
    coil = np.c_[0.1 * np.cos(t), 0.1 * np.sin(t), 0.01 * t]
    assert ts.Route.from_points(coil).curve_angle == pytest.approx(4 * np.pi, rel=2e-2)


def test_from_curvature_integrates_abs_kappa():
    s = np.linspace(0.2, 1.2, 201)
    kappa = np.where(s < 0.7, 2.0, -4.0)
    r = ts.Route.from_curvature(s, kappa)
    assert r.length == pytest.approx(1.0)
    assert r.curve_angle == pytest.approx(0.5 * 2.0 + 0.5 * 4.0, rel=1e-2)
    r2 = ts.Route.from_curvature(s, np.full_like(s, 1 / 0.3))
    assert r2.curve_angle == pytest.approx(1.0 / 0.3)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: ts.Route.uniform(-1.0, 1.0), "length must be > 0"),
        (lambda: ts.Route.uniform(1.0, -1.0), "curve_angle must be >= 0"),
        (lambda: ts.Route.uniform(float("nan"), 1.0), "length"),
        (lambda: ts.Route.arcs([(0.5, 1.0), (-0.1, 0.0)]), "length of piece 1 must be > 0"),
        (lambda: ts.Route.arcs([]), "at least one"),
        (lambda: ts.Route.from_points([[0, 0, 0], [np.nan, 0, 0]]), "not finite"),
        (lambda: ts.Route.from_points([[0, 0, 0]]), "at least two points"),
        (lambda: ts.Route.from_points([[0, 0], [1, 1]]), "K x 3"),
        (lambda: ts.Route.from_points([[0, 0, 0], [0, 0, 0]]), "coincide"),
        (lambda: ts.Route.from_curvature([0, 1, 1], [1, 1, 1]), "strictly increasing"),
        (lambda: ts.Route.from_curvature([0, 1], [1, np.inf]), "not finite"),
        (lambda: ts.Route([0, 1, 0.5], [0, 1, 2]), "non-decreasing"),
    ],
)
def test_bad_routes_raise_clear_errors(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_scaled_and_equality():
    r = ts.Route.arcs([(0.6, 1.0), (0.6, 2.0)])
    assert r.scaled(0.5).curve_angle == pytest.approx(1.5)
    assert r.scaled(1.0) == r
    assert r != ts.Route.uniform(1.2, 3.0)
