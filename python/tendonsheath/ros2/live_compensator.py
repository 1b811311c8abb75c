"""A saved compensator stepped from the latest inputs a robot sent, each cycle, with no ROS in
it: what the compensator node runs (and what its tests and benchmarks step directly).

Every input is the last value received and when it came. An input older than ``stale_after``
seconds (or never received) is given to the compensator as NaN, and the compensator's own
real-time core does what its status says for a missing value: a feedforward holds its last
command (``held_nonfinite_input``), a tip or encoder loop runs its fallback (``fallback``), a
LoadCompensated holds the last load. The loop's own limits (range, rate) cut the command
after the compensator and raise ``saturated``. When the desired input has been stale for
``stop_after`` seconds the loop stops: no command until a fresh one arrives.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..compensate.around import follows_route
from ..compensate.coupled_feedforward import CoupledFeedforward
from ..compensate.load_compensated import LoadCompensated
from ..plant.route import Route
from ..protocols import step_signals
from ..status import Status

#: The inputs a compensator may take, by the names the node's topics use.
INPUTS = ("desired", "tip", "motor", "load", "curve_angle")
# step_inputs' names (protocols.STEP_SIGNALS) -> the node's input names
_SIGNAL_INPUT = {"y_d": "desired", "y": "tip", "q": "motor"}


def needed_inputs(compensator: Any) -> tuple[str, ...]:
    """The inputs ``compensator`` takes each cycle (among :data:`INPUTS`), desired first.

    Parameters
    ----------
    compensator : compensator
        Any compensator the library saves (or a streaming compensator).

    Returns
    -------
    tuple of str
        "desired", then "tip" (the measured output), "motor" (the encoder), "load" and
        "curve_angle" where it takes them.
    """
    if isinstance(compensator, CoupledFeedforward):
        return ("desired",)
    if isinstance(compensator, LoadCompensated):  # step(y_d, dt, load): the load after dt
        names = ["desired", "load"]
    else:
        names = [_SIGNAL_INPUT[s] for s in step_signals(compensator)]
    if follows_route(compensator):
        names.append("curve_angle")
    return tuple(names)


@dataclass
class _Input:
    """The last value of one input (one float per joint) and when it came (s)."""

    value: np.ndarray
    stamp: float = -math.inf

    def fresh(self, now: float, stale_after: float) -> bool:
        return now - self.stamp <= stale_after


@dataclass
class Cycle:
    """What one cycle of a :class:`LiveCompensator` did.

    Parameters
    ----------
    command : numpy.ndarray of float or None
        One command per joint (None: stopped, or no desired input yet).
    status : Status
        The compensator's flags, and ``saturated`` where the loop's limits cut the command.
    stale : tuple of str
        The inputs that were stale (or never received) this cycle.
    stopped : bool
        The loop is stopped (no desired input for ``stop_after`` seconds, or none yet).
    """

    command: np.ndarray | None
    status: Status
    stale: tuple[str, ...] = field(default_factory=tuple)
    stopped: bool = False


@dataclass
class Limits:
    """The loop's own command limits, applied after the compensator's.

    Parameters
    ----------
    minimum : float, default -inf
        Lowest command.
    maximum : float, default inf
        Highest command.
    max_rate : float, default inf
        Largest change of the command per second.
    """

    minimum: float = -math.inf
    maximum: float = math.inf
    max_rate: float = math.inf

    def __post_init__(self):
        if not self.minimum <= self.maximum:
            raise ValueError(
                f"command limits: minimum {self.minimum:g} is above maximum {self.maximum:g}"
            )
        if not self.max_rate > 0:
            raise ValueError(f"command limits: max_rate must be > 0 (got {self.max_rate:g})")


class LiveCompensator:
    """A compensator stepped from its latest inputs: see the module.

    Parameters
    ----------
    compensator : compensator
        A saved compensator (``ts.compensate.load``) of any kind.
    joints : int, default 1
        How many joints; a CoupledFeedforward's count is its own.
    stale_after : float, default 0.05
        Seconds after which an input counts as missing (> 0).
    stop_after : float, default inf
        Seconds of stale desired input after which the loop stops commanding (> 0).
    limits : Limits, optional
        The loop's own command limits.

    Raises
    ------
    ValueError
        joints that do not match the compensator, or a bad time.
    """

    def __init__(
        self,
        compensator: Any,
        joints: int = 1,
        stale_after: float = 0.05,
        stop_after: float = math.inf,
        limits: Limits | None = None,
    ):
        if isinstance(compensator, CoupledFeedforward):
            if joints not in (1, len(compensator.joints)):
                raise ValueError(
                    f"the CoupledFeedforward drives {len(compensator.joints)} joints "
                    f"(got {joints} joint names)"
                )
            joints = len(compensator.joints)
        elif joints != 1:
            raise ValueError(
                f"a {type(compensator).__name__} drives one joint (got {joints} joint names)"
            )
        if not (stale_after > 0 and stop_after > 0):
            raise ValueError("stale_after and stop_after must be > 0 seconds")
        self.compensator = compensator
        self.joints = int(joints)
        self.inputs = needed_inputs(compensator)
        self.stale_after, self.stop_after = float(stale_after), float(stop_after)
        self.limits = limits or Limits()
        self.reset()

    def reset(self) -> None:
        """Forget every input and the compensator's state."""
        self.compensator.reset()
        self._last = {name: _Input(np.full(self.joints, np.nan)) for name in INPUTS}
        self._command: np.ndarray | None = None
        self._shape_seen = -math.inf
        self._route: Route | None = None  # the last route received (else a curve angle)

    def update(self, name: str, value: Any, now: float) -> None:
        """A new value of input ``name`` (one per joint; NaN where a joint was not in the
        message), received at ``now`` (s).

        Parameters
        ----------
        name : str
            One of :data:`INPUTS`.
        value : float or array_like of float or Route
            The value(s); a curve angle may be a Route (its exact shape).
        now : float
            The time it was received (s, the loop's clock).

        Raises
        ------
        ValueError
            An unknown input.
        """
        if name not in INPUTS:
            raise ValueError(f"unknown input {name!r}; known: {list(INPUTS)}")
        if isinstance(value, Route):
            self._route = value
            self._last[name] = _Input(np.array([value.curve_angle]), float(now))
            return
        arr = np.asarray(value, dtype=np.float64).reshape(-1)
        old = self._last[name].value
        new = np.where(np.isfinite(arr), arr, old) if arr.size == old.size else arr
        if name == "curve_angle":
            self._route = None
        self._last[name] = _Input(new, float(now))

    def step(self, now: float, dt: float) -> Cycle:
        """One control cycle at time ``now`` (s), ``dt`` (s) after the previous one.

        Parameters
        ----------
        now : float
            The loop's clock (s).
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        Cycle
            The commands, the flags and the stale inputs.
        """
        stale = tuple(n for n in self.inputs if not self._last[n].fresh(now, self.stale_after))
        desired = self._last["desired"]
        if desired.stamp == -math.inf or now - desired.stamp > self.stop_after:
            self._command = None
            return Cycle(None, Status.OK, stale, stopped=True)
        self._take_shape()
        values = {
            n: self._last[n].value if n not in stale else np.full(self.joints, np.nan)
            for n in self.inputs
        }
        raw = self._call(values, dt)
        status = self._status()
        command, cut = self._limited(raw, dt)
        if cut:
            status |= Status.SATURATED
        self._command = command
        return Cycle(command.copy(), status, stale)

    def _take_shape(self) -> None:
        """A curve angle (or route) received since the last cycle goes to the compensator."""
        if "curve_angle" not in self.inputs:
            return
        angle = self._last["curve_angle"]
        if angle.stamp <= self._shape_seen or not np.isfinite(angle.value[0]):
            return
        self._shape_seen = angle.stamp
        route = self._route
        if route is not None:
            self.compensator.set_route(route)
        else:
            self.compensator.set_curve_angle(max(float(angle.value[0]), 0.0))

    def _call(self, values: dict[str, np.ndarray], dt: float) -> np.ndarray:
        comp = self.compensator
        if isinstance(comp, CoupledFeedforward):
            return np.asarray(comp.step(values["desired"], dt), dtype=np.float64)
        if isinstance(comp, LoadCompensated):
            return np.array([comp.step(values["desired"][0], dt, values["load"][0])])
        args = [values[_SIGNAL_INPUT[s]][0] for s in step_signals(comp)]
        return np.array([float(comp.step(*args, dt))])

    def _status(self) -> Status:
        comp = self.compensator
        own = getattr(comp, "status", None)
        if not callable(own) and isinstance(comp, LoadCompensated):
            own = comp.inverse.status
        return Status(int(own())) if callable(own) else Status.OK

    def _limited(self, raw: np.ndarray, dt: float) -> tuple[np.ndarray, bool]:
        lim = self.limits
        cmd = np.clip(raw, lim.minimum, lim.maximum)
        if self._command is not None and math.isfinite(lim.max_rate):
            step = lim.max_rate * dt
            cmd = np.clip(cmd, self._command - step, self._command + step)
        finite = np.isfinite(raw)
        cut = bool(np.any(np.abs(cmd[finite] - raw[finite]) > 0.0))
        return cmd, cut


__all__ = ["INPUTS", "Cycle", "Limits", "LiveCompensator", "needed_inputs"]
