"""ShapeSensing: the curve angle (segments=0, unchanged) or the curvature profile in K arcs,
with noise, delay and a reading rate; what it reports is a Route."""

import math

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import physics
from tendonsheath.bench.shape_sensing import ShapeSensing, sensed_route_schedule, sensed_schedule

# A route every one of whose 20 equal arcs bends by at least 2 pi/20 = 0.31 rad: no sensed
# arc comes near the clip at 0 (noise <= 0.05 rad per arc), so the noise is not biased.
CURVED = ts.Route.arcs([(0.4, 2.0), (0.5, 2.5), (0.3, 3.0)])


def _old_readings(shape, t, angle_at, seed_offset=0):
    """The readings of the curve-angle sensor as calibration.py computed them before the
    profile was added (a plain copy of that algorithm, the reference for bit-for-bit)."""
    t = np.asarray(t, dtype=float)
    period = 1.0 / shape.rate_hz
    times = np.arange(t[0], t[-1] + 0.5 * period, period)
    idx = np.unique(np.searchsorted(t, times, side="left").clip(0, t.size - 1))
    rng = np.random.default_rng(10_000 + shape.seed + seed_offset)
    sensed = np.array(
        [angle_at(max(float(t[k]) - shape.delay, float(t[0]))) for k in idx], dtype=float
    )
    sensed = sensed + rng.normal(0.0, shape.noise_std, sensed.size)
    return idx, np.maximum(sensed, 0.0)


def _changing(t_switch, before, after):
    return lambda tk: before if tk < t_switch else after


def test_the_bench_exports_the_one_class():
    assert ts.bench.ShapeSensing is ShapeSensing


@pytest.mark.parametrize("seed", range(5))
def test_segments_0_reads_bit_for_bit_as_before(seed):
    rng = np.random.default_rng(seed)
    shape = ShapeSensing(
        noise_std=rng.uniform(0.0, 0.2), delay=rng.uniform(0, 0.5), rate_hz=rng.uniform(2, 50)
    )
    t = np.arange(0.0, 6.0, 1e-3)
    before = ts.Route.arcs([(0.7, 0.4), (0.5, 2.5)])
    after = ts.Route.uniform(1.2, 5.0)
    routes = _changing(2.5, before, after)

    def angle_at(tk):
        return routes(tk).curve_angle

    idx0, ref = _old_readings(shape, t, angle_at, seed_offset=seed)
    idx, sensed = shape.readings(t, angle_at, seed_offset=seed)
    assert np.array_equal(idx, idx0) and np.array_equal(sensed, ref)
    idx_r, sensed_routes = shape.route_readings(t, routes, seed_offset=seed)
    assert np.array_equal(idx_r, idx0)
    assert np.array_equal([r.curve_angle for r in sensed_routes], ref)
    # what it reports is a uniform route of the sensed angle, of the true route's length
    assert all(r == ts.Route.uniform(1.2, a) for r, a in zip(sensed_routes, ref, strict=True))
    # the old static reading and schedule are unchanged
    t_static = np.arange(0.0, 3.0, 1.0 / shape.rate_hz)
    _, ref_static = _old_readings(shape, t_static, lambda _t: 2.0, seed_offset=seed)
    assert shape.static_reading(2.0, 3.0, seed_offset=seed) == float(np.median(ref_static))
    assert shape.static_route(before, 3.0, seed) == ts.Route.uniform(
        1.2, shape.static_reading(before.curve_angle, 3.0, seed)
    )
    _, old_sensed, old_rows = sensed_schedule(shape, t, routes, 0.1, seed_offset=seed)
    assert np.array_equal(old_sensed, ref)
    _, _, rows = sensed_route_schedule(shape, t, routes, 0.1, seed_offset=seed)
    assert np.array_equal(rows, old_rows)


def _total_and_arc_errors(segments, seeds=25):
    """Sensed minus true curve angle, and sensed minus true arc angles, over many runs."""
    totals, arcs = [], []
    t = np.arange(0.0, 10.0, 0.01)
    for seed in range(seeds):
        shape = ShapeSensing(noise_std=0.05, delay=0.0, rate_hz=10.0, seed=seed, segments=segments)
        _, routes = shape.route_readings(t, lambda _t: CURVED)
        totals += [r.curve_angle - CURVED.curve_angle for r in routes]
        arcs += [shape.arc_angles(r) - shape.arc_angles(CURVED) for r in routes]
    return np.array(totals), np.concatenate(arcs)


@pytest.mark.parametrize("segments", [1, 5, 20])
def test_total_angle_noise_is_noise_std_for_any_number_of_arcs(segments):
    totals, arcs = _total_and_arc_errors(segments)
    n = totals.size  # 25 runs x 101 readings
    # The sample std of n Gaussian draws has a relative standard error 1/sqrt(2 n) = 1.4 %;
    # 5 of them (7 %) is the tolerance, and the mean is zero within 5 standard errors.
    assert np.std(totals) == pytest.approx(0.05, rel=5 / math.sqrt(2 * n))
    assert abs(np.mean(totals)) < 5 * 0.05 / math.sqrt(n)
    # each arc's noise: noise_std / sqrt(K), with K times as many draws
    per_arc = 0.05 / math.sqrt(segments)
    assert np.std(arcs) == pytest.approx(per_arc, rel=5 / math.sqrt(2 * arcs.size))


