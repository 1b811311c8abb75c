"""A tip-feedback loop around any feedforward: PI(D) on the measured tip angle, its gains
scheduled over the route's curve angle."""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import TYPE_CHECKING, Any

from .._util.args import core_errors_as, number
from .._util.arrays import checked_dt
from .._util.param_table import TABLE, number_rows, table_constructor
from .._util.pyobject import bound_attribute
from .._util.units import CURVE_ANGLE, warn_if_unit_slip, warn_unit_slips
from ..protocols import step_signals
from . import _bound as core
from ._kinds import require_dynamics, require_feedforward, require_model
from .around import AroundFeedforward, follows_route
from .limits import CommandLimits, LimitsLike, as_limits

if TYPE_CHECKING:
    from ..plant.route import Route

_GAINS = number_rows(core.TipLoopParams)  # kp, ki, kd, derivative_cutoff_hz, max_correction
MAX_SCHEDULE = 8  # TipLoopParams::kMaxSchedule

Schedule = tuple[tuple[float, float], ...]


def _schedule(who: str, schedule: Any) -> Schedule:
    """``schedule`` (None, (angle, gain) pairs or a dict {angle: gain}) as a tuple of pairs;
    the C++ core checks the values (angles increasing, gains > 0)."""
    if schedule is None:
        return ()
    if isinstance(schedule, Mapping):
        items = sorted(
            ((number(who, "schedule angle", a), number(who, "schedule gain", g)))
            for a, g in schedule.items()
        )
        pairs = tuple(items)
    else:
        if isinstance(schedule, str | bytes):
            raise TypeError(f"{who}: schedule must be (curve_angle, gain) pairs (got {schedule!r})")
        try:
            rows = list(schedule)
        except TypeError:
            raise TypeError(
                f"{who}: schedule must be None, (curve_angle, gain) pairs or a dict "
                f"{{curve_angle: gain}} (got {type(schedule).__name__})"
            ) from None
        out = []
        for i, row in enumerate(rows):
            if isinstance(row, str | bytes) or not hasattr(row, "__len__") or len(row) != 2:
                raise TypeError(
                    f"{who}: schedule entry {i} must be a (curve_angle, gain) pair (got {row!r})"
                )
            out.append(
                (number(who, "schedule angle", row[0]), number(who, "schedule gain", row[1]))
            )
        pairs = tuple(out)
    if len(pairs) > MAX_SCHEDULE:
        raise ValueError(
            f"{who}: the schedule holds at most {MAX_SCHEDULE} points (got {len(pairs)})"
        )
    return pairs


