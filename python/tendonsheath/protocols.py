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
* :class:`BenchCompensator`: exactly what :func:`bench.run <tendonsheath.bench.run>` asks of
  a compensator: ``reset()`` and ``step(...)``, and the optional declarations it reads
  (``step_inputs``, ``control_output``, ``bench_engine()``, ``bench_stage()``) with their
  defaults; :func:`bench_declarations` reads them.
* :class:`Compensator`: a streaming compensator that can also be saved: ``params``,
  ``to_json`` and a classmethod ``load`` (the shipped ones: ``tendonsheath.compensate.load``).
* :class:`FeedforwardCompensator`: a compensator with ``command(t, y_desired)``, a whole
  trajectory at once (the feedforwards; a feedback controller has none).
* :class:`SteppedPlant`: ``reset`` and ``step(command, dt)``: all that :func:`bench.run
  <tendonsheath.bench.run>` needs of a plant (what else it reads where a plant has it, such as
  its ``motor``, is listed in :mod:`tendonsheath.bench.plant_loop`).
* :class:`Plant`: a stepped plant that also has ``simulate`` and ``params`` (the shipped ones;
  a scenario's calibration simulates whole records).
"""

from __future__ import annotations

import inspect
from dataclasses import dataclass
from typing import Any, Protocol, runtime_checkable

__all__ = [
    "BenchCompensator",
    "BenchDeclarations",
    "Compensator",
    "FeedforwardCompensator",
    "Plant",
    "SteppedPlant",
    "StreamingCompensator",
    "bench_declarations",
    "missing_members",
    "step_signals",
]

# the signals a compensator's step may ask for, by their to_control() names
STEP_SIGNALS = ("y_d", "y", "q")


@runtime_checkable
class StreamingCompensator(Protocol):
    """One control cycle at a time: ``reset()``, then ``step(<step_inputs>, dt)``.

    A structural protocol: it is never instantiated; ``isinstance`` checks that an object has
    ``reset`` and ``step``.
    """

    def reset(self) -> None:
        """Forget the state: the next :meth:`step` starts a new run.

        Returns
        -------
        None
        """

    def step(self, *signals: float) -> float:
        """One control cycle.

        Parameters
        ----------
        *signals : float
            The signals named by the compensator's ``step_inputs`` (default ``("y_d",)``: the
            desired output; ``"y"``: the measured output, NaN in a sensor dropout; ``"q"``:
            the motor encoder angle), in that order, then dt, the time since the previous
            cycle (s).

        Returns
        -------
        float
            The command: a motor angle (rad), or a torque (N m) when the compensator's
            ``control_output`` is ``"torque"``.
        """


class BenchCompensator(StreamingCompensator, Protocol):
    """Everything :func:`bench.run <tendonsheath.bench.run>` asks of a compensator.

    Required: ``reset()`` and ``step(<step_inputs>, dt)`` (:class:`StreamingCompensator`).
    Optional, each read with its default where the compensator lacks it
    (:func:`bench_declarations`):

    * ``step_inputs`` (default ``("y_d",)``): the signals ``step`` takes before dt, among
      ``"y_d"`` (desired output), ``"y"`` (measured output, NaN in a sensor dropout) and
      ``"q"`` (motor encoder angle).
    * ``control_output`` (default ``"x"``, a motor angle): ``"torque"`` for a torque command
      (the bench then needs a torque motor on the plant).
    * :meth:`bench_engine` (default None): the real-time object the C++ loop steps at C++
      speed instead of calling ``step`` from Python.
    * :meth:`bench_stage` (default None): a C++ stage the loop runs around an inner
      compensator (a feedback loop around a feedforward, a learned table added to it).

    A compensator compiled with ``tendonsheath_bind/compensator.hpp`` gives its engine as its
    binding's ``_tendonsheath_compensator()`` capsule instead of :meth:`bench_engine`.

    A structural protocol for type checkers, never instantiated: it types each member as the
    loop reads it. Since all but ``reset`` and ``step`` are optional, it is not checked with
    ``isinstance`` (``isinstance(obj, StreamingCompensator)`` checks the two required ones).
    """

    step_inputs: tuple[str, ...]
    control_output: str

    def bench_engine(self) -> Any:
        """The bound C++ object the closed loop steps in C++ (a shipped compensator gives
        itself); None: the loop calls :meth:`step` from Python.

        Returns
        -------
        object or None
            The engine.
        """

    def bench_stage(self) -> tuple[Any, Any] | None:
        """A C++ stage the closed loop runs around an inner compensator, and that inner
        compensator (read in turn with :func:`bench_declarations`); None: no stage.

        Returns
        -------
        (stage, inner) or None
            ``stage`` is a bound ``EncoderLoop`` or ``TipLoop`` (a feedback loop around the
            inner compensator's command) or ``LearnedCorrection`` (a table added to it).
        """


@dataclass(frozen=True)
class BenchDeclarations:
    """What a compensator declares to the closed loop: each optional member of
    :class:`BenchCompensator`, or its default.

    Parameters
    ----------
    step_inputs : tuple of str
        The signals its ``step`` takes before dt, as declared (:func:`step_signals` checks
        them against ``step``).
    control_output : str
        ``"x"`` (a motor angle) or ``"torque"``.
    engine : object or None
        What the C++ loop steps (a bound C++ compensator, or a compiled one's capsule); None:
        ``step`` is called from Python.
    compiled : bool
        Whether ``engine`` is a compiled compensator's capsule.
    stage : (object, object) or None
        A C++ stage around an inner compensator, and that compensator.
    """

    step_inputs: tuple[str, ...]
    control_output: str
    engine: Any
    compiled: bool
    stage: tuple[Any, Any] | None


def bench_declarations(compensator: object) -> BenchDeclarations:
    """The optional members of :class:`BenchCompensator` that ``compensator`` declares, each
    defaulted where it lacks them.

    Parameters
    ----------
    compensator : object
        A streaming compensator.

    Returns
    -------
    BenchDeclarations
        Its step inputs, control output, engine and stage.
    """
    compiled = getattr(compensator, "_tendonsheath_compensator", None)
    engine_of = compiled if callable(compiled) else getattr(compensator, "bench_engine", None)
    stage_of = getattr(compensator, "bench_stage", None)
    return BenchDeclarations(
        step_inputs=tuple(getattr(compensator, "step_inputs", ("y_d",))),
        control_output=str(getattr(compensator, "control_output", "x")),
        engine=engine_of() if callable(engine_of) else None,
        compiled=callable(compiled),
        stage=stage_of() if callable(stage_of) else None,
    )


@runtime_checkable
class Compensator(StreamingCompensator, Protocol):
    """A streaming compensator that can be saved and loaded back.

    A structural protocol: it is never instantiated; ``isinstance`` checks that an object has
    ``reset``, ``step``, ``params``, ``to_json`` and ``load``.
    """

    @property
    def params(self) -> dict[str, Any]:
        """The settings it was built with (a copy): what :meth:`to_json` saves."""

    def to_json(self, path: Any = None) -> str:
        """The compensator as JSON text; also written to `path` when one is given.

        Parameters
        ----------
        path : str or Path, optional
            A file to write the JSON to.

        Returns
        -------
        str
            The JSON text, which :meth:`load` reads back.
        """

    @classmethod
    def load(cls, source: Any) -> Compensator:
        """A compensator saved with :meth:`to_json`.

        Parameters
        ----------
        source : str, Path or dict
            A path to a JSON file, JSON text, or the dict itself.

        Returns
        -------
        Compensator
            The saved compensator, an instance of this class.
        """


@runtime_checkable
class FeedforwardCompensator(Compensator, Protocol):
    """A compensator that also maps a whole desired trajectory to motor commands.

    A structural protocol: it is never instantiated; ``isinstance`` checks that an object has
    the members of :class:`Compensator` and ``command``.
    """

    def command(self, t: Any, y_desired: Any) -> Any:
        """The motor commands for a whole desired trajectory, from the initial state.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s).
        y_desired : array_like of float, shape (n,)
            The desired output.

        Returns
        -------
        numpy.ndarray of float, shape (n,)
            The commands.
        """


@runtime_checkable
class SteppedPlant(Protocol):
    """A drive stepped one sample at a time: all that :func:`bench.run
    <tendonsheath.bench.run>` asks of a plant.

    A structural protocol: it is never instantiated; ``isinstance`` checks that an object has
    ``reset`` and ``step``.
    """

    def reset(self) -> None:
        """Back to rest: the next :meth:`step` starts there.

        Returns
        -------
        None
        """

    def step(self, command: float, dt: float = 0.0) -> float:
        """One sample.

        Parameters
        ----------
        command : float
            The command (rad at the pulley; m for a single tendon; N m for a torque motor).
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        float
            The output after the step.
        """


@runtime_checkable
class Plant(SteppedPlant, Protocol):
    """A simulated drive: streaming (``reset``/``step``) and whole records (``simulate``).

    A structural protocol: it is never instantiated; ``isinstance`` checks that an object has
    ``reset``, ``step``, ``params`` and ``simulate``.
    """

    @property
    def params(self) -> dict[str, Any]:
        """The constructor's arguments, defaults filled in (a copy)."""

    def simulate(self, t: Any, command: Any) -> Any:
        """A whole record from rest, without touching the streaming state.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s), increasing.
        command : array_like of float, shape (n,)
            The commands.

        Returns
        -------
        SimulationResult
            The output samples, with what produced them.
        """


def missing_members(obj: object, protocol: type) -> list[str]:
    """The members of ``protocol`` that ``obj`` lacks (or has but cannot call), in order.

    Unlike ``isinstance(obj, protocol)``, it says which members are missing, for an error
    message; ``params`` may be any attribute, the other members must be callable.

    Parameters
    ----------
    obj : object
        The candidate compensator or plant.
    protocol : type
        One of this module's protocols, e.g. :class:`StreamingCompensator`.

    Returns
    -------
    list of str
        The missing member names, in the protocol's order (empty: ``obj`` has them all).
    """
    missing = []
    for name in _members(protocol):
        if not hasattr(obj, name):
            missing.append(name)
        elif name not in ("params",) and not callable(getattr(obj, name)):
            missing.append(name)
    return missing


def step_signals(compensator: object) -> tuple[str, ...]:
    """The signals ``compensator.step`` takes before dt: its ``step_inputs`` (checked).

    Parameters
    ----------
    compensator : object
        A streaming compensator; without a ``step_inputs`` attribute it takes ``("y_d",)``.

    Returns
    -------
    tuple of str
        The signal names, in the order ``step`` takes them: ``"y_d"`` (desired output),
        ``"y"`` (measured output) or ``"q"`` (motor encoder angle).

    Raises
    ------
    TypeError
        ``step_inputs`` is empty, repeats a signal, or names one that is not among these.
    """
    inputs = tuple(getattr(compensator, "step_inputs", ("y_d",)))
    bad = [s for s in inputs if s not in STEP_SIGNALS]
    if bad or len(set(inputs)) != len(inputs) or not inputs:
        raise TypeError(
            f"{type(compensator).__name__}.step_inputs must name distinct signals among "
            f"{list(STEP_SIGNALS)} (got {list(inputs)})"
        )
    _check_step_arguments(compensator, inputs)
    return inputs


def _check_step_arguments(compensator: object, inputs: tuple[str, ...]) -> None:
    """``step`` takes the signals ``inputs`` names, then dt: else the loop would fail on its
    first step, deep inside, or (a ``dt`` with a default after an undeclared measurement) feed
    dt in as the measurement. A step without a signature to read (a compiled one) is its
    binding's to check."""
    if callable(getattr(compensator, "_tendonsheath_compensator", None)):
        return
    try:
        params = list(inspect.signature(compensator.step).parameters.values())  # type: ignore[attr-defined]
    except (AttributeError, TypeError, ValueError):
        return
    if any(p.kind is p.VAR_POSITIONAL for p in params):
        return
    name = type(compensator).__name__
    keyword_only = [p.name for p in params if p.kind is p.KEYWORD_ONLY and p.default is p.empty]
    if keyword_only:
        raise TypeError(
            f"{name}.step takes {', '.join(keyword_only)} as keyword-only argument(s), but the "
            "loop passes the signals positionally, then dt: make them positional and declare "
            f"the class attribute step_inputs (the signals before dt, among {list(STEP_SIGNALS)})"
        )
    positional = [p for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    names = [p.name for p in positional]
    required = [p for p in positional if p.default is p.empty]
    dt_at = names.index("dt") if "dt" in names else None
    fits = len(required) <= len(inputs) + 1 <= len(positional)
    if fits and dt_at in (None, len(inputs)):
        return
    if dt_at is None:
        signals, after_dt = names[: max(len(required) - 1, 1)], []
    else:
        after_dt = [p.name for p in required if names.index(p.name) > dt_at]
        signals = names[:dt_at] + after_dt
    raise TypeError(_undeclared_signals(compensator, names, signals, after_dt, inputs))


def _undeclared_signals(compensator: object, names, signals, after_dt, inputs) -> str:
    """One line: what ``step`` takes, what the loop would pass, what to declare."""
    name = type(compensator).__name__
    told = "its step_inputs" if hasattr(compensator, "step_inputs") else "the default step_inputs"
    if after_dt:
        what = f"{', '.join(after_dt)} after dt (the loop passes the signals, then dt)"
    elif len(signals) > len(inputs):
        what = f"a measurement before dt, but {told} {list(inputs)} pass only {len(inputs)}"
    else:
        what = f"{len(signals)} signal(s) before dt, but {told} {list(inputs)} pass {len(inputs)}"
    if all(s in STEP_SIGNALS for s in signals) and len(set(signals)) == len(signals) > 0:
        declare = f"step_inputs = {tuple(signals)!r}"
    else:
        declare = "step_inputs (e.g. ('y_d', 'y') for a step(y_d, y, dt))"
    where = f" and take them before dt: step({', '.join(signals)}, dt)" if after_dt else ""
    return (
        f"{name}.step({', '.join(names)}) takes {what}: declare the class attribute "
        f'{declare}{where} (in order, among "y_d" the desired output, "y" the measured output, '
        '"q" the motor encoder angle)'
    )


def _members(protocol: type) -> list[str]:
    names: list[str] = []
    for base in reversed(protocol.__mro__):
        if base is object or base is Protocol or not getattr(base, "_is_protocol", False):
            continue
        for name in vars(base):
            if not name.startswith("_") and name not in names:
                names.append(name)
    return names