@pytest.mark.parametrize("segments", [0, 5])
def test_delay_shifts_a_route_change_by_delay(segments):
    before = ts.Route.arcs([(0.6, 0.5), (0.6, 1.0)])
    after = ts.Route.arcs([(0.3, 0.0), (0.9, 4.0)])
    t = np.arange(0.0, 4.0, 1e-3)
    switch, delay = 1.5, 0.35
    shape = ShapeSensing(noise_std=0.0, delay=delay, rate_hz=20.0, segments=segments)
    idx, routes = shape.route_readings(t, _changing(switch, before, after))
    changed = np.array([r.curve_angle == after.curve_angle for r in routes])
    assert not changed[0] and changed[-1]
    first = idx[np.argmax(changed)]
    # the first reading of the new route is the first reading at or after switch + delay
    assert t[first] >= switch + delay - 1e-9
    assert t[idx[np.argmax(changed) - 1]] < switch + delay
    assert np.all(changed[np.argmax(changed) :])
    if segments:  # without noise, each arc reports the true route's bend over it
        assert np.allclose(shape.arc_angles(routes[-1]), [0, 0.8, 16 / 15, 16 / 15, 16 / 15])
        assert routes[-1].length == pytest.approx(1.2)


def test_a_finer_profile_gives_the_true_dead_zone_factor():
    # the spec A.2 warning: curvature concentrated at the distal end (a corner on no arc edge)
    route = ts.Route.arcs([(0.83, 1.0), (0.17, 2.0)])
    mu = 0.15
    true = physics.route_dead_zone_factor(route, mu)
    errors = []
    for k in (0, 1, 2, 5, 10, 20, 40):
        sensed = ShapeSensing(noise_std=0.0, segments=k).static_route(route, 2.0)
        errors.append(abs(physics.route_dead_zone_factor(sensed, mu) / true - 1))
    # measured: 32 % with the curve angle only (0) or one arc (1, the same uniform route),
    # then 12 %, 1.1 %, 0.46 %, 0.13 %, 0.022 % for K = 2, 5, 10, 20, 40 (second order
    # in the arc length). Bounds: the curve angle off by > 25 %, the profile converging
    # monotonically to < 0.05 % at K = 40 (2x above the measured figure).
    assert errors[0] > 0.25 and errors[1] == pytest.approx(errors[0], abs=1e-12)
    assert all(e2 < e1 for e1, e2 in zip(errors[1:], errors[2:], strict=False))
    assert errors[-1] < 5e-4


def test_static_route_is_the_median_arc_by_arc():
    shape = ShapeSensing(noise_std=0.1, rate_hz=5.0, seed=3, segments=4)
    sensed = shape.static_route(CURVED, 4.0, seed_offset=2)
    t = np.arange(0.0, 4.0, 0.2)
    _, routes = shape.route_readings(t, lambda _t: CURVED, seed_offset=2)
    bends = np.array([shape.arc_angles(r) for r in routes])
    assert np.allclose(shape.arc_angles(sensed), np.median(bends, axis=0))


def test_schedule_rows_are_the_sensed_routes_shapes():
    t = np.arange(0.0, 2.0, 1e-3)
    shape = ShapeSensing(segments=6, seed=4)
    idx, routes, rows = sensed_route_schedule(shape, t, lambda _t: CURVED, 0.12, seed_offset=1)
    assert rows.shape == (idx.size, 3) and rows.flags.c_contiguous
    for route, row in zip(routes, rows, strict=True):
        s = physics.route_shape(route, 0.12)
        assert list(row) == [s.g, s.G, s.curve_angle]
    # a (route1, route2) pair: route1 is sensed
    _, pair_routes, _ = sensed_route_schedule(shape, t, lambda _t: (CURVED, CURVED), 0.12, 1)
    assert pair_routes == routes


def test_describe_and_bad_values():
    assert "curve angle" in ShapeSensing().describe()
    text = ShapeSensing(noise_std=0.08, segments=16).describe()
    assert "16 equal arcs" in text and "0.02 rad per arc" in text
    for kwargs, name in (
        ({"segments": -1}, "segments"),
        ({"segments": 1.5}, "segments"),
        ({"noise_std": -0.1}, "noise_std"),
        ({"delay": float("nan")}, "delay"),
        ({"rate_hz": 0.0}, "rate_hz"),
    ):
        with pytest.raises(ValueError, match=name):
            ShapeSensing(**kwargs)
    with pytest.raises(ValueError, match="segments is 0"):
        ShapeSensing().arc_angles(CURVED)
