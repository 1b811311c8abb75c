"""What every physics plant shares (spec A.5): the C++-backed streaming and batch simulation,
its route schedule, motor and sensor, the tensions after a step, and the SlackWarning.

The plants themselves: :mod:`~tendonsheath.plant.pull_pull`,
:mod:`~tendonsheath.plant.continuum`, :mod:`~tendonsheath.plant.single_tendon`.
"""

from __future__ import annotations

import functools
import inspect
import warnings
from collections.abc import Callable
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from .._util.args import integer, number
from .._util.arrays import as_time_and_signal, checked_dt
from .._util.pyobject import PythonObject, bound_attribute, constructor_arguments
from .._util.typing import ArrayLike
from ..simulation_result import SimulationResult
from ..status import Status
from . import _bound as core
from . import input_interpolation as reconstruction
from .motor import Motor
from .route import Route
from .sensor import Sensor

if TYPE_CHECKING:
    from matplotlib.axes import Axes


class SlackWarning(RuntimeWarning):
    """A tendon went slack (tension <= 0): the quasi-static model is not valid there."""


def _options(cls, max_increment, fast_path):
    o = core.ChainOptions()
    if max_increment is not None:
        o.max_increment = number(cls, "max_increment", max_increment)
    o.fast_path = bool(fast_path)
    return o


def _set_effects(p, cls, names, values):
    """Copy the effect keywords onto the C++ parameters (which validate them at construction)."""
    for name in names:
        value = values[name]
        if value is None:
            continue
        setattr(p, name, number(cls, name, value))


def _set_numbers(p, cls, names, values):
    for name in names:
        setattr(p, name, number(cls, name, values[name]))


def _row_arguments(plant: type) -> tuple[tuple[str, ...], tuple[str, ...]]:
    """The arguments of a plant's constructor that set a row of its table (``elements`` aside,
    checked on its own), in the signature's order: those with a default (numbers, always
    set) and those whose default is None (effects beyond the quasi-static chain, left at the
    C++ default, off, when None)."""
    owner = next(k for k in plant.__mro__ if "_table_struct" in vars(k))
    return _arguments_of_rows(owner, vars(owner)["_table_struct"])


@functools.cache
def _arguments_of_rows(owner: Any, struct: Any) -> tuple[tuple[str, ...], tuple[str, ...]]:
    rows = {r["name"] for r in struct.fields()} - {"elements"}
    params = inspect.signature(vars(owner)["__init__"]).parameters.values()
    numbers = tuple(p.name for p in params if p.name in rows and p.default is not None)
    effects = tuple(p.name for p in params if p.name in rows and p.default is None)
    return numbers, effects


def _effects_of(p, names) -> dict:
    return {name: getattr(p, name) for name in names}


def _check_elements(elements, cls):
    elements = integer(cls, "elements", elements)
    if elements < 2:
        raise ValueError(f"{cls}: elements must be >= 2 (got {elements})")
    return int(elements)


def _check_route(route, name, cls):
    if not isinstance(route, Route):
        raise TypeError(f"{cls}: {name} must be a tendonsheath.Route (got {type(route).__name__})")
    return route


def _rebuilt_plant(cls, arguments: dict, interpolation: tuple) -> _Plant:
    """A plant of class ``cls`` built with ``arguments``, its input interpolation set."""
    plant = cls(**arguments)
    plant.set_input_interpolation(*interpolation)
    return plant


def _encoder_reading(encoder: Sensor, t, q_motor: np.ndarray) -> np.ndarray:
    """What the motor encoder logs of the shaft angle ``q_motor`` at times ``t`` (its
    resolution, noise and latency, its noise sequence from its seed)."""
    engine = encoder.engine()
    return np.asarray(engine.measure_many(np.ascontiguousarray(q_motor, dtype=float),
                                          np.ascontiguousarray(t, dtype=float), 0.0))  # fmt: skip


