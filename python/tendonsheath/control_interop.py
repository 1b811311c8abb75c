"""python-control interop: models and compensators as discrete-time NonlinearIOSystems.

Every model and compensator updates its state from one sample to the next (``step(x, dt)``),
so its system is discrete-time with the sample time ``dt`` the user gives. The engines keep
their state inside C++ objects whose layout differs from class to class, so the system's
state vector does not spell that state out: it holds one number, the index of a *snapshot*,
an exact copy of the engine after a given input history. The system keeps its snapshots;
stepping a copy of snapshot ``i`` with input ``u`` gives the output, and the stepped copy is
filed as a new snapshot, whose index is the next state; each distinct ``(i, u)`` is stepped
once and remembered. Output and update are therefore pure functions of ``(state, input)``,
as ``control.interconnect`` and ``control.input_output_response`` need, and index 0 (the
default initial state) is the engine at rest, as ``simulate`` and ``command`` start.

What this rules out: ``linearize``, ``find_eqpt`` and any continuous-state algebra on the
index. Each distinct step keeps one engine copy and its output for the life of the system
(see ``benchmarks/python_control.py`` for the memory and CPU time per sample); ``simulate``
and ``command`` stay the way to run long records.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Sequence
from types import ModuleType
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numpy.typing import ArrayLike

from ._util.extras import require

if TYPE_CHECKING:
    import control  # python-control ships no types: its systems are Any to mypy


def require_control() -> ModuleType:
    """The ``control`` module, or an ImportError that says how to install it.

    Returns
    -------
    module
        python-control.

    Raises
    ------
    MissingExtraError
        python-control is not installed (the ``control`` extra; an ImportError).
    """
    return require("control", extra="control", feature="python-control interop")


class _Block(Protocol):
    """What a system steps: a model or a compensator (deep-copyable)."""

    @property
    def control_inputs(self) -> tuple[str, ...]: ...

    @property
    def control_output(self) -> str: ...

    def reset(self) -> None: ...

    def _control_step(self, u: Sequence[float], dt: float) -> float: ...


class _Stepping(Protocol):
    """A block's streaming step (its signals, then dt)."""

    def step(self, *signals: Any, **options: Any) -> float: ...


class Snapshots:
    """Engine snapshots addressed by a float index; index 0 is the engine at rest.

    ``block`` is a model or compensator: deep-copyable, with ``reset()`` and
    ``_control_step(u, dt)`` (u: the input vector); a block's first step gets dt = 0, as in
    ``simulate`` and ``command``.

    Parameters
    ----------
    block : model or compensator
        The block to step (deep-copied; the original is not touched).
    dt : float
        Sample time (s).
    """

    def __init__(self, block: _Block, dt: float):
        fresh = copy.deepcopy(block)
        fresh.reset()
        self.dt = dt
        self._engines: list[tuple[Any, bool]] = [(fresh, False)]
        self._next: dict[tuple, tuple[int, float]] = {}

    def __len__(self) -> int:
        return len(self._engines)

    def _at(self, state) -> tuple[Any, bool]:
        value = float(np.asarray(state, dtype=float).reshape(-1)[0])
        index = int(value) if math.isfinite(value) else -1
        if index != value or not 0 <= index < len(self._engines):
            raise ValueError(
                f"tendonsheath control system: the state is a snapshot index (0 = at rest, "
                f"0..{len(self._engines) - 1} known), got {value!r}"
            )
        return self._engines[index]

    def _advance(self, state, u) -> tuple[int, float]:
        """(index of the snapshot after input u, output at u) from the snapshot ``state``:
        stepped once per distinct (state, input), then remembered."""
        key = (float(np.asarray(state).reshape(-1)[0]), tuple(float(v) for v in u))
        if key not in self._next:
            engine, started = self._at(state)
            engine = copy.deepcopy(engine)
            y = float(engine._control_step(u, self.dt if started else 0.0))
            self._engines.append((engine, True))
            self._next[key] = (len(self._engines) - 1, y)
        return self._next[key]

    def output(self, state: ArrayLike, u: Sequence[float]) -> float:
        """The block's output for input u from snapshot ``state``.

        Parameters
        ----------
        state : array_like of float
            The snapshot index (the system's one state).
        u : array_like of float
            The input vector.

        Returns
        -------
        float
            The output.

        Raises
        ------
        ValueError
            A state that is not a known snapshot index.
        """
        return self._advance(state, u)[1]

    def update(self, state: ArrayLike, u: Sequence[float]) -> int:
        """The snapshot index after input u from snapshot ``state``.

        Parameters
        ----------
        state : array_like of float
            The snapshot index (the system's one state).
        u : array_like of float
            The input vector.

        Returns
        -------
        int
            The next state.

        Raises
        ------
        ValueError
            A state that is not a known snapshot index.
        """
        return self._advance(state, u)[0]


