"""What a compensator and a plant are to the rest of the package: structural protocols.

Any object with these members works where the package takes a compensator or a plant; it need
not inherit from a tendonsheath class. ``isinstance(obj, Compensator)`` checks that the members
are there (not their signatures).

* :class:`StreamingCompensator`: ``reset()`` and ``step(...)``, all that :func:`bench.run
  <tendonsheath.bench.run>` calls. ``step`` takes the signals named by the optional attribute
  ``step_inputs`` (default ``("y_d",)``: the desired output; ``"y"``: the measured output,
  NaN in a sensor dropout; ``"q"``: the motor encoder angle), then ``dt`` (s), and returns the
  command: a motor angle, or a torque when the optional attribute ``control_output`` is
  ``"torque"`` (the bench then needs a torque motor on the plant).
* :class:`Compensator`: a streaming compensator that can also be saved: ``params``,
  ``to_json`` and a classmethod ``load`` (the shipped ones: ``tendonsheath.compensate.load``).
* :class:`FeedforwardCompensator`: a compensator with ``command(t, y_desired)``, a whole
  trajectory at once (the feedforwards; a feedback controller has none).
* :class:`Plant`: ``reset``, ``step``, ``simulate`` and ``params``.
"""

from __future__ import annotations

from typing import Any, Protocol, runtime_checkable

__all__ = [
    "Compensator",
    "FeedforwardCompensator",
    "Plant",
    "StreamingCompensator",
    "missing_members",
    "step_signals",
]

# the signals a compensator's step may ask for, by their to_control() names
STEP_SIGNALS = ("y_d", "y", "q")


@runtime_checkable
class StreamingCompensator(Protocol):
    """One control cycle at a time: ``reset()``, then ``step(<step_inputs>, dt)``."""

    def reset(self) -> None: ...

    # (*Any, **Any): any step signature matches (it takes step_inputs, then dt)
    def step(self, *signals: Any, **options: Any) -> float: ...


@runtime_checkable
class Compensator(StreamingCompensator, Protocol):
    """A streaming compensator that can be saved and loaded back."""

    @property
    def params(self) -> dict[str, Any]: ...

    def to_json(self, path: Any = None) -> str: ...

    @classmethod
    def load(cls, source: Any) -> Compensator: ...


@runtime_checkable
class FeedforwardCompensator(Compensator, Protocol):
    """A compensator that also maps a whole desired trajectory to motor commands."""

    def command(self, t: Any, y_desired: Any) -> Any: ...


@runtime_checkable
class Plant(Protocol):
    """A simulated drive: streaming (``reset``/``step``) and whole records (``simulate``)."""

    @property
    def params(self) -> dict[str, Any]: ...

    def reset(self) -> None: ...

    def step(self, command: float, dt: float = 0.0) -> float: ...

    def simulate(self, t: Any, command: Any) -> Any: ...


def missing_members(obj: object, protocol: type) -> list[str]:
    """The members of ``protocol`` that ``obj`` lacks (or has but cannot call), in order."""
    missing = []
    for name in _members(protocol):
        if not hasattr(obj, name):
            missing.append(name)
        elif name not in ("params",) and not callable(getattr(obj, name)):
            missing.append(name)
    return missing


def step_signals(compensator: object) -> tuple[str, ...]:
    """The signals ``compensator.step`` takes before dt: its ``step_inputs`` (checked)."""
    inputs = tuple(getattr(compensator, "step_inputs", ("y_d",)))
    bad = [s for s in inputs if s not in STEP_SIGNALS]
    if bad or len(set(inputs)) != len(inputs) or not inputs:
        raise TypeError(
            f"{type(compensator).__name__}.step_inputs must name distinct signals among "
            f"{list(STEP_SIGNALS)} (got {list(inputs)})"
        )
    return inputs


def _members(protocol: type) -> list[str]:
    names: list[str] = []
    for base in reversed(protocol.__mro__):
        if base is object or base is Protocol or not getattr(base, "_is_protocol", False):
            continue
        for name in vars(base):
            if not name.startswith("_") and name not in names:
                names.append(name)
    return names