class _Plant(PythonObject):
    """Shared streaming/batch behaviour; each subclass is also its bound C++ plant
    (``class PullPullPlant(_Plant, core.PullPullPlant)``), initialises it in its ``__init__``
    and describes its routes."""

    _rows = 1
    # the C++ parameter struct whose table the constructor's rows come from (table_constructor)
    _table_struct: ClassVar[Any] = None
    # the C++ motor the plant steps between command and pulley (a copy of ``motor``, at rest)
    _drive: Any = None
    motor: Motor | None = None
    sensor: Sensor | None = None
    encoder: Sensor | None = None
    _interpolation = (
        "hold",
        reconstruction.DEFAULT_SUBSTEPS,
        reconstruction.DEFAULT_LOOKAHEAD,
    )

    _arguments: dict  # the constructor's arguments, kept by _keep_arguments

    def _keep_arguments(self, values: dict[str, Any]) -> None:
        """Keep the constructor's arguments, read by :attr:`params` and pickling: each plant's
        ``__init__`` calls it first, with its ``locals()`` (a subclass's ``__init__`` that
        calls its parent's keeps its own: the outermost call's are kept)."""
        if "_arguments" not in vars(self):
            self._arguments = constructor_arguments(type(self), values)

    @property
    def params(self) -> dict:
        """The constructor's arguments, defaults filled in (a copy)."""
        return dict(self._arguments)

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject): the constructor's arguments
        return dict(self._arguments)

    def _recipe(self):
        # pickled as its constructor's arguments: an equal plant at rest (_util.pyobject)
        return _rebuilt_plant, (type(self), self._arguments, self._interpolation)

    def set_input_interpolation(
        self,
        mode: str,
        substeps: int = reconstruction.DEFAULT_SUBSTEPS,
        lookahead: int = reconstruction.DEFAULT_LOOKAHEAD,
    ) -> None:
        """The default reconstruction of the command between samples in :meth:`simulate`
        ("hold", "linear" or "bandlimited", on a grid ``substeps`` times finer; see
        :mod:`tendonsheath.plant.input_interpolation`). :meth:`step` stays causal (hold)
        whatever it is.

        Parameters
        ----------
        mode : {"hold", "linear", "bandlimited"}
            The reconstruction.
        substeps : int, optional
            Refinement of the grid (default
            ``tendonsheath.plant.input_interpolation.DEFAULT_SUBSTEPS``).
        lookahead : int, optional
            Half-width of the band-limited sinc in samples (default
            ``tendonsheath.plant.input_interpolation.DEFAULT_LOOKAHEAD``).

        Raises
        ------
        ValueError
            An unknown mode or a substeps or lookahead out of range.
        """
        reconstruction.check_interpolation(mode, substeps, lookahead, type(self).__name__)
        self._interpolation = (mode, int(substeps), int(lookahead))

    @property
    def input_interpolation(self) -> str:
        """The default reconstruction of the command in :meth:`simulate` ("hold", "linear" or
        "bandlimited"; see :meth:`set_input_interpolation`)."""
        return self._interpolation[0]

    def _setup_io(self, motor, sensor, encoder=None):
        for name, value, kind in (
            ("motor", motor, Motor),
            ("sensor", sensor, Sensor),
            ("encoder", encoder, Sensor),
        ):
            if value is not None and not isinstance(value, kind):
                raise TypeError(
                    f"{type(self).__name__}: {name} must be a tendonsheath.{kind.__name__} or "
                    f"None (got {type(value).__name__})"
                )
        if encoder is not None and motor is None:
            raise ValueError(
                f"{type(self).__name__}: an encoder reads a motor's shaft: give the plant a motor"
            )
        self.motor = motor
        self.sensor = sensor
        self.encoder = encoder
        self._drive = motor.engine() if motor is not None else None

    # -- streaming -------------------------------------------------------------------
    def reset(self) -> None:
        """Back to rest: uniform pretension, everything stuck; the next step starts there."""
        self._bound_class.reset(self)
        if self._drive is not None:
            self._drive.reset()

    def step(self, command: float, dt: float = 0.0) -> float:
        """One sample: the command goes through the motor (if any), then the plant.

        dt (s) is needed by a motor and by a damper load. A non-finite command holds the output.
        The first step after construction or ``reset()`` takes its command as the rest state
        (both tendons at pretension, output = command): start a stream from the position the
        mechanism is really at, e.g. ``step(0.0)``, or the first move skips the dead zone.

        Parameters
        ----------
        command : float
            The command (rad at the pulley; m for a single tendon; N m for a torque motor).
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        float
            The output after the step (rad; m for a single tendon).
        """
        dt = checked_dt(dt)
        u = float(command)
        if self._drive is not None:
            u = self._drive.step(u, float(dt), self._bound_class.drive_reaction(self))
        return self._bound_class.step(self, u, float(dt))

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status`: the plant's (held, clamped,
        not_converged, slack) and its motor's (held, clamped, saturated).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        s = self._bound_class.status(self)
        if self._drive is not None:
            s |= self._drive.status()
        return Status(s)

    def output(self) -> float:
        """The output after the last step (rad or m).

        Returns
        -------
        float
            The output.
        """
        return self._bound_class.output(self)

    def input(self) -> float:
        """The plant input after the motor (rad or m).

        Returns
        -------
        float
            The proximal pulley angle (rad) or displacement (m).
        """
        return self._bound_class.input(self)

    def motor_position(self) -> float:
        """The motor shaft's angle after the last step, before the gear's play: what its
        encoder reads (without a motor, the plant input).

        Returns
        -------
        float
            The shaft angle (rad; m for a single tendon).
        """
        if self._drive is None:
            return self.input()
        return float(self._drive.position())

    def tensions(self) -> np.ndarray:
        """Element tensions (N) after the last step, proximal to distal.

        Returns
        -------
        numpy.ndarray of float
            Shape (N,) for one tendon, (2, N) for a pair.
        """
        t = self._bound_class.tensions(self)
        return t[0] if self._rows == 1 else t

    def slip_state(self) -> np.ndarray:
        """Stick/slip map of the interior sheath nodes, proximal to distal: +1 slipping toward
        the proximal end (the tendon is pulled), -1 toward the distal end, 0 stuck.

        Returns
        -------
        numpy.ndarray of int
            Shape (N - 1,) for one tendon, (2, N - 1) for a pair.
        """
        s = self._bound_class.slip_state(self)
        return s[0] if self._rows == 1 else s

    def slack(self) -> bool:
        """True when a tendon tension is <= 0 after the last step.

        Returns
        -------
        bool
            Whether a tendon is slack.
        """
        return self._bound_class.slack(self)

    def min_tension(self) -> float:
        """The smallest element tension after the last step.

        Returns
        -------
        float
            The tension (N).
        """
        return self._bound_class.min_tension(self)

    @property
    def elements(self) -> int:
        """Elements N per sheath."""
        return bound_attribute(self, "elements")

    @property
    def friction(self) -> float:
        """Friction coefficient mu (of sheath 1 for a pair)."""
        return bound_attribute(self, "params").friction

    @property
    def stiffness(self) -> float:
        """Tendon axial stiffness EA (N) (of tendon 1 for a pair)."""
        return bound_attribute(self, "params").stiffness

    def element_positions(self, sheath: int = 1) -> np.ndarray:
        """Arc length (m) of each element's midpoint along its sheath, proximal to distal.

        Parameters
        ----------
        sheath : int, default 1
            1, or 2 for the second sheath of a pair.

        Returns
        -------
        numpy.ndarray of float, shape (N,)
            The midpoints (m).
        """
        L = self._lengths()[sheath - 1]
        n = self.elements
        return (np.arange(n) + 0.5) * L / n

    # -- batch -----------------------------------------------------------------------
    def simulate(
        self,
        t: ArrayLike | None,
        command: ArrayLike,
        routes: Callable | None = None,
        input_interpolation: str | None = None,
        periodic: bool | None = None,
    ) -> SimulationResult:
        """Simulate from rest (on the current route) without touching the streaming state.

        ``input_interpolation`` ("hold", "linear", "bandlimited"; default: the plant's, see
        :meth:`set_input_interpolation`) reconstructs the command between samples and steps
        the plant on the finer grid (uniform ``t`` needed); ``periodic`` (None: detected)
        picks exact FFT upsampling for a record of whole periods (see
        :mod:`tendonsheath.plant.input_interpolation`).

        ``t`` (s) may be None only without a motor, a damper and a route schedule. ``routes``
        is None or a callable t -> Route (or a (route1, route2) pair for a pull-pull plant); it
        is evaluated once per sample in Python and only the changes are passed to C++.
        Returns a :class:`SimulationResult` (q_out as an array, with the plant's fields; its
        ``status`` holds each sample's flags). Warns
        (:class:`SlackWarning`) with the time of the first slack sample.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s), increasing.
        command : array_like of float, shape (n,)
            Commands (as for :meth:`step`).
        routes : callable, optional
            t -> Route (or a (route1, route2) pair), evaluated at every sample.
        input_interpolation : {"hold", "linear", "bandlimited"}, optional
            The reconstruction of the command (default: the plant's).
        periodic : bool, optional
            Whether the record is a whole number of periods (None: detected).

        Returns
        -------
        result : SimulationResult, shape (n,)
            The output q_out, with ``command``, ``q_in``, ``q_motor``, ``measured``,
            ``slack``, ``tensions``, ``nonconverged``, ``status`` (each sample's Status
            flags, uint8) and ``input_interpolation``.

        Raises
        ------
        ValueError
            t missing where it is needed, routes not callable, a bad route, or bad samples.
        """
        name = f"{type(self).__name__}.simulate"
        ts, us = as_time_and_signal(t, command, "command")
        if ts is None and (self.motor is not None or routes is not None or self._needs_time()):
            raise ValueError(f"{name}: t is required with a motor, a damper or routes=")
        idx = angles = None
        if routes is not None:
            if not callable(routes):
                raise ValueError(f"{name}: routes must be None or a callable t -> Route")
            assert ts is not None  # routes without t raised above
            idx, angles = self.route_schedule(ts, routes)
        motor_arg = self.motor.engine() if self.motor is not None else None
        sensor_arg = self.sensor.engine() if self.sensor is not None else None
        mode, fine, lookahead = self._interpolation
        mode = mode if input_interpolation is None else input_interpolation
        reconstruction.check_interpolation(mode, fine, lookahead, name)
        how, t_run, u_run, idx_run = "hold", ts, us, idx
        if mode != "hold" and us.size > 1:
            if ts is None:
                raise ValueError(f"{name}: input_interpolation={mode!r} needs the time t")
            t_run, u_run, how = reconstruction.fine_grid(
                ts, us, mode, fine, lookahead, periodic, name
            )
            idx_run = None if idx is None else (idx * fine).astype(np.uint64)
        q_out, q_in, slack, meas, tens, noncon, q_motor, flags = self._bound_class.simulate(
            self, t_run, u_run, motor_arg, sensor_arg, idx_run, angles
        )
        if t_run is not ts:  # read at the original samples; slack anywhere in a step counts
            step = slice(None, None, fine)
            n = us.size
            slack = np.r_[slack[0], slack[1 : (n - 1) * fine + 1].reshape(n - 1, fine).any(axis=1)]
            flags = np.r_[
                flags[0],
                np.bitwise_or.reduce(flags[1 : (n - 1) * fine + 1].reshape(n - 1, fine), axis=1),
            ].astype(flags.dtype)
            q_out, q_in, meas = q_out[step], q_in[step], meas[step]
            q_motor = None if q_motor is None or q_motor.size == 0 else q_motor[step]
        self._warn_slack(ts, slack)
        if self.encoder is not None and q_motor is not None and q_motor.size:
            q_motor = _encoder_reading(self.encoder, ts, q_motor)
        return SimulationResult(
            q_out,
            t=ts,
            input=us,
            command=us,
            q_in=q_in,
            measured=meas,
            slack=slack,
            tensions=tens[0] if self._rows == 1 else tens,
            nonconverged=int(noncon),
            q_motor=q_motor,
            status=flags,
            input_interpolation=how,
        )

    def _warn_slack(self, ts, slack) -> None:
        """A SlackWarning with the time of the first slack sample (pointing at the caller of
        simulate)."""
        if not slack.any():
            return
        k = int(np.flatnonzero(slack)[0])
        when = f"t = {ts[k]:.6g} s" if ts is not None else "the start"
        warnings.warn(
            f"{type(self).__name__}: a tendon went slack (tension <= 0) first at {when} "
            f"(sample {k}, {int(slack.sum())} samples in all); the quasi-static model is not "
            f"valid there: raise the pretension or lower the load",
            SlackWarning,
            stacklevel=3,
        )

    def route_schedule(self, t: ArrayLike, routes: Callable) -> tuple[np.ndarray, np.ndarray]:
        """The route changes of ``routes`` over the times ``t``, as the C++ loops take them:
        the sample indices where the route changes (the first always 0) and each new route's
        node angles (what :meth:`simulate` and :func:`tendonsheath.bench.run` pass to C++).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s).
        routes : callable
            t -> Route (or a (route1, route2) pair for a pull-pull plant).

        Returns
        -------
        index : numpy.ndarray of uint64
            The samples at which the route changes.
        angles : numpy.ndarray of float, shape (changes, node angles)
            Each new route's node angles (:meth:`node_angles`).

        Raises
        ------
        ValueError
            A route of the wrong kind or length.
        """
        idx, rows = [], []
        prev_obj = object()
        prev = None
        for k, tk in enumerate(np.asarray(t, dtype=float)):
            r = routes(float(tk))
            if r is prev_obj:
                continue
            prev_obj = r
            a = self._angles_for(r)
            if prev is not None and np.array_equal(a, prev):
                continue
            prev = a
            idx.append(k)
            rows.append(a)
        return (
            np.asarray(idx, dtype=np.uint64),
            np.ascontiguousarray(np.vstack(rows)),
        )

    def node_angles(self, route: Route | tuple[Route, Route]) -> np.ndarray:
        """The lumped node angles (rad) a route gives this plant's elements.

        Parameters
        ----------
        route : Route or (Route, Route)
            The route (a pull-pull plant: or the pair of its two sheaths).

        Returns
        -------
        numpy.ndarray of float
            The node angles, as the C++ plant's set_node_angles takes them.

        Raises
        ------
        ValueError
            A route of the wrong kind or length.
        """
        return self._angles_for(route)

    def _tendonsheath_plant(self):
        # what tendonsheath.bench.run steps: the C++ plant without the motor (the bench runs
        # the motor between controller and plant); the loop steps a copy
        return self

    def _lengths(self) -> tuple[float, ...]:
        raise NotImplementedError  # the subclass's sheath lengths

    def _angles_for(self, r) -> np.ndarray:
        raise NotImplementedError  # the subclass's node angles for a route

    def _needs_time(self) -> bool:
        return self._bound_class.time_dependent(self)

    def plot_tensions(self, ax: Axes | None = None) -> Axes:
        """Draw the tension profile along the route(s) (see :func:`tendonsheath.plots`).

        Parameters
        ----------
        ax : matplotlib.axes.Axes, optional
            Where to draw (default a new figure).

        Returns
        -------
        matplotlib.axes.Axes
            The axes drawn on.
        """
        from ..plots import plot_tension_profile

        return plot_tension_profile(self, ax=ax)


__all__ = ["SlackWarning"]