def to_system(
    block: _Block,
    dt: float,
    inputs: Sequence[str] | None = None,
    output: str | None = None,
    name: str | None = None,
) -> control.NonlinearIOSystem:
    """A ``control.NonlinearIOSystem`` (discrete, sample time dt) stepping ``block``; the
    signal names default to the block's ``control_inputs`` and ``control_output``.

    Parameters
    ----------
    block : model or compensator
        The block.
    dt : float
        Sample time (s), finite and > 0.
    inputs : sequence of str, optional
        Input signal names, as many as the block's.
    output : str, optional
        Output signal name.
    name : str, optional
        The system's name.

    Returns
    -------
    control.NonlinearIOSystem
        The system, with its ``snapshots`` attached.

    Raises
    ------
    ValueError
        A wrong number of input names, a bad dt, or a block that streams with a delay.
    ImportError
        python-control is not installed.
    """
    control = require_control()
    inputs = list(block.control_inputs if inputs is None else inputs)
    if len(inputs) != len(block.control_inputs):
        raise ValueError(
            f"to_control: {type(block).__name__} has {len(block.control_inputs)} input(s) "
            f"{list(block.control_inputs)}; got the names {inputs}"
        )
    output = block.control_output if output is None else output
    number = isinstance(dt, int | float) and not isinstance(dt, bool)
    if not (number and math.isfinite(dt) and dt > 0):
        raise ValueError(f"to_control: dt must be a finite sample time > 0 in s (got {dt!r})")
    lag = streaming_delay(block)
    if lag:
        raise ValueError(
            f"to_control: {type(block).__name__} streams with a delay of {lag} samples "
            "(input_interpolation='bandlimited'); use 'linear' or 'hold'"
        )
    snaps = Snapshots(block, float(dt))
    system = control.nlsys(
        lambda t, x, u, params: np.array([snaps.update(x, u)], dtype=float),
        lambda t, x, u, params: np.array([snaps.output(x, u)]),
        inputs=inputs,
        outputs=[output],
        states=["snapshot"],
        dt=float(dt),
        name=name,
    )
    system.snapshots = snaps
    return system


class _ControlBlock:
    """What makes a model or a compensator a python-control system: :meth:`to_control`, over
    its ``step`` and its signal names ``control_inputs`` and ``control_output``."""

    def to_control(
        self: _Block,
        dt: float,
        name: str | None = None,
        inputs: Sequence[str] | None = None,
        output: str | None = None,
    ) -> control.NonlinearIOSystem:
        """This block as a discrete-time ``control.NonlinearIOSystem`` with sample time dt (s),
        inputs ``control_inputs`` and output ``control_output``: a model maps ``x`` (and
        ``curve_angle`` where it takes one) to ``y``; a feedforward maps ``y_d`` to ``x``, the
        input name of a model's system, so ``control.interconnect`` connects them by name; the
        AdaptiveController maps ``y_d``, ``y`` (measured output) and ``q`` (motor angle) to
        ``torque``. One state, the index of an exact snapshot of the engine (see
        :mod:`tendonsheath.control_interop`). Needs python-control:
        ``pip install 'tendonsheath[control]'``.

        Parameters
        ----------
        dt : float
            Sample time (s), > 0.
        name : str, optional
            The system's name.
        inputs : str or list of str, optional
            Input signal names (default ``control_inputs``).
        output : str, optional
            Output signal name (default ``control_output``).

        Returns
        -------
        control.NonlinearIOSystem
            The discrete-time system.
        """
        return to_system(self, dt, inputs, output, name)

    def _control_step(self: _Stepping, u: Sequence[float], dt: float) -> float:
        return self.step(u[0], dt)


def streaming_delay(block: _Block) -> int:
    """Samples by which ``block.step`` lags its input (parts of a Chain or Scaled included).

    Parameters
    ----------
    block : model or compensator
        The block.

    Returns
    -------
    int
        The delay in samples.
    """
    lag = getattr(block, "delay", 0)
    lag = lag if isinstance(lag, int) else 0
    for part in ("first", "second", "inner"):
        inner = getattr(block, part, None)
        if inner is not None and inner is not block and hasattr(inner, "step"):
            lag += streaming_delay(inner)
    return lag


def frequency_response_data(
    frequencies_hz: ArrayLike, gain_db: ArrayLike, phase_deg: ArrayLike, name: str | None = None
) -> control.FrequencyResponseData:
    """``control.FrequencyResponseData`` from gains (dB) and phases (deg) at frequencies (Hz).

    Parameters
    ----------
    frequencies_hz : array_like of float
        Frequencies (Hz).
    gain_db : array_like of float
        Gains (dB).
    phase_deg : array_like of float
        Phases (deg).
    name : str, optional
        The system's name.

    Returns
    -------
    control.FrequencyResponseData
        The response at omega = 2 pi f (rad/s).
    """
    control = require_control()
    f = np.asarray(frequencies_hz, dtype=float)
    response = 10.0 ** (np.asarray(gain_db, dtype=float) / 20.0) * np.exp(
        1j * np.radians(np.asarray(phase_deg, dtype=float))
    )
    return control.FrequencyResponseData(response, 2.0 * np.pi * f, name=name)


__all__ = [
    "Snapshots",
    "frequency_response_data",
    "require_control",
    "streaming_delay",
    "to_system",
]
