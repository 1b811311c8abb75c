"""Physics plants of spec A.5: quasi-static N-element tendon-sheath simulators (C++ core).

* :class:`PullPullPlant`: the bidirectional pair of Sun, Wang & Phee 2015 and Do
  et al. 2015; pulley angle in, pulley angle out (rad).
* :class:`ContinuumPlant`: the pair bending a continuum segment (Lau et al. 2015); output the
  bending angle (rad).
* :class:`SingleTendonPlant`: one tendon, proximal displacement in, distal displacement out (m).

Every plant simulates in C++ (``simulate``) or streams (``reset``/``step``); its route may change
at any step (``set_route``, or ``routes=`` a callable of time in ``simulate``). Tensions and the
stick/slip map are readable after any step. Slack (a tendon tension <= 0) invalidates the model:
it is flagged per sample in the full result and raises a :class:`SlackWarning`.
"""

from __future__ import annotations

import functools
import inspect
import math
import warnings
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from .. import _core as core
from .._args import core_errors_as, integer, number
from .._arrays import as_time_and_signal, checked_dt
from .._pyobject import PythonObject
from .._typing import ArrayLike
from ..simulation_result import SimulationResult
from ..status import Status
from . import input_interpolation as reconstruction
from . import physics
from .loads import (
    ConstantForce,
    ConstantTorque,
    LinearSpring,
    SpringDamper,
    SpringPreload,
    TorsionalSpring,
)
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


# Effects beyond the quasi-static capstan chain (C++ parameter names); None leaves the default.
_RATE_EFFECTS = ("sheath_viscosity", "relaxation_fraction", "relaxation_time")
_PAIR_EFFECTS = ("distal_inertia", "distal_damping", *_RATE_EFFECTS, "friction2", "stiffness2")


def _set_effects(p, cls, names, values):
    """Copy the effect keywords onto the C++ parameters (which validate them at construction)."""
    for name in names:
        value = values[name]
        if value is None:
            continue
        setattr(p, name, number(cls, name, value))


# The plants' scalar parameters (same names in Python and C++).
_PAIR_NUMBERS = ("friction", "stiffness", "pretension", "proximal_radius", "distal_radius")
_CONTINUUM_NUMBERS = (
    *_PAIR_NUMBERS[:4],
    "bending_stiffness",
    "tendon_offset",
    "backbone_length",
)


def _set_numbers(p, cls, names, values):
    for name in names:
        setattr(p, name, number(cls, name, values[name]))


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


def _recording_arguments(init):
    """``init`` that first keeps its bound arguments as ``self._arguments`` (the outermost
    constructor's, when a subclass's calls its parent's)."""
    signature = inspect.signature(init)

    @functools.wraps(init)
    def wrapper(self, *args, **kwargs):
        if not hasattr(self, "_arguments"):
            try:
                bound = signature.bind(self, *args, **kwargs)
            except TypeError:  # the constructor itself names the bad argument
                return init(self, *args, **kwargs)
            bound.apply_defaults()
            self._arguments = _flat_arguments(signature, bound.arguments)
        init(self, *args, **kwargs)

    return wrapper


def _flat_arguments(signature, arguments: dict) -> dict:
    """Bound arguments without ``self``, a ``**kwargs`` catch-all spread into its keys."""
    out = {}
    for name, value in list(arguments.items())[1:]:
        if signature.parameters[name].kind is inspect.Parameter.VAR_KEYWORD:
            out.update(value)
        else:
            out[name] = value
    return out


def _rebuilt_plant(cls, arguments: dict, interpolation: tuple) -> _Plant:
    """A plant of class ``cls`` built with ``arguments``, its input interpolation set."""
    plant = cls(**arguments)
    plant.set_input_interpolation(*interpolation)
    return plant