@table_constructor(core.TipLoopParams)
class TipLoop(AroundFeedforward, core.TipLoop):  # type: ignore[misc]
    """A feedforward's command corrected by a PI(D) loop on the measured tip angle.

    A feedforward computes the motor command x_ff its model says gives the desired output
    y_d; whatever the model misses shows at the tip. This compensator reads the tip (an EM
    tracker, a distal encoder) and, with e = y_d(previous cycle) - y,

        u = x_ff + clamp(s kp e + I + s kd de/dt, +-max_correction),   I += s ki e dt

    shaped to ``limits``. The integral is held while the command is cut in the direction the
    error pushes (anti-windup); a NaN tip reading (a dropout) falls back toward the
    feedforward: the P and D terms are zeroed and the integral held (status ``fallback``).
    ``s`` is the gain schedule: the piecewise-linear interpolation of the schedule's gains at
    the curve angle now (clamped at its ends; 1 with no schedule), which :meth:`set_route`,
    :meth:`set_curve_angle` or, in ``bench.run``, the route's (or sensed) shape sets. The
    sign convention: a larger motor command gives a larger tip angle.

    Parameters
    ----------
    feedforward : compensator
        Any feedforward with ``reset()``, ``step(y_d, dt)`` and ``status()`` (a shipped
        InverseFeedforward, CurveAngleFeedforward or ContinuumFeedforward, or your own).
    schedule : sequence of (float, float), dict or None, optional
        Up to 8 (curve_angle, gain) points: curve angles (rad) strictly increasing and
        finite, gains > 0. A dict {curve_angle: gain} is taken in order of its angles.
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the servo command and its rate (after the correction).

    Raises
    ------
    TypeError
        A feedforward without reset/step(y_d, dt), or a setting of the wrong type.
    ValueError
        A gain, schedule point or limit out of range (the message names it).
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    limits: CommandLimits
    design: Any

    control_inputs = ("y_d", "y")
    control_output = "x"
    step_inputs = ("y_d", "y")
    _saved_settings = ("feedforward", *_GAINS, "schedule", "limits")

    def __init__(
        self,
        feedforward: Any,
        kp: float = TABLE,
        ki: float = TABLE,
        kd: float = TABLE,
        derivative_cutoff_hz: float = TABLE,
        max_correction: float = TABLE,
        schedule: Any = None,
        limits: LimitsLike = None,
    ):
        who = "TipLoop"
        require_feedforward(who, feedforward)
        if step_signals(feedforward) != ("y_d",):
            raise TypeError(
                f"{who}: feedforward must be a feedforward compensator with reset() and "
                f"step(y_d, dt) (got {type(feedforward).__name__})"
            )
        values = locals()
        p = core.TipLoopParams()
        for key in _GAINS:
            setattr(p, key, number(who, key, values[key]))
        pairs = _schedule(who, schedule)
        self.limits = as_limits(limits)
        p.limits = self.limits.to_core()
        with core_errors_as(who):
            p.set_schedule([a for a, _ in pairs], [g for _, g in pairs])
            core.TipLoop.__init__(self, p)
        warn_unit_slips(who, p)
        for i, (angle, _) in enumerate(pairs):
            warn_if_unit_slip(angle, who, f"schedule[{i}] curve angle", CURVE_ANGLE)
        self.feedforward = feedforward
        self.design = None
        self._settings = {
            **{k: getattr(p, k) for k in _GAINS},
            "schedule": pairs,
            "limits": self.limits,
        }

    @classmethod
    def from_design(cls, feedforward: Any, design: Any, limits: LimitsLike = None) -> TipLoop:
        """The loop a design (a tuner's result) describes; the design is kept in ``design``.

        Parameters
        ----------
        feedforward : compensator
            The feedforward whose command the loop corrects.
        design : object
            Any object with a ``gains()`` method returning a dict of kp, ki, kd and
            derivative_cutoff_hz (max_correction too, optionally), and optionally a
            ``schedule`` attribute: a list of (curve_angle, gain) pairs.
        limits : CommandLimits, tuple, dict or None, optional
            Saturation of the servo command.

        Returns
        -------
        TipLoop
            The compensator, with ``design`` set.

        Raises
        ------
        TypeError
            The design has no ``gains()`` method, or it returns an unknown setting.
        """
        gains = getattr(design, "gains", None)
        if not callable(gains):
            raise TypeError(
                f"TipLoop.from_design: the design must have a gains() method "
                f"(got {type(design).__name__})"
            )
        loop = cls(
            feedforward, **dict(gains()), schedule=getattr(design, "schedule", None), limits=limits
        )
        loop.design = design
        return loop

    @classmethod
    def from_calibration(
        cls,
        model: Any,
        dynamics: Any,
        *,
        curve_angles: Sequence[float] | None = None,
        dt: float = 1e-3,
        max_sensitivity: float | Sequence[float] = 1.7,
        derivative: bool = True,
        dead_band_scale: float | Sequence[float] = 1.0,
        trial: Callable[[TipLoop], float] | None = None,
        refine: bool = False,
        feedforward_options: dict[str, Any] | None = None,
        limits: LimitsLike = None,
    ) -> TipLoop:
        """The inverse feedforward of ``model`` inside a tip loop whose gains come from the loop
        dynamics identified on the calibration shapes
        (:func:`~tendonsheath.compensate.tip_tuning.tune_tip_loop`: robust MIGO, the peak
        sensitivity bounded on every shape, a gain schedule over their curve angles).

        With several sensitivity bounds or dead-band scales, ``trial`` chooses among them
        (:func:`~tendonsheath.compensate.tip_tuning.choose_by_trials`): it runs a candidate on
        the calibration shapes (never a test route) and returns its mean squared tip error.

        Parameters
        ----------
        model : HysteresisModel
            The model the feedforward inverts (fitted from the command: the loop adds to it).
        dynamics : LoopDynamics or sequence of LoopDynamics
            The identified loop of each calibration shape (``Calibration.loop_dynamics``).
        curve_angles : sequence of float, optional
            The sensed curve angle of each shape (rad), for the gain schedule.
        dt : float, default 1e-3
            The control cycle (s).
        max_sensitivity : float or sequence of float, default 1.7
            The bound(s) on the peak sensitivity, > 1.
        derivative : bool, default True
            PID (True) or PI.
        dead_band_scale : float or sequence of float, default 1.0
            Factor(s) on the model's dead band, in (0, 1] (< 1: under-compensated, so the loop
            never has to cross the band back).
        trial : callable, optional
            candidate -> score; needed with more than one bound or scale, or ``refine``.
        refine : bool, default False
            Then refine the chosen gains by trials under a robustness test
            (:func:`~tendonsheath.compensate.tip_tuning.refine_by_trials`).
        feedforward_options : dict, optional
            Keywords of the InverseFeedforward (smoothing, limits, ...).
        limits : CommandLimits, tuple, dict or None, optional
            Saturation of the servo command.

        Returns
        -------
        TipLoop
            The compensator; ``design`` holds the gains, margins, the dynamics designed from
            (resonance and delay of each shape) and the trial scores.

        Raises
        ------
        ValueError
            No gains keep the identified loop stable within the bound (the design is refused),
            several candidates without a ``trial``, or a bad argument.
        """
        from dataclasses import replace

        from .inverse_feedforward import InverseFeedforward
        from .tip_tuning import (
            choose_by_trials,
            refine_by_trials,
            tune_tip_loop,
            with_dead_band_scaled,
        )

        who = "TipLoop.from_calibration"
        require_model(who, model)
        dynamics = require_dynamics(who, dynamics)
        bounds = _as_values(max_sensitivity)
        scales = _as_values(dead_band_scale)
        options = dict(feedforward_options or {})

        def build(ms: float, scale: float) -> TipLoop:
            design = tune_tip_loop(dynamics, curve_angles, dt, ms, derivative)
            ff = InverseFeedforward(with_dead_band_scaled(model, scale), **options)
            return cls.from_design(ff, replace(design, dead_band_scale=scale), limits=limits)

        if trial is None and (refine or len(bounds) > 1 or len(scales) > 1):
            raise ValueError(
                "TipLoop.from_calibration: several sensitivity bounds or dead-band scales, or "
                "refine, need a trial (a function running a candidate on the calibration shapes)"
            )
        if trial is None:
            return build(bounds[0], scales[0])
        chosen = choose_by_trials(build, trial, bounds, scales)
        return refine_by_trials(chosen, trial) if refine else chosen

    # -- streaming ------------------------------------------------------------------
    def reset(self) -> None:
        """Forget the feedforward's and the loop's state (the curve angle is kept)."""
        self.feedforward.reset()
        core.TipLoop.reset(self)

    def step(self, y_d: float, y: float, dt: float) -> float:
        """One control cycle: the servo command.

        Parameters
        ----------
        y_d : float
            Desired output (rad).
        y : float
            The tip reading now (rad); NaN when there is none this cycle.
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The servo command (rad).
        """
        dt = checked_dt(dt)
        y_d = float(y_d)
        x = float(self.feedforward.step(y_d, dt))
        return self.correct(x, y_d, float(y), dt)

    @property
    def correction(self) -> float:  # type: ignore[override]
        """The correction added to the feedforward's last command (rad)."""
        return core.TipLoop.correction(self)

    @property
    def gain_scale(self) -> float:  # type: ignore[override]
        """The gain schedule's factor at the curve angle now (1 with no schedule)."""
        return core.TipLoop.gain_scale(self)

    @property
    def schedule(self) -> Schedule:
        """The gain schedule: (curve_angle, gain) pairs (empty: none)."""
        return self._settings["schedule"]

    def _control_step(self, u, dt: float) -> float:
        return self.step(u[0], u[1], dt)

    # -- the route ------------------------------------------------------------------------
    @property
    def follows_route(self) -> bool:
        """Whether the loop wants the route: it has a gain schedule, or its feedforward
        follows the route's shape."""
        return bool(self.schedule) or self._feedforward_follows

    @property
    def _feedforward_follows(self) -> bool:
        return follows_route(self.feedforward)

    @property
    def friction(self) -> float:
        """The friction route shapes are computed with: the feedforward's when it follows the
        route, else 0 (the gain schedule uses only the curve angle)."""
        if self._feedforward_follows:
            return self.feedforward.friction or 0.0
        return 0.0

    def set_route(self, route: Route) -> None:
        """Tell the feedforward the route's shape (when it follows the route) and the gain
        schedule its curve angle.

        Parameters
        ----------
        route : Route
            The route now.
        """
        if self._feedforward_follows:
            self.feedforward.set_route(route)
        self._set_angle(route.curve_angle)

    def set_curve_angle(self, curve_angle: float) -> None:  # type: ignore[override]
        """Tell the feedforward the curve angle (when it follows the route) and the gain
        schedule.

        Parameters
        ----------
        curve_angle : float
            The total curve angle (rad), finite and >= 0.

        Raises
        ------
        ValueError
            A curve angle that is not finite or negative (the C++ core ignores one and says
            ``input_clamped``; the Python call says so instead).
        """
        angle = number("TipLoop.set_curve_angle", "curve_angle", curve_angle)
        self._check_angle(angle)
        if self._feedforward_follows:
            self.feedforward.set_curve_angle(angle)
        self._set_angle(angle)

    @staticmethod
    def _check_angle(angle: float) -> None:
        if not (math.isfinite(angle) and angle >= 0.0):
            raise ValueError(
                f"TipLoop.set_curve_angle: curve_angle must be finite and >= 0 (got {angle})"
            )

    def _set_angle(self, angle: float) -> None:
        angle = float(angle)
        self._check_angle(angle)
        core.TipLoop.set_curve_angle(self, angle)

    # -- the bench and persistence ------------------------------------------------------
    def bench_stage(self) -> tuple[Any, Any]:
        """The C++ loop and the feedforward it is around, for bench.run's C++ loop
        (:class:`~tendonsheath.protocols.BenchCompensator`).

        Returns
        -------
        (object, compensator)
            A copy of this loop's real-time core, and the feedforward.
        """
        loop = core.TipLoop(bound_attribute(self, "params"))
        loop.set_curve_angle(self.curve_angle())
        return loop, self.feedforward

    @classmethod
    def _from_saved(cls, values: dict):
        return cls(**values)

    def to_dict(self) -> dict:
        """The compensator as a dict, its feedforward saved whole and its schedule as pairs.

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` reads back.
        """
        out = super().to_dict()
        out["schedule"] = [[a, g] for a, g in self.schedule]
        return out

    def __repr__(self) -> str:
        gains = ", ".join(f"{k}={self._settings[k]:g}" for k in _GAINS[:3])  # kp, ki, kd
        sched = f", schedule={list(self.schedule)}" if self.schedule else ""
        return f"TipLoop({self.feedforward!r}, {gains}{sched})"


def _as_values(value: float | Sequence[float]) -> list[float]:
    values = list(value) if isinstance(value, Sequence) else [value]
    if not values:
        raise ValueError("TipLoop.from_calibration: an empty list of candidates")
    return [float(v) for v in values]


__all__ = ["TipLoop"]
