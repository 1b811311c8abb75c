"""Common behaviour of the feedforward compensators: streaming and whole trajectories."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self

import numpy as np

from .._arrays import as_time_and_signal, checked_dt
from .._typing import ArrayLike, FloatArray
from ..status import Status
from . import persistence

if TYPE_CHECKING:
    import control  # python-control ships no types: its systems are Any to mypy


class Feedforward:
    """A compensator that maps a desired distal trajectory to motor commands.

    ``step(y_d, dt)`` runs one control cycle (real-time core, no allocation);
    ``command(t, y_d)`` runs a whole trajectory in C++ from the initial state and
    leaves the streaming state untouched.
    """

    _engine: Any  # the C++ compensator the subclass builds (each its own class)
    _settings: dict  # the constructor's settings, saved by to_json
    _saved_settings: tuple[str, ...] = ()  # the keys of a saved file, in order
    # signal names of to_control()'s system: desired output in, motor command out
    control_inputs: tuple[str, ...] = ("y_d",)
    control_output: str = "x"

    def reset(self) -> None:
        """Forget the streaming state (the desired-rate history and the last command)."""
        self._engine.reset()

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
        return self._engine.step(float(y_d), float(dt))

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status` (held y_d, saturated command, ...).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        return Status(self._engine.status())

    def command(
        self, t: ArrayLike, y_desired: ArrayLike, status: bool = False
    ) -> FloatArray | tuple[FloatArray, np.ndarray]:
        """Motor commands for a whole trajectory; with ``status=True`` returns
        ``(commands, flags)``, flags holding each cycle's :class:`Status` (uint8).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        y_desired : array_like of float, shape (n,)
            Desired outputs.
        status : bool, default False
            Also return each cycle's Status flags.

        Returns
        -------
        commands : numpy.ndarray of float, shape (n,)
            Motor commands; ``(commands, flags)`` with ``status=True``, flags each cycle's
            :class:`~tendonsheath.Status` (uint8).

        Raises
        ------
        ValueError
            t missing, or samples not finite or of different lengths.
        """
        ts, ys = as_time_and_signal(t, y_desired, "y_desired")
        if ts is None:
            raise ValueError(f"{type(self).__name__}.command needs the time vector t")
        return self._engine.command(ts, ys, bool(status))

    def to_control(
        self,
        dt: float,
        name: str | None = None,
        inputs: Sequence[str] | None = None,
        output: str | None = None,
    ) -> control.NonlinearIOSystem:
        """This compensator as a discrete-time ``control.NonlinearIOSystem`` with sample time dt
        (s): input ``y_d``, output ``x`` (the motor command, the input name of a model's
        system, so ``control.interconnect`` connects them by name); one state, the index of an
        exact snapshot of the engine (see :mod:`tendonsheath.control_interop`).

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
        from ..control_interop import to_system

        return to_system(self, dt, inputs, output, name)

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], dt)

    # -- persistence -----------------------------------------------------------------
    @property
    def params(self) -> dict:
        """The constructor settings (a copy)."""
        return dict(self._settings)

    def to_dict(self) -> dict:
        """The compensator as a dict (format ``tendonsheath.compensator``).

        Returns
        -------
        dict
            format, version, compensator and its settings.
        """
        return persistence.compensator_dict(type(self).__name__, self._settings)

    def to_json(self, path: str | Path | None = None) -> str:
        """The compensator as JSON text; also written to `path` when one is given.
        ``tendonsheath.compensate.load`` and the C++ ``tendonsheath/io/json.hpp`` read it.

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
        Feedforward
            The saved compensator, an instance of this class.

        Raises
        ------
        ValueError
            An unreadable source or an invalid compensator file.
        TypeError
            The file holds another kind of compensator.
        """
        return persistence.load_as(cls, source)

    @classmethod
    def _from_saved(cls, values: dict):
        return cls(**values)

    def _bench_engine(self):
        """The C++ engine ``bench.run`` runs in its C++ loop (None: step it from Python)."""
        return self._engine
