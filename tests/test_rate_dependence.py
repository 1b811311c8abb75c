"""The realistic plant's hysteresis depends on the rate; the capstan-only plant's does not."""

from __future__ import annotations

import math

import pytest

import tendonsheath as ts
from tendonsheath.bench.rate_dependence import hysteresis_loops, loops_figure

ROUTE = ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2), (0.5, math.pi / 2)])
COMMON = dict(pretension=20.0, proximal_radius=15e-3, distal_radius=15e-3, elements=40)


def test_capstan_only_loops_do_not_depend_on_rate():
    plant = ts.PullPullPlant(ROUTE, friction=0.1, stiffness=5e3, **COMMON)
    widths = [loop.width for loop in hysteresis_loops(plant).values()]
    # Coulomb friction is rate independent: equal to rounding (measured 0.16493 rad at all three)
    assert max(widths) - min(widths) < 1e-9


def test_realistic_loops_widen_with_rate():
    plant = ts.PullPullPlant(
        ROUTE,
        **COMMON,
        **ts.presets.realistic_plant(friction=0.1, stiffness=5e3),
        motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
    )
    loops = hysteresis_loops(plant)
    w = {f: loop.width for f, loop in loops.items()}
    # measured 0.205 / 0.235 / 0.398 rad at 0.1 / 1 / 5 Hz: thresholds keep about half of each
    # step's rise as margin, and both fail for a rate-independent loop
    assert w[1.0] > 1.07 * w[0.1]
    assert w[5.0] > 1.4 * w[1.0]
    assert loops_figure(loops).axes[0].get_legend() is not None


def test_loops_reject_bad_arguments():
    plant = ts.PullPullPlant(ROUTE, **COMMON)
    with pytest.raises(ValueError, match="cycles"):
        hysteresis_loops(plant, cycles=1)
    with pytest.raises(ValueError, match="frequencies"):
        hysteresis_loops(plant, frequencies=(0.0,))
