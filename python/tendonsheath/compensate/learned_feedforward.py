"""A learned correction table added to any feedforward's command (iterative learning control)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .._util.args import core_errors_as, number, number_array
from .._util.arrays import as_timed_signal, checked_dt
from .._util.param_table import TABLE, table_constructor
from .._util.pyobject import bound_attribute
from .._util.typing import ArrayLike, FloatArray
from .._util.units import warn_unit_slips
from ..simulation_result import SimulationResult
from . import _bound as core
from ._kinds import require_feedforward
from .around import AroundFeedforward
from .base import command_result
from .limits import CommandLimits, LimitsLike, as_limits


@table_constructor(core.LearnedFeedforwardParams)
class LearnedFeedforward(AroundFeedforward, core.LearnedCorrection):  # type: ignore[misc]
    """A feedforward's command plus a correction learned over repeated trials, played in time.

    Iterative learning (:class:`~tendonsheath.compensate.IterativeLearning`) learns, from the tip
    error of repeated runs of the same motion, a correction ``c(t)`` for each time ``t`` of the
    motion; this compensator plays it back in real time (C++ ``LearnedCorrection``), with or
    without the tip sensor::

        u = shape(feedforward(y_d) + c(t))

    where ``t`` is the time since :meth:`reset` (the sum of the steps' dt; the first step after
    a reset plays sample 0) and ``c`` is ``table`` interpolated linearly (sample ``i`` at
    ``t = i * table_dt``). Past the table's end it adds the last sample (``hold_last``) or 0,
    and the status has ``input_clamped``. A NaN command of the feedforward holds the last one.
    Put an :class:`~tendonsheath.compensate.EncoderLoop` (or a
    :class:`~tendonsheath.compensate.TipLoop`) around it to have the motor encoder follow (or
    the tip loop correct) the corrected command.

    Parameters
    ----------
    feedforward : compensator
        Any feedforward with ``reset()`` and ``step(y_d, dt)`` (a shipped InverseFeedforward,
        CurveAngleFeedforward or ContinuumFeedforward, or your own); not an EncoderLoop or a
        TipLoop (put that around this one instead).
    table : array_like of float, shape (n,)
        The correction (the command's unit, rad) at ``t = 0, table_dt, 2 table_dt, ...``;
        n >= 1, finite.
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the corrected command and its rate.

    Raises
    ------
    TypeError
        A feedforward without reset/step, or a setting of the wrong type.
    ValueError
        An empty table, a non-finite entry (its index named), table_dt <= 0, or bad limits.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    limits: CommandLimits

    control_inputs = ("y_d",)
    control_output = "x"
    _saved_settings = ("feedforward", "table", "table_dt", "hold_last", "limits")

    def __init__(
        self,
        feedforward: Any,
        table: ArrayLike,
        table_dt: float,
        hold_last: bool = TABLE,
        limits: LimitsLike = None,
    ):
        who = "LearnedFeedforward"
        require_feedforward(who, feedforward)
        takes_y_d = tuple(getattr(feedforward, "step_inputs", ("y_d",))) == ("y_d",)
        if not takes_y_d or isinstance(feedforward, LearnedFeedforward):
            raise TypeError(
                f"{who}: feedforward must be a feedforward compensator with reset() and "
                f"step(y_d, dt) (got {type(feedforward).__name__}; put an EncoderLoop or a "
                "TipLoop around the LearnedFeedforward, not inside it)"
            )
        values = number_array(who, "table", table)
        if values.ndim != 1:
            raise ValueError(f"{who}: table must be one-dimensional (got shape {values.shape})")
        if not isinstance(hold_last, bool | np.bool_):
            raise TypeError(f"{who}: hold_last must be True or False (got {hold_last!r})")
        p = core.LearnedFeedforwardParams()
        p.table_dt = number(who, "table_dt", table_dt)
        p.hold_last = bool(hold_last)
        self.limits = as_limits(limits)
        p.limits = self.limits.to_core()
        with core_errors_as(who):
            core.LearnedCorrection.__init__(self, values.tolist(), p)
        warn_unit_slips(who, p)
        self.feedforward = feedforward
        self._settings = {
            "table": values.tolist(),
            "table_dt": p.table_dt,
            "hold_last": p.hold_last,
            "limits": self.limits,
        }

    def with_table(self, table: ArrayLike) -> LearnedFeedforward:
        """The same feedforward and settings with another correction table.

        Parameters
        ----------
        table : array_like of float, shape (m,)
            The new correction table.

        Returns
        -------
        LearnedFeedforward
            A new compensator (the feedforward object is shared).
        """
        return LearnedFeedforward(
            self.feedforward, table, self.table_dt, self.hold_last, limits=self.limits
        )

    # -- streaming ------------------------------------------------------------------
    def reset(self) -> None:
        """Forget the feedforward's state; the table's time back to 0."""
        self.feedforward.reset()
        core.LearnedCorrection.reset(self)

    def step(self, y_d: float, dt: float) -> float:
        """One control cycle: the feedforward's command plus the table at the time since reset.

        Parameters
        ----------
        y_d : float
            Desired output.
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The corrected command (rad).
        """
        dt = checked_dt(dt)
        x = float(self.feedforward.step(float(y_d), dt))
        return self.correct(x, dt)

    def command(self, t: ArrayLike, y_desired: ArrayLike) -> SimulationResult:
        """Corrected commands for a whole trajectory, from the initial state (the streaming
        state is left untouched); the feedforward must have ``command(t, y_d)``.

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing.
        y_desired : array_like of float, shape (n,)
            Desired outputs.

        Returns
        -------
        SimulationResult, shape (n,)
            The commands, with ``t``, ``input`` (y_desired) and ``status`` (each cycle's
            flags: the feedforward's, where its result has them, and the table's).

        Raises
        ------
        TypeError
            The feedforward has no ``command``.
        """
        inner = getattr(self.feedforward, "command", None)
        if not callable(inner):
            raise TypeError(
                f"LearnedFeedforward.command: its feedforward {type(self.feedforward).__name__} "
                "has no command(t, y_d)"
            )
        ts, ys = as_timed_signal(t, y_desired, "y_desired", "LearnedFeedforward.command")
        x = inner(ts, ys)
        u, flags = self.play(ts, np.ascontiguousarray(x, dtype=np.float64))
        inner_flags = getattr(x, "status", None)
        if inner_flags is not None:
            flags = (flags | np.asarray(inner_flags, dtype=np.uint8)).astype(np.uint8)
        return command_result(ts, ys, (u, flags))

    @property
    def table(self) -> FloatArray:  # type: ignore[override]
        """The correction table (a copy)."""
        return np.array(self._settings["table"], dtype=np.float64)

    @property
    def table_dt(self) -> float:
        """Time between the table's samples (s)."""
        return float(self._settings["table_dt"])

    @property
    def hold_last(self) -> bool:
        """Whether the last sample is held past the table's end (else 0 is added)."""
        return bool(self._settings["hold_last"])

    @property
    def correction(self) -> float:  # type: ignore[override]
        """The correction added in the last step."""
        return core.LearnedCorrection.correction(self)

    @property
    def time(self) -> float:  # type: ignore[override]
        """The time since reset (s) the table was read at in the last step."""
        return core.LearnedCorrection.time(self)

    def at(self, t: ArrayLike) -> FloatArray:  # type: ignore[override]
        """The table interpolated at times ``t`` (s; past the end the last sample or 0).

        Parameters
        ----------
        t : array_like of float
            Times since the start (s).

        Returns
        -------
        numpy.ndarray of float
            The corrections.
        """
        times = np.asarray(t, dtype=np.float64)
        return np.array([core.LearnedCorrection.at(self, float(v)) for v in times.ravel()]).reshape(
            times.shape
        )

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], dt)

    # -- the bench and persistence ------------------------------------------------------
    @classmethod
    def _from_saved(cls, values: dict):
        try:
            return cls(**values)
        except TypeError as err:  # a file whose feedforward cannot be inside: a bad file
            raise ValueError(f"LearnedFeedforward file: {err}") from None

    def bench_stage(self) -> tuple[Any, Any]:
        """The C++ table player and the feedforward it adds to, for bench.run's C++ loop
        (:class:`~tendonsheath.protocols.BenchCompensator`).

        Returns
        -------
        (object, compensator)
            The correction table's real-time player, and the feedforward.
        """
        return core.LearnedCorrection(
            self._settings["table"], bound_attribute(self, "params")
        ), self.feedforward

    def __repr__(self) -> str:
        n = len(self._settings["table"])
        span = (n - 1) * self.table_dt
        peak = max((abs(v) for v in self._settings["table"]), default=0.0)
        return (
            f"LearnedFeedforward({self.feedforward!r}, {n} samples over {span:g} s, "
            f"peak {peak:.3g}{'' if self.hold_last else ', zero past the end'})"
        )


__all__ = ["LearnedFeedforward"]
