"""Common behaviour of the feedforward compensators: streaming and whole trajectories."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Self

from .._util.arrays import as_timed_signal, checked_dt
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike
from ..control_interop import _ControlBlock
from ..simulation_result import SimulationResult
from ..status import Status
from . import persistence


def command_result(t: Any, y_desired: Any, out: Any) -> SimulationResult:
    """A compensator's ``command`` result: the commands (an array) with ``t``, ``input`` (the
    desired outputs) and ``status`` (each cycle's Status flags, uint8), from `out` (the
    commands, or ``(commands, flags)`` as the C++ engines give them)."""
    commands, flags = out if isinstance(out, tuple) else (out, getattr(out, "status", None))
    return SimulationResult(commands, t=t, input=y_desired, status=flags)


class SavedAsJson:
    """Saving a compensator as its JSON file (``to_json``) and reading one back (``load``);
    the class gives ``to_dict``. A class that declares its file's keys (``_saved_settings``)
    is a kind of file ``load`` reads once registered under its name
    (:func:`~tendonsheath.compensate.persistence.register`, which
    :mod:`tendonsheath.compensate` calls with the compensators it exports)."""

    def to_dict(self) -> dict:
        """The compensator as a dict (format ``tendonsheath.compensator``): each class its own.

        Returns
        -------
        dict
            format, version, compensator and its settings.
        """
        raise NotImplementedError(f"{type(self).__name__} does not define to_dict")

    def to_json(self, path: str | Path | None = None) -> str:
        """The compensator as JSON text; also written to `path` when one is given.
        ``tendonsheath.compensate.load`` reads it; the C++ ``tendonsheath/io/json.hpp`` reads
        the feedforwards' files (not the AdaptiveController's), and
        ``tendonsheath/io/json_multi_input.hpp`` the LoadCompensated's and the
        CoupledFeedforward's.

        Parameters
        ----------
        path : str or Path, optional
            A file to write the JSON to.

        Returns
        -------
        str
            The JSON text.
        """
        return persistence.to_json(self.to_dict(), path)

    @classmethod
    def load(cls, source: str | Path | dict) -> Self:
        """A compensator saved with :meth:`to_json` (a path, JSON text or a dict); it must be
        of this class (``tendonsheath.compensate.load`` reads any).

        Parameters
        ----------
        source : str, Path or dict
            A path to a JSON file, JSON text, or the dict itself.

        Returns
        -------
        SavedAsJson
            The saved compensator, an instance of this class.

        Raises
        ------
        ValueError
            An unreadable source or an invalid compensator file.
        TypeError
            The file holds another kind of compensator.
        """
        return persistence.load_as(cls, source)


class EngineCompensator(PythonObject, SavedAsJson, _ControlBlock):
    """What every compensator built on a C++ engine shares: its status, its constructor
    settings and saving them (``to_json``/``load``), and the engine ``bench.run`` steps.

    Each subclass is also its bound C++ class (``class TipLoop(AroundFeedforward,
    core.TipLoop)``) and initialises it in its ``__init__``: the compensator *is* the real-time
    object the C++ closed loop steps."""

    _settings: dict  # the constructor's settings, saved by to_json
    _saved_settings: tuple[str, ...] = ()  # the keys of a saved file, in order

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status` (held input, saturated command, ...).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        return Status(self._bound_class.status(self))

    @property
    def params(self) -> dict:
        """The constructor settings, defaults resolved (a copy)."""
        return dict(self._settings)

    def to_dict(self) -> dict:
        """The compensator as a dict (format ``tendonsheath.compensator``; a model setting as
        the model's own dict, or null).

        Returns
        -------
        dict
            format, version, compensator and its settings.
        """
        return persistence.compensator_dict(type(self).__name__, self._settings)

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject): the constructor settings
        return dict(self._settings)

    def _recipe(self):
        # pickled as its saved file: an equal compensator at rest (tendonsheath._util.pyobject)
        # (with its design, where a tuning chose its gains: not part of the file)
        extra = {k: v for k, v in vars(self).items() if k == "design"}
        return persistence.load_compensator, (self.to_dict(),), extra

    @classmethod
    def _from_saved(cls, values: dict):
        return cls(**values)

    def bench_engine(self) -> Any:
        """The real-time object ``bench.run`` steps in its C++ loop: the compensator itself
        (:class:`~tendonsheath.protocols.BenchCompensator`).

        Returns
        -------
        object
            This compensator (its bound C++ class).
        """
        return self


class Feedforward(EngineCompensator):
    """A compensator that maps a desired distal trajectory to motor commands.

    ``step(y_d, dt)`` runs one control cycle (real-time core, no allocation);
    ``command(t, y_d)`` runs a whole trajectory in C++ from the initial state and
    leaves the streaming state untouched.
    """

    # signal names of to_control()'s system: desired output in, motor command out
    control_inputs: tuple[str, ...] = ("y_d",)
    control_output: str = "x"

    def reset(self) -> None:
        """Forget the streaming state (the desired-rate history and the last command)."""
        self._bound_class.reset(self)

    def step(self, y_d: float, dt: float) -> float:
        """One control cycle (real-time core, no allocation).

        Parameters
        ----------
        y_d : float
            Desired output (the model's output unit).
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The motor command.
        """
        dt = checked_dt(dt)
        return self._bound_class.step(self, float(y_d), float(dt))

    def command(self, t: ArrayLike, y_desired: ArrayLike) -> SimulationResult:
        """Motor commands for a whole trajectory, with each cycle's :class:`Status` flags
        (uint8) in the result's ``status``.

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        y_desired : array_like of float, shape (n,)
            Desired outputs.

        Returns
        -------
        SimulationResult, shape (n,)
            Motor commands (an array), with ``t``, ``input`` (y_desired) and ``status`` (each
            cycle's :class:`~tendonsheath.Status`, uint8).

        Raises
        ------
        ValueError
            t missing, or samples not finite or of different lengths.
        """
        ts, ys = as_timed_signal(t, y_desired, "y_desired", f"{type(self).__name__}.command")
        out = self._bound_class.command(self, ts, ys, True)
        return command_result(ts, ys, out)


__all__ = ["EngineCompensator", "Feedforward", "SavedAsJson"]
