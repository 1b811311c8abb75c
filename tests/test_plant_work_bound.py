"""The hard work bound of a plant step (issue 13 item 2, issue 16 item 9): no step makes more
than max_solves() = max_substeps + 2 (max_iterations + E) tridiagonal solves (E =
extra_iterations, -1: 2 M + 50; with the defaults 8 N + 264 for a pull-pull pair), whatever the
input; a step that reaches it reports NOT_CONVERGED and the plant goes on."""

from __future__ import annotations

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core


def adversarial(steps: int, n_angles: int, seed: int = 2):
    """Random routes every 250 steps, a sine with reversals, and a one-step jump of up to
    +-0.5 rad every 97 steps (each slackens a tendon behind the damped load)."""
    rng = np.random.default_rng(seed)
    t = np.arange(steps) * 1e-3
    q = 0.5 * np.sin(2 * np.pi * t) + 0.05 * np.sin(2 * np.pi * 37.0 * t)
    q[::97] += rng.uniform(-0.5, 0.5, q[::97].size)
    index = np.arange(0, steps, 250, dtype=np.uint64)
    totals = 0.3 + 8.0 * rng.uniform(size=index.size)
    angles = totals[:, None] * (0.2 + 1.6 * rng.uniform(size=(index.size, n_angles)))
    return q, index, angles / (n_angles // 2)


@pytest.mark.parametrize("elements", [20, 100])
def test_damped_load_never_exceeds_the_bound(elements):
    plant = ts.PullPullPlant(
        route=ts.Route.uniform(1.2, np.pi),
        elements=elements,
        load=ts.loads.SpringDamper(0.05, 0.01),
    )
    engine = plant
    assert engine.max_solves() == 8 * elements + 264
    q, index, angles = adversarial(3000, engine.n_node_angles)
    _, _, solves, status = engine.profile_steps(q, 1e-3, index, angles)
    assert solves.max() <= engine.max_solves()
    # the set is hard enough to reach the bound, and such steps say so
    flagged = (status & int(ts.Status.NOT_CONVERGED)) != 0
    assert (flagged & (solves == engine.max_solves())).any()
    # and the plant recovers: after a shock the tendon behind the damper stays slack for a few
    # steps (measured: at most 9 flagged in a row at N = 100), then the steps converge again
    for i in np.flatnonzero(flagged):
        assert not flagged[i : i + 20].all(), i


def test_a_step_past_the_bound_is_flagged_and_the_next_steps_recover():
    """Tight options (bound 4 + 2 (5 + 4) = 22 solves) and a damped load under the adversarial
    set: the first step that ends at the bound unconverged is flagged; holding its input, the
    plant gets there within a few steps and converges."""
    route = ts.Route.uniform(1.2, 2 * np.pi)
    p = core.PullPullParams()
    p.elements = 40
    p.load_stiffness, p.load_damping = 0.05, 0.01
    options = core.ChainOptions()
    options.max_iterations, options.max_halvings = 5, 1
    options.max_substeps, options.extra_iterations = 4, 4
    p.options = options
    tight = core.PullPullPlant(p, route, route)
    assert tight.max_solves() == 22
    q, index, angles = adversarial(3000, tight.n_node_angles)
    routes = dict(zip(index.tolist(), angles, strict=True))
    for k, x in enumerate(q):
        if k in routes:
            tight.set_node_angles(routes[k])
        tight.step(float(x), 1e-3)
        assert tight.last_solves() <= 22
        if tight.last_solves() == 22 and not tight.last_converged():
            break
    else:
        pytest.fail("the bound was never reached")
    assert ts.Status(tight.status()) & ts.Status.NOT_CONVERGED
    assert np.isfinite(tight.output())
    target = float(x)
    held = 0
    while held < 20 and not (tight.last_converged() and abs(tight.input() - target) < 1e-12):
        tight.step(float(x), 1e-3)
        held += 1
    assert held < 20
    assert np.all(np.isfinite(tight.tensions()))
