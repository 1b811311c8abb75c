"""`ts.bench.run`: close the loop controller -> motor -> plant -> sensor at a fixed rate."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import numpy as np

from .._util.arrays import as_timed_signal
from .._util.pyobject import bound_base
from ..plant.physics import route_shape as shape_of
from ..plant.sensor import Sensor
from ..protocols import (
    STEP_SIGNALS,
    SteppedPlant,
    StreamingCompensator,
    bench_declarations,
    missing_members,
    step_signals,
)
from ..simulation_result import FIELDS, SimulationResult
from ..status import status_counts
from . import _bound as core
from .limit_cycle import limit_cycle
from .metrics import dominant_period, tracking_metrics
from .plant_loop import BenchPlant

if TYPE_CHECKING:
    from .._util.typing import ArrayLike
    from ..compensate import AdaptiveController
    from ..compensate.base import Feedforward
    from ..compensate.learned_feedforward import LearnedFeedforward
    from .shape_sensing import ShapeSensing

# what bench.run closes the loop with: any StreamingCompensator (None: uncompensated); the
# shipped ones are named too, their step(y_d, dt) being narrower than the protocol's
# step(*signals) to a type checker
Controller: TypeAlias = (
    "StreamingCompensator | Feedforward | LearnedFeedforward | AdaptiveController | None"
)


class Result(SimulationResult):
    """A bench run: a :class:`~tendonsheath.SimulationResult` of the plant's output (an
    array), with every signal of the loop and its metrics (computed after ``warmup`` seconds).

    ``input`` and ``reference`` are the desired output; ``status`` holds each cycle's
    :class:`~tendonsheath.Status` flags of controller, motor, plant and sensor (uint8);
    ``metrics["status"]`` counts the cycles with each flag (the whole run, warm-up included).

    Parameters
    ----------
    controller : str
        The controller's name ("none" uncompensated).
    t : numpy.ndarray of float
        Sample times (s).
    reference : numpy.ndarray of float
        The desired output (rad; m for a SingleTendonPlant).
    output : numpy.ndarray of float
        The plant's output (rad; m for a SingleTendonPlant).
    measured : numpy.ndarray of float
        The sensor's reading of the output (NaN during dropouts).
    command : numpy.ndarray of float
        The controller's command (rad, or N m for a torque controller).
    q_motor : numpy.ndarray of float
        The motor shaft angle its encoder reads (rad), as a plant's
        :class:`~tendonsheath.SimulationResult` names it.
    slack : numpy.ndarray of bool
        Per cycle: a tendon was slack.
    fallback : numpy.ndarray of bool
        Per cycle: the controller ran its dropout fallback.
    warmup : float
        Seconds at the start left out of the metrics.
    metrics : dict, optional
        The tracking metrics (:func:`tracking_metrics`), slack_samples, status counts and
        the limit-cycle test (:func:`~tendonsheath.bench.limit_cycle.limit_cycle`).
    status : numpy.ndarray of uint8, optional
        Each cycle's Status flags.
    """

    _fields = (*FIELDS, "controller", "fallback", "warmup")

    def __new__(
        cls,
        controller: str,
        t: np.ndarray,
        reference: np.ndarray,
        output: np.ndarray,
        measured: np.ndarray,
        command: np.ndarray,
        q_motor: np.ndarray,
        slack: np.ndarray,
        fallback: np.ndarray,
        warmup: float,
        metrics: dict[str, Any] | None = None,
        status: np.ndarray | None = None,
    ) -> Result:
        result = super().__new__(
            cls,
            output,
            t=t,
            input=reference,
            reference=reference,
            metrics={} if metrics is None else metrics,  # floats, and "status": counts
            status=status,
            controller=controller,
            measured=measured,
            command=command,
            q_motor=q_motor,
            slack=slack,
            fallback=fallback,
            warmup=warmup,
        )
        return cast(Result, result)

    @property
    def error(self) -> np.ndarray:
        """The tracking error output - reference (rad)."""
        return self.output - self.reference

    @property
    def scored(self) -> np.ndarray:
        """Mask of the samples the metrics cover (after the warm-up)."""
        return _scored(self.t, self.warmup)


def _scored(t: np.ndarray, warmup: float) -> np.ndarray:
    return t >= t[0] + warmup


def controller_name(controller) -> str:
    if controller is None:
        return "none"
    return type(controller).__name__


def _sensor_engine(noise, plant: BenchPlant):
    if noise is None:
        noise = plant.sensor
    if noise is None:
        return None
    if isinstance(noise, int | float):
        noise = Sensor(noise_std=float(noise))
    if not isinstance(noise, Sensor):
        raise ValueError("noise must be None, a standard deviation (rad) or a tendonsheath.Sensor")
    return noise.engine()


def _dropout_mask(dropout, t):
    if dropout is None:
        return None
    mask = np.zeros(t.size, dtype=np.uint8)
    for start, stop in dropout:
        if not stop > start:
            raise ValueError(f"dropout windows need start < stop (got {start}, {stop})")
        mask[(t >= start) & (t < stop)] = 1
    return mask


def run(
    plant: SteppedPlant,
    controller: Controller,
    t: ArrayLike,
    reference: ArrayLike,
    routes: Callable | None = None,
    noise: Sensor | float | None = None,
    dropout: Sequence[tuple[float, float]] | None = None,
    warmup: float | None = None,
    shape_sensing: ShapeSensing | None = None,
) -> Result:
    """Track ``reference`` (the plant's output: a distal angle, rad; a SingleTendonPlant's
    distal displacement, m) at times ``t`` with ``controller`` on ``plant``.

    ``plant``: any object with ``reset()`` and ``step(command, dt)``
    (:class:`~tendonsheath.protocols.SteppedPlant`; no ``params`` or ``simulate`` needed), all
    closed in one C++ loop: a shipped plant (PullPullPlant, ContinuumPlant, SingleTendonPlant)
    or a compiled one (bound with ``tendonsheath_bind/plant.hpp``) at C++ speed, any other
    stepped from Python (``step(command, dt)`` once per cycle, after ``reset()``). What the
    loop reads of a plant beyond the protocol, each optional (its ``motor`` and ``sensor``,
    ``kinematic_gain`` or ``distal_radius``/``proximal_radius``, ``set_route``, ``slack()``,
    ``status()`` ...), is listed in :mod:`tendonsheath.bench.plant_loop`; a member the run
    needs and the plant lacks is named in the error.

    ``controller``: None (uncompensated: the kinematic command ``plant.kinematic_gain * y_d``,
    r_d/r_p * y_d for a pull-pull pair, y_d for a single tendon), an
    :class:`InverseFeedforward` (of any model; one that follows the route, of a
    CurveAngleModel or AngleDependent model, is given the route's shape like the
    CurveAngleFeedforward), :class:`CurveAngleFeedforward` (it is given the route's shape
    every time the route changes, as from shape sensing), :class:`ContinuumFeedforward` or
    :class:`AdaptiveController` (needs a torque motor on the plant), or any
    :class:`~tendonsheath.protocols.StreamingCompensator`. The plant's own motor
    (``plant.motor``) sits between controller and plant. ``routes``: None or a callable
    t -> Route. ``noise``: a Sensor, a noise standard deviation (rad), or None (then
    ``plant.sensor``). ``dropout``: [(start, stop), ...] seconds when the sensor reads NaN.
    ``warmup`` (s): excluded from the metrics; default one period of the reference.
    ``shape_sensing`` (a :class:`~tendonsheath.bench.shape_sensing.ShapeSensing`): the
    CurveAngleFeedforward (or a route-following InverseFeedforward) is told the sensed curve
    angle (noise, delay, reading rate) instead of the route's exact shape.

    Parameters
    ----------
    plant : SteppedPlant
        The plant (with its motor and sensor): a shipped one, a compiled one or one written in
        Python (see above).
    controller : compensator or None
        See above.
    t : array_like of float, shape (n,)
        Sample times (s), at least 2.
    reference : array_like of float, shape (n,)
        The desired output (rad; m for a SingleTendonPlant).
    routes : callable, optional
        t -> Route (or a (route1, route2) pair).
    noise : Sensor or float, optional
        The distal sensor, or its noise standard deviation (rad).
    dropout : list of (float, float), optional
        Windows (s) when the sensor reads NaN.
    warmup : float, optional
        Seconds excluded from the metrics, in [0, the run's length).
    shape_sensing : ShapeSensing, optional
        Tell a CurveAngleFeedforward the sensed curve angle instead of the exact shape.

    Returns
    -------
    Result
        Every signal and the metrics.

    Raises
    ------
    ValueError
        A plant without reset() or step(), or without a member the run needs (named), a
        controller it does not know, bad samples or arguments, or an AdaptiveController
        without a torque motor.
    TypeError
        A compensator without reset and step, a plant's motor or sensor of the wrong kind, or a
        Python plant's step that returned no number.
    RuntimeError
        The closed loop produced a non-finite output.
    """
    bench_plant = BenchPlant(plant)
    ts, ys = _record(t, reference)
    warmup = _checked_warmup(warmup, ts)
    loop = _Loop(bench_plant, ts, ys, routes, noise, dropout)
    outputs = _run_controller(loop, controller, shape_sensing)
    if warmup is None:
        warmup = min(dominant_period(ts, ys), 0.5 * float(ts[-1] - ts[0]))
    return _result(controller, ts, ys, outputs, warmup)


def _record(t, reference):
    ts, ys = as_timed_signal(t, reference, "reference", "bench.run")
    if ts.size < 2:
        raise ValueError(f"bench.run needs at least 2 samples (got {ts.size})")
    return ts, ys


def _checked_warmup(warmup, ts) -> float | None:
    if warmup is None:
        return None
    warmup = float(warmup)
    span = float(ts[-1] - ts[0])
    if not 0.0 <= warmup < span:
        raise ValueError(
            f"bench.run: warmup must be in [0, {span:g}) s, the run's length (got {warmup})"
        )
    return warmup


class _Loop:
    """What every closed loop shares: the plant, its motor and sensor, the record, the route
    schedule and the dropout mask, as the C++ bench functions take them."""

    def __init__(self, plant: BenchPlant, ts, ys, routes, noise, dropout):
        self.plant, self.ts, self.ys, self.routes = plant, ts, ys, routes
        self.idx = self.angles = None
        if routes is not None:
            if not callable(routes):
                raise ValueError("routes must be None or a callable t -> Route")
            self.idx, self.angles = plant.schedule(ts, routes)
        self.motor = plant.motor.engine() if plant.motor is not None else None
        self.sensor = _sensor_engine(noise, plant)
        self.encoder = plant.encoder.engine() if plant.encoder is not None else None
        self.mask = _dropout_mask(dropout, ts)
        # a core.EncoderLoop or core.TipLoop around the controller's command
        self.outer_loop: Any = None
        self.learned: Any = None  # a core.LearnedCorrection added to the command (in the loop)

    @property
    def scheduled(self) -> bool:
        """Whether the outer loop is a TipLoop with a gain schedule (it needs the shapes)."""
        return isinstance(self.outer_loop, core.TipLoop) and bool(
            self.outer_loop.params.schedule_angles
        )

    def call(self, controller, shapes=None, idx=None, angles=None, **how):
        """The C++ closed loop (``bench_run``) with ``controller`` (None, a shipped compensator,
        a compiled one's capsule or a Python one; ``how``: its ``gain`` or step ``inputs``);
        the schedule may be replaced, and ``shapes`` go to the controller at each change."""
        return core.bench_run(
            self.plant.engine,
            self.motor,
            self.sensor,
            controller,
            self.ts,
            self.ys,
            self.idx if idx is None else idx,
            self.angles if angles is None else angles,
            shapes,
            self.mask,
            self.outer_loop,
            self.learned,
            encoder=self.encoder,
            **how,
        )

    def call_with_shapes(self, controller, *, friction, shape_sensing, **how):
        """``controller`` given the route's shapes (or the sensed ones) from the start and at
        every change, for a TipLoop's gain schedule around a feedforward that does not follow
        the route."""
        idx, angles, shapes = _route_shapes(self, friction, shape_sensing)
        return self.call(controller, shapes=shapes, idx=idx, angles=angles, **how)


def _run_controller(loop: _Loop, controller, shape_sensing):
    """Run the loop on the fastest path the controller declares
    (:class:`~tendonsheath.protocols.BenchCompensator`): its stages (an EncoderLoop's or
    TipLoop's loop around its feedforward, a LearnedFeedforward's table added to its
    feedforward) run in C++ around the inner compensator's path, and that compensator is
    stepped in C++ where it gives an engine, else from Python (a TipLoop with a gain schedule
    is given the route's shapes on every path)."""
    if controller is None:
        return loop.call(None, gain=loop.plant.kinematic_gain)
    _check_compensator(controller)
    _check_motor_kind(loop.plant, controller)
    declared = bench_declarations(controller)
    while declared.stage is not None:  # each stage's slot in the C++ loop is taken once
        stage, inner = declared.stage
        slot = "learned" if isinstance(stage, core.LearnedCorrection) else "outer_loop"
        if getattr(loop, slot) is not None:
            raise ValueError(
                f"bench.run: {type(controller).__name__} declares a second {slot} stage "
                "(one feedback loop and one learned table at most)"
            )
        setattr(loop, slot, stage)
        controller = inner
        _check_compensator(controller)
        declared = bench_declarations(controller)
    how: dict[str, Any] = {}
    engine = declared.engine
    if not declared.compiled:  # a user's C++ compensator (tendonsheath_bind/compensator.hpp)
        if engine is not None and bound_base(type(engine)) is None:
            engine = None  # a Python class without a C++ core: stepped from Python
        if isinstance(engine, core.CurveAngleFeedforward) or (
            isinstance(engine, core.ModelInverse) and core.ModelInverse.follows_route(engine)
        ):
            return _run_curve_angle(loop, controller, engine, shape_sensing)
        if engine is None:  # a Python one: its step called with these signals
            engine = controller
            how["inputs"] = [STEP_SIGNALS.index(s) for s in step_signals(controller)]
    if loop.scheduled:
        friction = _friction(controller)
        return loop.call_with_shapes(engine, friction=friction, shape_sensing=shape_sensing, **how)
    return loop.call(engine, **how)


def _friction(controller) -> float:
    """The friction a controller computes route shapes with (0 when it does not follow the
    route: a TipLoop's schedule uses only the curve angle)."""
    from ..compensate.around import follows_route

    if not follows_route(controller):
        return 0.0
    return float(getattr(controller, "friction", None) or 0.0)


def _check_compensator(controller) -> None:
    missing = missing_members(controller, StreamingCompensator)
    if missing:
        raise TypeError(
            f"bench.run: the controller {type(controller).__name__} has no "
            f"{' and no '.join(missing)}: a compensator needs reset() and "
            "step(<step_inputs>, dt) (see tendonsheath.protocols.StreamingCompensator)"
        )


def _check_motor_kind(plant: BenchPlant, controller) -> None:
    if getattr(controller, "control_output", "x") != "torque":
        return
    if plant.motor is None or plant.motor.kind != "torque":
        raise ValueError(
            f"the {type(controller).__name__} commands torque: give the plant a Motor.torque(...)"
        )


def _run_curve_angle(loop: _Loop, controller, engine, shape_sensing):
    """The controller is told the route's shape from the start and at every change (a route
    schedule always starts at sample 0), or the sensed shape with ``shape_sensing``."""
    idx, angles, shapes = _route_shapes(loop, controller.friction, shape_sensing)
    return loop.call(engine, shapes=shapes, idx=idx, angles=angles)


def _route_shapes(loop: _Loop, friction: float, shape_sensing):
    """(schedule index, node angles, (g, G, Theta) rows): the route's shape from the start and
    at every change, at ``friction``, or the sensed shape with ``shape_sensing``."""
    plant, ts, routes, idx = loop.plant, loop.ts, loop.routes, loop.idx
    angles = loop.angles
    if idx is None:
        idx = np.array([0], dtype=np.uint64)
        angles = np.ascontiguousarray(plant.angles_for(plant.route)[None, :])
        route_at = [plant.route]
    else:
        route_at = [_first(routes(float(ts[int(k)]))) for k in idx]
    shape_rows = [shape_of(r, friction) for r in route_at]
    shapes = np.ascontiguousarray([[s.g, s.G, s.curve_angle] for s in shape_rows])
    if shape_sensing is not None:
        idx, angles, shapes = _sensed(plant, ts, routes, shape_sensing, friction, idx)
    return idx, angles, shapes


def _result(controller, ts, ys, outputs, warmup: float) -> Result:
    output, measured, command, motor_pos, slack, fallback, status = outputs
    slack = slack.astype(bool)
    keep = _scored(ts, float(warmup))
    metrics: dict[str, Any] = {
        **tracking_metrics(ys[keep], output[keep]),
        "slack_samples": int(slack.sum()),
        "status": status_counts(status),
        "limit_cycle": limit_cycle(ts[keep], ys[keep], output[keep]),
    }
    if not math.isfinite(metrics["mse"]):
        raise RuntimeError("bench.run: the closed loop produced a non-finite output")
    return Result(
        controller=controller_name(controller),
        t=ts,
        reference=ys,
        output=output,
        measured=measured,
        command=command,
        q_motor=motor_pos,
        slack=slack,
        fallback=fallback.astype(bool),
        warmup=float(warmup),
        metrics=metrics,
        status=status,
    )


def _sensed(plant, ts, routes, shape_sensing, friction, idx):
    """Merge the plant's route changes with the shape sensor's readings: at every index
    the plant gets its true route and the controller the last sensed shape (the curve angle's
    uniform route, or the sensed curvature profile)."""
    from .shape_sensing import sensed_route_schedule

    if routes is None:
        route = plant.route

        def routes(_t):
            return route

    r_idx, _, sensed_rows = sensed_route_schedule(shape_sensing, ts, routes, friction)
    merged = np.union1d(np.asarray(idx, dtype=np.int64), r_idx.astype(np.int64))
    angle_rows, shape_rows = [], []
    for k in merged:
        angle_rows.append(plant.angles_for(routes(float(ts[k]))))
        j = int(np.searchsorted(r_idx, k, side="right")) - 1
        shape_rows.append(sensed_rows[max(j, 0)])
    return (
        merged.astype(np.uint64),
        np.ascontiguousarray(np.vstack(angle_rows)),
        np.ascontiguousarray(np.vstack(shape_rows)),
    )


def _first(route):
    return route[0] if isinstance(route, tuple | list) else route


__all__ = ["Controller", "Result", "controller_name", "run"]
