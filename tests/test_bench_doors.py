"""The doors of bench.run for a user's own classes (issue 37, item 6): a plant with only
``reset()`` and ``step(command, dt)`` closes the loop (no ``params``, no ``simulate``), and a
compensator whose ``step`` takes a measurement it did not declare is one line naming the
declaration (``step_inputs``), before the loop runs, never a bare TypeError from inside it
nor dt read as the measurement."""

from __future__ import annotations

import math

import numpy as np
import pytest

import tendonsheath as ts


class Lag:
    """A first-order lag, the smallest plant: y' = (u - y) / tau, exact for a held command."""

    def __init__(self, tau: float) -> None:
        self.tau, self.y = tau, 0.0

    def reset(self) -> None:
        self.y = 0.0

    def step(self, command: float, dt: float) -> float:
        a = math.exp(-dt / self.tau)
        self.y = a * self.y + (1.0 - a) * command
        return self.y


class Proportional:
    """u = y_d + gain (y_d - y): it reads the measured output, and says so."""

    step_inputs = ("y_d", "y")

    def __init__(self, gain: float) -> None:
        self.gain = gain

    def reset(self) -> None:
        pass

    def step(self, y_d: float, y: float, dt: float) -> float:
        return y_d + self.gain * (y_d - y)


def _by_hand(t, y_d, tau, gain):
    """The loop written out: each cycle reads the output of the previous one (0 at rest),
    commands, and the lag holds that command over the cycle (dt = 0 at the first sample)."""
    y, outputs, commands = 0.0, [], []
    for k in range(t.size):
        dt = 0.0 if k == 0 else t[k] - t[k - 1]
        u = y_d[k] + gain * (y_d[k] - y)
        a = math.exp(-dt / tau)
        y = a * y + (1.0 - a) * u
        outputs.append(y)
        commands.append(u)
    return np.array(outputs), np.array(commands)


def test_a_plant_of_two_methods_closes_the_loop_as_computed_by_hand():
    rng = np.random.default_rng(37)
    for _ in range(5):
        tau, gain = rng.uniform(0.005, 0.1), rng.uniform(0.0, 4.0)
        dt, f = rng.uniform(2e-4, 2e-3), rng.uniform(0.5, 5.0)
        t = np.arange(0.0, 0.4, dt)
        y_d = rng.uniform(0.1, 1.0) * np.sin(2 * np.pi * f * t)
        plant = Lag(tau)
        assert not hasattr(plant, "params") and not hasattr(plant, "simulate")
        result = ts.bench.run(plant, Proportional(gain), t, y_d)
        outputs, commands = _by_hand(t, y_d, tau, gain)
        # the same arithmetic in the same order: equal to rounding
        np.testing.assert_allclose(result.output, outputs, rtol=0, atol=1e-14)
        np.testing.assert_allclose(result.command, commands, rtol=0, atol=1e-14)
        np.testing.assert_array_equal(result.measured, result.output)  # no sensor: exact
        assert result.metrics["rmse"] > 0 and not result.slack.any()


def test_a_plant_without_step_is_named():
    class NoStep:
        def reset(self):
            pass

    with pytest.raises(ValueError, match=r"NoStep has no step: a plant needs reset\(\) and step"):
        ts.bench.run(NoStep(), Proportional(1.0), [0.0, 1e-3], [0.0, 0.1])


def _compensator(step, declared=None):
    namespace = {"reset": lambda self: None, "step": step}
    if declared is not None:
        namespace["step_inputs"] = declared
    return type("MyComp", (), namespace)()


UNDECLARED = [
    # a measurement before dt, not declared: the loop would pass one signal too few
    (
        lambda self, y_d, y, dt: y_d,
        None,
        r"takes a measurement before dt.*step_inputs = \('y_d', 'y'\)",
    ),
    # dt with a default after it: the loop would pass dt as y, silently, before this check
    (lambda self, y_d, y, dt=1e-3: y_d, None, r"takes a measurement.*step_inputs = \('y_d', 'y'\)"),
    (lambda self, y_d, q, dt: y_d, None, r"step_inputs = \('y_d', 'q'\)"),
    # a measurement after dt: named, with the order the loop calls step in
    (lambda self, y_d, dt, y: y_d, None, r"takes y after dt.*step\(y_d, y, dt\)"),
    # a name that is no signal: the declaration is shown by example
    (lambda self, y_d, tip, dt: y_d, None, r"step_inputs \(e\.g\. \('y_d', 'y'\)"),
    # a keyword-only measurement: the loop passes signals positionally
    (lambda self, y_d, dt, *, y: y_d, None, r"takes y as keyword-only.*step_inputs"),
    # declared, but step does not take it
    (lambda self, y_d, dt: y_d, ("y_d", "y"), r"its step_inputs \['y_d', 'y'\] pass 2.*\('y_d',\)"),
]


@pytest.mark.parametrize(("step", "declared", "message"), UNDECLARED)
def test_a_step_that_does_not_match_its_declaration_is_one_line_naming_it(step, declared, message):
    t = np.arange(0.0, 0.01, 1e-3)
    with pytest.raises(TypeError, match=r"^MyComp\.step") as err:
        ts.bench.run(Lag(0.02), _compensator(step, declared), t, 0.1 * t)
    assert "\n" not in str(err.value)
    assert err.match(message)


def test_the_declared_step_runs():
    t = np.arange(0.0, 0.01, 1e-3)
    comp = _compensator(lambda self, y_d, y, dt: y_d + (y_d - y), ("y_d", "y"))
    assert np.all(np.isfinite(ts.bench.run(Lag(0.02), comp, t, 0.1 * t).output))