class _Plant(PythonObject):
    """Shared streaming/batch behaviour; subclasses build ``_engine`` and describe their routes."""

    _rows = 1
    # core.SingleTendonPlant, core.PullPullPlant or core.ContinuumPlant, built by the subclass
    _engine: Any = None
    motor: Motor | None = None
    sensor: Sensor | None = None
    _interpolation = (
        "hold",
        reconstruction.DEFAULT_SUBSTEPS,
        reconstruction.DEFAULT_LOOKAHEAD,
    )

    _arguments: dict  # the constructor's arguments, kept by _recording_arguments

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        if "__init__" in vars(cls):
            cls.__init__ = _recording_arguments(cls.__init__)

    @property
    def params(self) -> dict:
        """The constructor's arguments, defaults filled in (a copy)."""
        return dict(self._arguments)

    def _recipe(self):
        # pickled as its constructor's arguments: an equal plant at rest (tendonsheath._pyobject)
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

    def _setup_io(self, motor, sensor):
        if motor is not None and not isinstance(motor, Motor):
            raise TypeError(
                f"{type(self).__name__}: motor must be a tendonsheath.Motor or None "
                f"(got {type(motor).__name__})"
            )
        if sensor is not None and not isinstance(sensor, Sensor):
            raise TypeError(
                f"{type(self).__name__}: sensor must be a tendonsheath.Sensor or None "
                f"(got {type(sensor).__name__})"
            )
        self.motor = motor
        self.sensor = sensor
        self._motor_engine = motor.engine() if motor is not None else None

    # -- streaming -------------------------------------------------------------------
    def reset(self) -> None:
        """Back to rest: uniform pretension, everything stuck; the next step starts there."""
        self._engine.reset()
        if self._motor_engine is not None:
            self._motor_engine.reset()

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
        if self._motor_engine is not None:
            u = self._motor_engine.step(u, float(dt), self._engine.drive_reaction())
        return self._engine.step(u, float(dt))

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status`: the plant's (held, clamped,
        not_converged, slack) and its motor's (held, clamped, saturated).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        s = self._engine.status()
        if self._motor_engine is not None:
            s |= self._motor_engine.status()
        return Status(s)

    def output(self) -> float:
        """The output after the last step (rad or m).

        Returns
        -------
        float
            The output.
        """
        return self._engine.output()

    def input(self) -> float:
        """The plant input after the motor (rad or m).

        Returns
        -------
        float
            The proximal pulley angle (rad) or displacement (m).
        """
        return self._engine.input()

    def tensions(self) -> np.ndarray:
        """Element tensions (N) after the last step, proximal to distal.

        Returns
        -------
        numpy.ndarray of float
            Shape (N,) for one tendon, (2, N) for a pair.
        """
        t = self._engine.tensions()
        return t[0] if self._rows == 1 else t

    def slip_state(self) -> np.ndarray:
        """Stick/slip map of the interior sheath nodes, proximal to distal: +1 slipping toward
        the proximal end (the tendon is pulled), -1 toward the distal end, 0 stuck.

        Returns
        -------
        numpy.ndarray of int
            Shape (N - 1,) for one tendon, (2, N - 1) for a pair.
        """
        s = self._engine.slip_state()
        return s[0] if self._rows == 1 else s

    def slack(self) -> bool:
        """True when a tendon tension is <= 0 after the last step.

        Returns
        -------
        bool
            Whether a tendon is slack.
        """
        return self._engine.slack()

    def min_tension(self) -> float:
        """The smallest element tension after the last step.

        Returns
        -------
        float
            The tension (N).
        """
        return self._engine.min_tension()

    @property
    def elements(self) -> int:
        """Elements N per sheath."""
        return self._engine.elements

    @property
    def friction(self) -> float:
        """Friction coefficient mu (of sheath 1 for a pair)."""
        return self._engine.params.friction

    @property
    def stiffness(self) -> float:
        """Tendon axial stiffness EA (N) (of tendon 1 for a pair)."""
        return self._engine.params.stiffness

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
        full: bool = False,
        input_interpolation: str | None = None,
        periodic: bool | None = None,
        status: bool = False,
    ) -> SimulationResult | tuple[SimulationResult, np.ndarray]:
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
        ``status`` holds each sample's flags), or ``(result, flags)`` with ``status=True``. Warns
        (:class:`SlackWarning`) with the time of the first slack sample.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s), increasing.
        command : array_like of float, shape (n,)
            Commands (as for :meth:`step`).
        routes : callable, optional
            t -> Route (or a (route1, route2) pair), evaluated at every sample.
        full : bool, default False
            Accepted for older code; the result is the same (it always has every field).
        input_interpolation : {"hold", "linear", "bandlimited"}, optional
            The reconstruction of the command (default: the plant's).
        periodic : bool, optional
            Whether the record is a whole number of periods (None: detected).
        status : bool, default False
            Also return each sample's Status flags.

        Returns
        -------
        result : SimulationResult, shape (n,)
            The output q_out, with ``command``, ``q_in``, ``q_motor``, ``measured``,
            ``slack``, ``tensions``, ``nonconverged``, ``status`` and ``input_interpolation``;
            ``(result, flags)`` with ``status=True``.

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
            idx, angles = self._schedule(ts, routes)
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
        q_out, q_in, slack, meas, tens, noncon, q_motor, flags = self._engine.simulate(
            t_run, u_run, motor_arg, sensor_arg, idx_run, angles
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
        result = SimulationResult(
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
        return (result, flags) if status else result

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
        return self._schedule(np.asarray(t, dtype=float), routes)

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
        # what tendonsheath.bench.run steps: the C++ engine without the motor (the bench runs
        # the motor between controller and plant); the loop steps a copy
        return self._engine

    def _schedule(self, ts, routes):
        idx, rows = [], []
        prev_obj = object()
        prev = None
        for k, tk in enumerate(ts):
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

    def _lengths(self) -> tuple[float, ...]:
        raise NotImplementedError  # the subclass's sheath lengths

    def _angles_for(self, r) -> np.ndarray:
        raise NotImplementedError  # the subclass's node angles for a route

    def _needs_time(self) -> bool:
        return self._engine.time_dependent()

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


class SingleTendonPlant(_Plant):
    """One tendon in one sheath: proximal displacement in (m), distal displacement out (m).

    ``load`` is a :class:`~tendonsheath.plant.loads.ConstantForce`, ``LinearSpring`` or
    ``SpringPreload`` pulling the distal end (default ConstantForce(10 N)).

    Parameters
    ----------
    route : Route
        Route of the sheath.
    friction : float, default 0.1
        Friction coefficient mu.
    stiffness : float, default 2.4e4
        Tendon axial stiffness EA (N).
    elements : int, default 100
        Elements N per sheath, >= 2.
    load : ConstantForce, LinearSpring or SpringPreload, optional
        The distal load (default ConstantForce(10.0)).
    motor : Motor, optional
        A drive between the command and the proximal pulley.
    sensor : Sensor, optional
        Reads the output (``SimulationResult.measured``).
    max_increment : float, optional
        Largest input sub-increment of the solver (m); None: the plant chooses.
    fast_path : bool, default True
        Use the solver's exact shortcuts (lazy update while the slip map stays valid).
    sheath_viscosity : float, optional
        Viscous drag on the sliding tendon (N s/m per metre of sheath; None: off).
    relaxation_fraction : float, optional
        Share r in [0, 1) of EA that relaxes (standard linear solid; None: off).
    relaxation_time : float, optional
        Time constant tau of the relaxation (s).

    Raises
    ------
    ValueError
        A route, load, motor or sensor of the wrong kind, elements not an integer >= 2, or a
        value the C++ core rejects (the message names it).
    TypeError
        An effect that is not a number.
    """

    _rows = 1

    def __init__(
        self,
        route: Route,
        friction: float = 0.1,
        stiffness: float = 2.4e4,
        elements: int = 100,
        load: ConstantForce | LinearSpring | SpringPreload | None = None,
        motor: Motor | None = None,
        sensor: Sensor | None = None,
        max_increment: float | None = None,
        fast_path: bool = True,
        sheath_viscosity: float | None = None,
        relaxation_fraction: float | None = None,
        relaxation_time: float | None = None,
    ):
        cls = type(self).__name__
        effects = {
            "sheath_viscosity": sheath_viscosity,
            "relaxation_fraction": relaxation_fraction,
            "relaxation_time": relaxation_time,
        }
        self.route = _check_route(route, "route", cls)
        load = ConstantForce(10.0) if load is None else load
        if not isinstance(load, ConstantForce | LinearSpring | SpringPreload):
            raise TypeError(
                f"{cls}: load must be ConstantForce, LinearSpring or SpringPreload "
                f"(got {type(load).__name__})"
            )
        self.load = load
        p = core.SingleTendonParams()
        p.friction = number(cls, "friction", friction)
        p.stiffness = number(cls, "stiffness", stiffness)
        p.elements = _check_elements(elements, cls)
        p.load_force, p.load_stiffness = load.linear()
        p.options = _options(cls, max_increment, fast_path)
        _set_effects(p, cls, _RATE_EFFECTS, effects)
        with core_errors_as(cls):
            self._engine = core.SingleTendonPlant(p, route._core)
        self._setup_io(motor, sensor)

    @property
    def kinematic_gain(self) -> float:
        """The uncompensated command per unit of desired output: 1 (m of proximal displacement
        per m of distal displacement)."""
        return 1.0

    def _lengths(self) -> tuple[float, ...]:
        return (self.route.length,)

    def set_route(self, route: Route) -> None:
        """Bend the sheath to a new route (same length); over-capacity nodes slip next step.

        Parameters
        ----------
        route : Route
            The new route, of the same length.

        Raises
        ------
        ValueError
            Not a Route, or of another length.
        """
        self._engine.set_route(_check_route(route, "route", type(self).__name__)._core)
        self.route = route

    def _angles_for(self, r):
        return self._engine.node_angles(_check_route(r, "routes(t)", type(self).__name__)._core)

    def closed_form(self) -> dict:
        """Capstan ratio and (A4) dead zone for the current route and load at rest (m).

        Returns
        -------
        dict
            ``capstan_ratio`` and ``dead_zone`` (m).
        """
        F0, _ = self.load.linear()
        return {
            "capstan_ratio": float(physics.capstan_ratio(self.friction, self.route.curve_angle)),
            "dead_zone": physics.single_tendon_dead_zone(
                self.route, self.stiffness, F0, self.friction
            ),
        }


class PullPullPlant(_Plant):
    """The bidirectional pull-pull pair (Sun, Wang & Phee 2015; Do et al. 2015): angle in and out.

    Two tendons with pretension T0 (N) and axial stiffness EA (``stiffness``, N) run in two
    sheaths (``route`` for tendon 1, the one a positive input pulls; ``route2`` for tendon 2,
    default the same) between a proximal pulley of radius r_p and a distal one of radius r_d
    (m). ``load`` (None, ConstantTorque, TorsionalSpring or SpringDamper) acts on the distal
    pulley. ``elements`` N per sheath; ``friction`` mu.

    Effects beyond the quasi-static capstan pair (all off by default; with none of them and
    no load the pair *is* a classic backlash, see :mod:`tendonsheath.plant.presets` for realistic
    values):

    - ``distal_inertia`` J_d (kg m^2) and ``distal_damping`` c_d (N m s/rad): a dynamic distal
      joint;
    - ``sheath_viscosity`` (N s/m per metre of sheath): viscous drag on the sliding tendon
      besides Coulomb friction, so the hysteresis widens with rate;
    - ``relaxation_fraction`` r in [0, 1) and ``relaxation_time`` tau (s): each tendon element a
      standard linear solid (r EA relaxes with time constant tau), so a held input creeps;
    - ``friction2`` and ``stiffness2``: sheath 2's friction and tendon 2's EA when the pair is
      unequal (None: the same as tendon 1).

    Any of these (or a damped load) makes a step depend on dt, so ``t`` is then required.

    Parameters
    ----------
    route : Route
        Route of the sheath (of tendon 1 for a pair).
    friction : float, default 0.1
        Friction coefficient mu (of sheath 1 for a pair).
    stiffness : float, default 2.4e4
        Tendon axial stiffness EA (N) (of tendon 1 for a pair).
    pretension : float, default 10.0
        Pretension T0 of both tendons (N).
    proximal_radius : float, default 5e-3
        Proximal (motor) pulley radius r_p (m).
    distal_radius : float, default 5e-3
        Distal pulley radius r_d (m).
    elements : int, default 100
        Elements N per sheath, >= 2.
    load : ConstantTorque, TorsionalSpring or SpringDamper, optional
        The load on the distal pulley (None: none).
    motor : Motor, optional
        A drive between the command and the proximal pulley.
    route2 : Route, optional
        Route of sheath 2 (default: route).
    sensor : Sensor, optional
        Reads the output (``SimulationResult.measured``).
    max_increment : float, optional
        Largest input sub-increment of the solver (m); None: the plant chooses.
    fast_path : bool, default True
        Use the solver's exact shortcuts (lazy update while the slip map stays valid).
    distal_inertia : float, optional
        J_d (kg m^2) of a dynamic distal joint (None: off).
    distal_damping : float, optional
        c_d (N m s/rad) of the distal joint (None: off).
    sheath_viscosity : float, optional
        Viscous drag on the sliding tendon (N s/m per metre of sheath; None: off).
    relaxation_fraction : float, optional
        Share r in [0, 1) of EA that relaxes (standard linear solid; None: off).
    relaxation_time : float, optional
        Time constant tau of the relaxation (s).
    friction2 : float, optional
        Friction of sheath 2 (None: as sheath 1).
    stiffness2 : float, optional
        EA of tendon 2 (N) (None: as tendon 1).

    Raises
    ------
    ValueError
        A route, load, motor or sensor of the wrong kind, elements not an integer >= 2, or a
        value the C++ core rejects (the message names it).
    TypeError
        An effect that is not a number.
    """

    _rows = 2

    def __init__(
        self,
        route: Route,
        friction: float = 0.1,
        stiffness: float = 2.4e4,
        pretension: float = 10.0,
        proximal_radius: float = 5e-3,
        distal_radius: float = 5e-3,
        elements: int = 100,
        load: ConstantTorque | TorsionalSpring | SpringDamper | None = None,
        motor: Motor | None = None,
        route2: Route | None = None,
        sensor: Sensor | None = None,
        max_increment: float | None = None,
        fast_path: bool = True,
        distal_inertia: float | None = None,
        distal_damping: float | None = None,
        sheath_viscosity: float | None = None,
        relaxation_fraction: float | None = None,
        relaxation_time: float | None = None,
        friction2: float | None = None,
        stiffness2: float | None = None,
    ):
        cls = type(self).__name__
        effects = {k: v for k, v in locals().items() if k in _PAIR_EFFECTS}
        self.route = _check_route(route, "route", cls)
        self.route2 = _check_route(route if route2 is None else route2, "route2", cls)
        if load is not None and not isinstance(
            load, ConstantTorque | TorsionalSpring | SpringDamper
        ):
            raise TypeError(
                f"{cls}: load must be None, ConstantTorque, TorsionalSpring or SpringDamper "
                f"(got {type(load).__name__})"
            )
        self.load = load
        p = core.PullPullParams()
        _set_numbers(p, cls, _PAIR_NUMBERS, locals())
        p.elements = _check_elements(elements, cls)
        if load is not None:
            p.load_torque, p.load_stiffness, p.load_damping = load.rotary()
        p.options = _options(cls, max_increment, fast_path)
        _set_effects(p, cls, _PAIR_EFFECTS, effects)
        with core_errors_as(cls):
            self._engine = self._make_engine(p)
        self._setup_io(motor, sensor)

    def _make_engine(self, p):
        return core.PullPullPlant(p, self.route._core, self.route2._core)

    @property
    def effects(self) -> dict:
        """The effects beyond the quasi-static pair (C++ names; 0 or -1 = off / as tendon 1)."""
        return _effects_of(self._engine.params, _PAIR_EFFECTS)

    # parameters
    @property
    def pretension(self) -> float:
        """Pretension T0 of both tendons (N)."""
        return self._engine.params.pretension

    @property
    def proximal_radius(self) -> float:
        """Proximal (motor) pulley radius r_p (m)."""
        return self._engine.params.proximal_radius

    @property
    def distal_radius(self) -> float:
        """Distal pulley radius r_d (m); for a continuum plant, the tendon offset r_t."""
        return self._engine.params.distal_radius

    @property
    def kinematic_gain(self) -> float:
        """The uncompensated command per unit of desired output: distal_radius /
        proximal_radius (the motor angle for a distal angle)."""
        return self.distal_radius / self.proximal_radius

    def _lengths(self) -> tuple[float, ...]:
        return (self.route.length, self.route2.length)

    def set_route(self, route: Route, route2: Route | None = None) -> None:
        """Bend the sheaths (route2 defaults to route); lengths must not change. Nodes whose
        stored tension gradient exceeds the new friction capacity start to slip at the next
        step (spec A.5).

        Parameters
        ----------
        route : Route
            New route of sheath 1.
        route2 : Route, optional
            New route of sheath 2 (default: route).

        Raises
        ------
        ValueError
            Not a Route, or a length that changed.
        """
        cls = type(self).__name__
        r1 = _check_route(route, "route", cls)
        r2 = r1 if route2 is None else _check_route(route2, "route2", cls)
        self._engine.set_route(r1._core, r2._core)
        self.route, self.route2 = r1, r2

    def _angles_for(self, r):
        cls = type(self).__name__
        if isinstance(r, tuple | list):
            if len(r) != 2:
                raise ValueError(f"{cls}: routes(t) must give a Route or a (route1, route2) pair")
            r1, r2 = (_check_route(x, "routes(t)", cls) for x in r)
        else:
            r1 = r2 = _check_route(r, "routes(t)", cls)
        return self._engine.node_angles(r1._core, r2._core)

    # closed forms ------------------------------------------------------------------
    def load_force(self) -> float:
        """Distal load at rest at the tendon level F_L = tau_L / r_d (N) (springs: preload).

        Returns
        -------
        float
            F_L (N); 0 without a load.
        """
        if self.load is None:
            return 0.0
        return self.load.rotary()[0] / self.distal_radius

    def steady_offsets(self, load_force: float | None = None) -> tuple[float, float]:
        """Full-slip x_in - x_out (m) on the forward and backward branch: (A5)/(A6) with g, G.

        Parameters
        ----------
        load_force : float, optional
            Distal load F_L (N); default :meth:`load_force`.

        Returns
        -------
        forward, backward : float
            The two offsets (m at the tendon level).
        """
        F = self.load_force() if load_force is None else float(load_force)
        return physics.pull_pull_offsets(
            self.route, self.stiffness, self.pretension, self.friction, F, self.route2
        )

    def dead_zone_width(self, load_force: float | None = None) -> float:
        """Input dead-zone width (m at the tendon level; divide by r_p for rad): A7 / g, G.

        Parameters
        ----------
        load_force : float, optional
            Distal load F_L (N); default :meth:`load_force`.

        Returns
        -------
        float
            The width (m).
        """
        f, b = self.steady_offsets(load_force)
        return f - b

    def backlash_half_width(self) -> float:
        """e_b (m): half the dead zone without load (uniform routes: T0 L tanh(a/2)/EA).

        Returns
        -------
        float
            e_b (m).
        """
        return 0.5 * self.dead_zone_width(0.0)

    def closed_form(self) -> dict:
        """Closed-form figures for the current routes and load (m at the tendon level).

        Returns
        -------
        dict
            offset_forward, offset_backward, dead_zone, backlash_half_width, load_offset (m)
            and no_slack_limit (N).
        """
        f, b = self.steady_offsets()
        return {
            "offset_forward": f,
            "offset_backward": b,
            "dead_zone": f - b,
            "backlash_half_width": self.backlash_half_width(),
            "load_offset": 0.5 * (f + b),
            "no_slack_limit": float(
                physics.no_slack_limit(
                    self.pretension,
                    self.friction,
                    max(self.route.curve_angle, self.route2.curve_angle),
                )
            ),
        }


class ContinuumPlant(PullPullPlant):
    """A pull-pull pair bending a continuum segment (Lau et al. 2015, spec C.5); output theta_b.

    Li and Rahn: the tendon force that holds a bending angle theta_b is F = kappa EI/r_t with
    kappa = theta_b / l, and the stroke is x_out = r_t theta_b, so the segment is a spring
    k = EI/(r_t^2 l) on the stroke. Defaults: EI = 4e-4 N m^2, r_t = 2 mm, l = 30 mm and a 1 m
    sheath on a 0.6 m-diameter semicircle (Theta = pi).

    Parameters
    ----------
    route : Route, optional
        Route of sheath 1 (default: 1 m, Theta = pi, uniform).
    friction : float, default 0.1
        Friction coefficient mu (of sheath 1 for a pair).
    stiffness : float, default 2.4e4
        Tendon axial stiffness EA (N) (of tendon 1 for a pair).
    pretension : float, default 10.0
        Pretension T0 of both tendons (N).
    proximal_radius : float, default 5e-3
        Proximal (motor) pulley radius r_p (m).
    bending_stiffness : float, default 4e-4
        Backbone bending stiffness EI (N m^2).
    tendon_offset : float, default 2e-3
        Distance r_t of the tendons from the backbone (m).
    backbone_length : float, default 0.03
        Length l of the segment (m).
    elements : int, default 100
        Elements N per sheath, >= 2.
    motor : Motor, optional
        A drive between the command and the proximal pulley.
    route2 : Route, optional
        Route of sheath 2 (default: route).
    sensor : Sensor, optional
        Reads the output (``SimulationResult.measured``).
    max_increment : float, optional
        Largest input sub-increment of the solver (m); None: the plant chooses.
    fast_path : bool, default True
        Use the solver's exact shortcuts (lazy update while the slip map stays valid).
    distal_inertia : float, optional
        J_d (kg m^2) of a dynamic distal joint (None: off).
    distal_damping : float, optional
        c_d (N m s/rad) of the distal joint (None: off).
    sheath_viscosity : float, optional
        Viscous drag on the sliding tendon (N s/m per metre of sheath; None: off).
    relaxation_fraction : float, optional
        Share r in [0, 1) of EA that relaxes (standard linear solid; None: off).
    relaxation_time : float, optional
        Time constant tau of the relaxation (s).
    friction2 : float, optional
        Friction of sheath 2 (None: as sheath 1).
    stiffness2 : float, optional
        EA of tendon 2 (N) (None: as tendon 1).

    Raises
    ------
    ValueError
        A route, load, motor or sensor of the wrong kind, elements not an integer >= 2, or a
        value the C++ core rejects (the message names it).
    TypeError
        An effect that is not a number.
    """

    def __init__(
        self,
        route: Route | None = None,
        friction: float = 0.1,
        stiffness: float = 2.4e4,
        pretension: float = 10.0,
        proximal_radius: float = 5e-3,
        bending_stiffness: float = 4e-4,
        tendon_offset: float = 2e-3,
        backbone_length: float = 0.03,
        elements: int = 100,
        motor: Motor | None = None,
        route2: Route | None = None,
        sensor: Sensor | None = None,
        max_increment: float | None = None,
        fast_path: bool = True,
        distal_inertia: float | None = None,
        distal_damping: float | None = None,
        sheath_viscosity: float | None = None,
        relaxation_fraction: float | None = None,
        relaxation_time: float | None = None,
        friction2: float | None = None,
        stiffness2: float | None = None,
    ):
        cls = type(self).__name__
        effects = {k: v for k, v in locals().items() if k in _PAIR_EFFECTS}
        route = Route.uniform(1.0, math.pi) if route is None else route
        self.route = _check_route(route, "route", cls)
        self.route2 = _check_route(route if route2 is None else route2, "route2", cls)
        c = core.ContinuumParams()
        _set_numbers(c, cls, _CONTINUUM_NUMBERS, locals())
        c.elements = _check_elements(elements, cls)
        c.options = _options(cls, max_increment, fast_path)
        _set_effects(c, cls, _PAIR_EFFECTS, effects)
        with core_errors_as(cls):
            self._engine = core.ContinuumPlant(c, self.route._core, self.route2._core)
        self.load = TorsionalSpring(c.bending_stiffness / c.backbone_length)
        self._setup_io(motor, sensor)

    @property
    def bending_stiffness(self) -> float:
        """Backbone bending stiffness EI (N m^2)."""
        return self._engine.continuum_params.bending_stiffness

    @property
    def tendon_offset(self) -> float:
        """Distance r_t of the tendons from the backbone (m)."""
        return self._engine.continuum_params.tendon_offset

    @property
    def backbone_length(self) -> float:
        """Length l of the continuum segment (m)."""
        return self._engine.continuum_params.backbone_length

    @property
    def spring_stiffness(self) -> float:
        """k = EI/(r_t^2 l) (N/m): the segment as a spring on the tendon stroke."""
        return self.bending_stiffness / (self.tendon_offset**2 * self.backbone_length)

    def tendon_force(self) -> float:
        """Li and Rahn tendon force F = kappa EI / r_t (N) at the current bending angle.

        Returns
        -------
        float
            F (N).
        """
        return self._engine.tendon_force()


__all__ = [
    "ContinuumPlant",
    "PullPullPlant",
    "SimulationResult",
    "SingleTendonPlant",
    "SlackWarning",
]
