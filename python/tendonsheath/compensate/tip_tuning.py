"""Gains of a tip-feedback loop from the loop dynamics identified on the calibration shapes.

A :class:`~tendonsheath.compensate.TipLoop` closes a PI(D) on the tip sensor around the
position servo. Its plant, on calibration shape i, is the identified path from the servo
command to the tip reading (:class:`~tendonsheath.identify.loop_dynamics.LoopDynamics`: the
servo, the distal resonance, the sensor's delay), seen one cycle late by the loop (the reading
at cycle k shows the command of cycle k - 1): P_i(z) = z^-1 G_i(z). The design is MIGO (as the
encoder loop's, :mod:`~tendonsheath.compensate.tuning`) made robust over the shapes: the
largest integral gain over kp (and kd) such that the loop is stable and its peak sensitivity
|1 / (1 + C P_i)| stays below ``max_sensitivity`` on *every* calibration shape. The resonance
and the delay enter through P_i, so a longer latency or a lighter resonance gives smaller gains;
a path no PI(D) can close within the bound is refused. A shape whose logs showed no resonance
within the excitation's band (``LoopDynamics.resonance_identified`` False) is designed with the
band's upper edge as the highest frequency known: it stands for the resonance in the choice of
the gains (derivative range, rejection band), and the loop gain must be below one from that edge
up (a crossover where the logs say nothing is refused); the summary says so.

The design states the peak sensitivity it reached beside its target (on a grid ten times
denser than the search's); a design above its target (a refinement by trials may go up to
``REFINED_SENSITIVITY`` times it) warns with a
:class:`~tendonsheath.compensate.tuning.MarginNotMetWarning`.

The gain schedule keeps the loop gain of each shape at the design's: the factor at shape i's
curve angle is the median static gain of the shapes over shape i's.

What the linear design cannot see is the drive's dead band: a feedforward that overshoots it
at a reversal leaves the loop a correction that must cross the band back. ``dead_band_scale``
(< 1) makes the feedforward under-compensate the band, so that the loop only ever pushes on in
the direction of motion; :func:`choose_by_trials` picks it, with the sensitivity bound, from
trial runs on the calibration shapes (a robustness test over them, never a test route).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.units import CURVE_ANGLE, warn_if_unit_slip
from .tuning import (
    MS_TOLERANCE,
    RobustLoop,
    _evaluate,
    _warn_if_not_met,
    controller_polynomials,
    implied_margins,
    largest_ki,
    loop_margins,
    reached_peak,
)

if TYPE_CHECKING:
    from ..identify.loop_dynamics import LoopDynamics

#: The robustness test of a refined design: every gain times this (3.5 dB) ...
ROBUSTNESS_GAIN = 1.5
#: ... may raise the trial error at most this many times (a loop near its limit cycle does more)
ROBUSTNESS_RATIO = 2.0
#: A refined loop keeps the identified linear loops' peak sensitivity within this many times
#: the design's bound (2: a gain margin of at least 2.5 dB at a bound of 2)
REFINED_SENSITIVITY = 2.0
_STEP = 1.5  # a refinement move multiplies or divides one gain by this


@dataclass(frozen=True)
class TipLoopDesign:
    """Gains of a tip loop, the margins they keep on each calibration shape, and the dynamics
    they were designed from.

    Parameters
    ----------
    kp, ki, kd : float
        The gains (rad of command per rad of tip; 1/s; s).
    derivative_cutoff_hz : float
        Corner of the derivative filter (Hz).
    max_sensitivity : float
        The design's bound on the peak sensitivity (every shape).
    sensitivity_peaks : tuple of float
        The achieved peak of |1 / (1 + L)| on each shape.
    gain_margins_db, phase_margins_deg, crossovers_hz : tuple of float
        Each shape's gain margin (dB), phase margin (deg) and gain crossover (Hz).
    schedule : tuple of (float, float)
        (curve angle, gain factor) points; empty for one shape.
    dynamics : tuple of LoopDynamics
        The identified loop of each calibration shape.
    dt : float
        The control cycle (s).
    dead_band_scale : float, default 1.0
        The factor on the feedforward model's dead band (< 1: under-compensated).
    trials : dict, optional
        The trial runs' scores ((max_sensitivity, dead_band_scale) -> mean squared error) when
        the design was chosen by :func:`choose_by_trials`.
    refined : tuple of dict, optional
        The moves :func:`refine_by_trials` made from the linear design (gains and score each);
        the margins above are then those of the refined gains, which may exceed the bound.
    robustness_ratio : float, optional
        After a refinement: the trial error with every gain x ``robustness_gain`` over the
        trial error with the gains (the robustness test over the calibration shapes).
    """

    kp: float
    ki: float
    kd: float
    derivative_cutoff_hz: float
    max_sensitivity: float
    sensitivity_peaks: tuple[float, ...]
    gain_margins_db: tuple[float, ...]
    phase_margins_deg: tuple[float, ...]
    crossovers_hz: tuple[float, ...]
    schedule: tuple[tuple[float, float], ...]
    dynamics: tuple[LoopDynamics, ...]
    dt: float
    dead_band_scale: float = 1.0
    trials: dict[tuple[float, float], float] = field(default_factory=dict)
    refined: tuple[dict[str, float], ...] = ()
    robustness_ratio: float | None = None

    def gains(self) -> dict[str, float]:
        """The gains as TipLoop keywords.

        Returns
        -------
        dict of str to float
            kp, ki, kd and derivative_cutoff_hz.
        """
        return {
            "kp": self.kp,
            "ki": self.ki,
            "kd": self.kd,
            "derivative_cutoff_hz": self.derivative_cutoff_hz,
        }

    @property
    def resonances_hz(self) -> tuple[float, ...]:
        """The identified distal resonance of each calibration shape (Hz; inf where none was
        identified within the excitation's band)."""
        return tuple(d.resonance_hz for d in self.dynamics)

    @property
    def limits_hz(self) -> tuple[float, ...]:
        """The frequency each shape was designed with as its limit (Hz): its resonance, or
        the band's upper edge where no resonance was identified within the band."""
        return tuple(d.design_limit_hz for d in self.dynamics)

    @property
    def sensitivity_reached(self) -> float:
        """The worst shape's peak sensitivity."""
        return max(self.sensitivity_peaks)

    @property
    def target_met(self) -> bool:
        """Whether every shape's peak sensitivity is within the bound (see ``MS_TOLERANCE``)."""
        return self.sensitivity_reached <= MS_TOLERANCE * self.max_sensitivity

    @property
    def delays(self) -> tuple[float, ...]:
        """The identified tip-sensor delay of each calibration shape (s)."""
        return tuple(d.delay for d in self.dynamics)

    def as_dict(self) -> dict[str, Any]:
        """The design as a JSON-ready dict, the identified dynamics it came from included.

        Returns
        -------
        dict
            Gains, margins, schedule, dead-band scale, trials and dynamics.
        """
        skip = ("dynamics", "trials", "schedule", "refined")
        out: dict[str, Any] = {
            k: getattr(self, k) for k in self.__dataclass_fields__ if k not in skip
        }
        out = {k: list(v) if isinstance(v, tuple) else v for k, v in out.items()}
        out["schedule"] = [list(p) for p in self.schedule]
        gm, pm = implied_margins(self.max_sensitivity)
        out["target"] = {"sensitivity_peak": self.max_sensitivity, "gain_margin_db": gm,
                         "phase_margin_deg": pm}  # fmt: skip
        out["reached"] = {"sensitivity_peak": self.sensitivity_reached,
                          "gain_margin_db": min(self.gain_margins_db),
                          "phase_margin_deg": min(self.phase_margins_deg)}  # fmt: skip
        out["target_met"] = self.target_met
        out["resonances_hz"] = [f if math.isfinite(f) else None for f in self.resonances_hz]
        out["limits_hz"] = list(self.limits_hz)
        out["delays_s"] = list(self.delays)
        out["trials"] = [
            {"max_sensitivity": ms, "dead_band_scale": k, "mse": v}
            for (ms, k), v in self.trials.items()
        ]
        out["refined"] = [dict(m) for m in self.refined]
        out["dynamics"] = [d.as_dict() for d in self.dynamics]
        return out

    def summary(self) -> str:
        """One line: the gains, the worst margins over the shapes and what they came from.

        Returns
        -------
        str
            Gains, dead-band scale, peak sensitivity, margins, resonance and delay.
        """
        if all(d.resonance_identified for d in self.dynamics):
            res = "resonance " + ", ".join(f"{f:.3g}" for f in self.resonances_hz) + " Hz"
        else:
            res = "resonance " + ", ".join(d.resonance_text() for d in self.dynamics)
        delays = ", ".join(f"{1e3 * d:.3g}" for d in self.delays)
        met = "met" if self.target_met else "NOT met"
        refined = (
            f"; refined by {len(self.refined)} trial moves on the calibration shapes (gains x "
            f"{ROBUSTNESS_GAIN:g}: trial error x {self.robustness_ratio:.3g})"
            if self.refined and self.robustness_ratio is not None
            else ""
        )
        return (
            f"tip loop: kp {self.kp:.3g}, ki {self.ki:.4g} 1/s, kd {self.kd:.3g} s, dead band x "
            f"{self.dead_band_scale:g}; Ms {self.sensitivity_reached:.3g} reached (target <= "
            f"{self.max_sensitivity:g}: {met}), gain margin {min(self.gain_margins_db):.3g} dB, "
            f"phase margin {min(self.phase_margins_deg):.3g} deg (worst shape); designed from "
            f"{res}, delay {delays} ms{refined}"
        )


def loop_plant(dynamics: LoopDynamics, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """The path command -> tip reading as the loop sees it (one cycle late), in z^-1."""
    num, den = dynamics.discrete(dt)
    return np.concatenate([[0.0], num]), np.asarray(den, dtype=float)


class _RobustLoop(RobustLoop):
    """The shared robust loop on the tip loop's grid, with the band criterion; ``limits``: per
    plant, the frequency (Hz) from which the loop gain must stay below one (None: no such
    limit), for shapes with no resonance identified within their excitation's band."""

    def __init__(self, plants: list[tuple[np.ndarray, np.ndarray]], dt: float, cutoff: float,
                 limits: Sequence[float | None] | None = None):  # fmt: skip
        super().__init__(plants, dt, cutoff, points=600)
        self.limited = []
        for plant, limit in zip(plants, limits or [None] * len(plants), strict=True):
            if limit is not None and limit < 0.5 / dt:
                f = np.geomspace(limit, 0.5 / dt, 200)
                zinv = np.exp(-2j * math.pi * f * dt)
                self.limited.append((zinv, _evaluate(*plant, zinv)))

    def acceptable(self, kp: float, ki: float, kd: float, ms: float) -> bool:
        """Stable within ms on every plant, the loop gain below one above each limit."""
        if not super().acceptable(kp, ki, kd, ms):
            return False
        c_num, c_den = controller_polynomials(kp, ki, kd, self.cutoff, self.dt)
        return all(float(np.max(np.abs(_evaluate(c_num, c_den, zinv) * P))) < 1.0
                   for zinv, P in self.limited)  # fmt: skip

    def band_sensitivity(self, kp: float, ki: float, kd: float, f_hz: np.ndarray) -> float:
        """The mean |S| over the frequencies ``f_hz``, worst shape: the rejection of what the
        feedforward leaves (reversals, route changes), not only of the slowest drift."""
        zinv = np.exp(-2j * math.pi * f_hz * self.dt)
        c_num, c_den = controller_polynomials(kp, ki, kd, self.cutoff, self.dt)
        C = _evaluate(c_num, c_den, zinv)
        return max(
            float(np.mean(np.abs(1.0 / (1.0 + C * _evaluate(num, den, zinv)))))
            for num, den in self.plants
        )


def _band_limits(dynamics: Sequence[LoopDynamics]) -> list[float | None]:
    """Per shape: the band's upper edge where no resonance was identified within it, else
    None."""
    return [None if d.resonance_identified else d.design_limit_hz for d in dynamics]


def _largest_ki(loop: RobustLoop, kp: float, kd: float, ms: float) -> float:
    return largest_ki(loop, kp, kd, ms, tolerance=1.01)


_margins = loop_margins


def _schedule(dynamics: Sequence[LoopDynamics], angles: Sequence[float] | None):
    """(angle, factor) points keeping each shape's static loop gain at the median's."""
    if angles is None or len(dynamics) < 2:
        return ()
    gains = np.array([d.servo.gain * d.gain for d in dynamics])
    if not np.all(gains > 0):
        return ()
    ref = float(np.median(gains))
    points = sorted(zip((float(a) for a in angles), (ref / g for g in gains), strict=True))
    merged: list[tuple[float, float]] = []
    for a, s in points:  # one point per angle (the mean of shapes sensed at the same angle)
        if merged and abs(a - merged[-1][0]) < 1e-9:
            merged[-1] = (a, 0.5 * (merged[-1][1] + s))
        else:
            merged.append((a, float(s)))
    return tuple(merged[:8]) if len(merged) >= 2 else ()


def tune_tip_loop(
    dynamics: LoopDynamics | Sequence[LoopDynamics],
    curve_angles: Sequence[float] | None = None,
    dt: float = 1e-3,
    max_sensitivity: float = 1.7,
    derivative: bool = True,
    kp: float | None = None,
) -> TipLoopDesign:
    """PI(D) gains of a tip loop, robust over the calibration shapes (see the module).

    Parameters
    ----------
    dynamics : LoopDynamics or sequence of LoopDynamics
        The loop identified on each calibration shape (``Calibration.loop_dynamics``).
    curve_angles : sequence of float, optional
        The sensed curve angle of each shape (rad): a gain schedule over them.
    dt : float, default 1e-3
        The control cycle (s), > 0.
    max_sensitivity : float, default 1.7
        The bound on the peak sensitivity on every shape, > 1.
    derivative : bool, default True
        Also search a derivative gain (filtered at a tenth of the sample rate); PI otherwise.
    kp : float, optional
        Hold the proportional gain at this value (>= 0) and search the others: a linear design
        favours integral action, which a dead band punishes (the integral winds up while the
        tip sticks); trials on the calibration shapes can weigh the two.

    Returns
    -------
    TipLoopDesign
        The gains, the margins on each shape and the schedule.

    Raises
    ------
    ValueError
        No dynamics, a bad dt or bound, curve angles that do not match the shapes, or no gains
        that keep every shape's loop stable within ``max_sensitivity`` (the latency or the
        resonance leaves no room: the design is refused).

    Warns
    -----
    MarginNotMetWarning
        The peak sensitivity reached is above ``max_sensitivity`` (the design states both).
    """
    dyns = [dynamics] if not isinstance(dynamics, Sequence) else list(dynamics)
    dt, ms = float(dt), float(max_sensitivity)
    if not dyns:
        raise ValueError("tune_tip_loop: no loop dynamics (calibrate with dynamics=True)")
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"tune_tip_loop: dt must be > 0 (got {dt})")
    if not (math.isfinite(ms) and ms > 1.0):
        raise ValueError(f"tune_tip_loop: max_sensitivity must be > 1 (got {ms})")
    if curve_angles is not None and len(curve_angles) != len(dyns):
        raise ValueError(
            f"tune_tip_loop: {len(curve_angles)} curve angles for {len(dyns)} loop dynamics"
        )
    for i, angle in enumerate(curve_angles or ()):
        warn_if_unit_slip(angle, "tune_tip_loop", f"curve_angles[{i}]", CURVE_ANGLE)
    cutoff = 0.1 / dt
    plants = [loop_plant(d, dt) for d in dyns]
    loop = _RobustLoop(plants, dt, cutoff, _band_limits(dyns))
    g = float(np.median([abs(d.servo.gain * d.gain) or 1.0 for d in dyns]))
    w_n = 2.0 * math.pi * min(min(d.design_limit_hz, d.servo.frequency) for d in dyns)
    kds = np.linspace(0.0, 2.0 / (g * w_n), 5) if derivative else np.zeros(1)
    band = np.geomspace(0.1, 0.25 * min(d.design_limit_hz for d in dyns), 40)
    best, best_cost = (0.0, 0.0, 0.0), math.inf
    if kp is not None and not (math.isfinite(float(kp)) and float(kp) >= 0):
        raise ValueError(f"tune_tip_loop: kp must be >= 0 (got {kp})")
    kps = np.linspace(0.0, 1.5 / g, 16) if kp is None else np.array([float(kp)])
    for kd in kds:
        for p in kps:
            ki = _largest_ki(loop, float(p), float(kd), ms)
            cost = loop.band_sensitivity(float(p), ki, float(kd), band) if ki > 0 else math.inf
            if cost < best_cost:
                best, best_cost = (float(p), ki, float(kd)), cost
    if not best[1] > 0:
        worst = max(dyns, key=lambda d: d.delay)
        raise ValueError(
            f"tune_tip_loop: no PI{'D' if derivative else ''} gains keep the tip loop stable "
            f"with a peak sensitivity <= {ms:g} on every calibration shape at dt = {dt:g} s "
            f"(identified: {worst.summary()}); the tip loop cannot be closed on this drive"
        )
    peaks = reached_peak(loop, best)
    margins = [_margins(p, dt, best, cutoff) for p in plants]
    _warn_if_not_met("tune_tip_loop", max(peaks), ms)
    return TipLoopDesign(
        kp=best[0],
        ki=best[1],
        kd=best[2],
        derivative_cutoff_hz=cutoff,
        max_sensitivity=ms,
        sensitivity_peaks=tuple(peaks),
        gain_margins_db=tuple(m[0] for m in margins),
        phase_margins_deg=tuple(m[1] for m in margins),
        crossovers_hz=tuple(m[2] for m in margins),
        schedule=_schedule(dyns, curve_angles),
        dynamics=tuple(dyns),
        dt=dt,
    )


def with_dead_band_scaled(model: Any, scale: float) -> Any:
    """``model`` with its dead band (B_r, B_l) multiplied by ``scale``: a Backlash or
    BoucWenBacklash, or an AngleDependent one (every coefficient of its B laws).

    Parameters
    ----------
    model : HysteresisModel
        The identified model.
    scale : float
        The factor, in (0, 1]; 1 returns ``model`` itself.

    Returns
    -------
    HysteresisModel
        A new model (or ``model`` for a scale of 1).

    Raises
    ------
    ValueError
        A scale out of (0, 1].
    TypeError
        A model without a dead band B_r, B_l.
    """
    scale = float(scale)
    if not (math.isfinite(scale) and 0.0 < scale <= 1.0):
        raise ValueError(f"dead_band_scale must be in (0, 1] (got {scale})")
    if scale == 1.0:
        return model
    data = model.to_dict()
    params = data["params"]
    holder = params.get("coefficients", params)
    if "B_r" not in holder or "B_l" not in holder:
        raise TypeError(
            f"dead_band_scale needs a model with a dead band B_r, B_l (got {type(model).__name__})"
        )
    for key in ("B_r", "B_l"):
        value = holder[key]
        holder[key] = [scale * v for v in value] if isinstance(value, list) else scale * value
    return type(model).from_dict(data)


def choose_by_trials(
    build: Callable[[float, float], Any],
    trial: Callable[[Any], float],
    max_sensitivities: Sequence[float],
    dead_band_scales: Sequence[float],
) -> Any:
    """The candidate with the least trial score over every (bound, dead-band scale) pair.

    ``build(max_sensitivity, dead_band_scale)`` makes a candidate (it may raise ValueError: a
    bound no gains meet is skipped); ``trial(candidate)`` runs it on the calibration shapes
    and returns its mean squared tip error (inf for a run that saturated or diverged). The
    chosen candidate's ``design`` records every score.

    Parameters
    ----------
    build : callable
        (max_sensitivity, dead_band_scale) -> candidate with a ``design`` attribute.
    trial : callable
        candidate -> score (lower is better).
    max_sensitivities : sequence of float
        The sensitivity bounds tried.
    dead_band_scales : sequence of float
        The dead-band scales tried.

    Returns
    -------
    Any
        The best candidate.

    Raises
    ------
    ValueError
        No bound gave a design, or every trial failed.
    """
    scores: dict[tuple[float, float], float] = {}
    best, best_score, reasons = None, math.inf, []
    for ms in max_sensitivities:
        for k in dead_band_scales:
            try:
                candidate = build(float(ms), float(k))
            except ValueError as err:
                reasons.append(str(err))
                break  # the bound has no design, whatever the scale
            score = float(trial(candidate))
            scores[(float(ms), float(k))] = score
            if score < best_score:
                best, best_score = candidate, score
    if best is None:
        why = reasons[0] if reasons else "every trial run failed"
        raise ValueError(f"no tip-loop design passed its trials: {why}")
    from dataclasses import replace

    best.design = replace(best.design, trials=scores)
    return best


def refine_by_trials(
    loop: Any,
    trial: Callable[[Any], float],
    max_moves: int = 4,
) -> Any:
    """Refine a tip loop's gains by trial runs on the calibration shapes, under a robustness
    test.

    The linear design cannot see the dead band, which lowers the loop's effective gain while
    the tip sticks; it leaves proportional and derivative gain on the table. Each move
    multiplies or divides kp, ki or kd by 1.5 (kp from 0 to 0.1 first); the move that lowers the
    trial error most (by at least 2 %) is kept if the loop passes the robustness test: with
    every gain x ``ROBUSTNESS_GAIN`` (3.5 dB) the trial error rises at most
    ``ROBUSTNESS_RATIO`` times and nothing saturates (a loop near a limit cycle fails). A move
    must also keep the identified linear loops stable with a peak sensitivity within
    ``REFINED_SENSITIVITY`` times the design's bound (the dead band lowers the loop gain while
    the tip sticks, never while it slips). The final margins are recomputed and stated beside
    the target; refined gains above the design's bound warn (MarginNotMetWarning).

    Parameters
    ----------
    loop : TipLoop
        The start, with its ``design`` (:func:`tune_tip_loop`).
    trial : callable
        candidate -> mean squared tip error on the calibration shapes (inf: failed).
    max_moves : int, default 4
        The most moves kept.

    Returns
    -------
    TipLoop
        The refined loop (``loop`` itself when no move passed), ``design`` updated.
    """
    from dataclasses import replace

    design = loop.design
    build = _rebuilder(loop)
    gains = {"kp": design.kp, "ki": design.ki, "kd": design.kd}
    plants = [loop_plant(d, design.dt) for d in design.dynamics]
    rl = _RobustLoop(plants, design.dt, design.derivative_cutoff_hz,
                     _band_limits(design.dynamics))  # fmt: skip
    ceiling = REFINED_SENSITIVITY * design.max_sensitivity
    score = float(trial(loop))
    moves: list[dict[str, float]] = []
    ratio = None
    for _ in range(max_moves):
        tried = []
        for key in ("kp", "ki", "kd"):
            for factor in (_STEP, 1.0 / _STEP):
                g = dict(gains)
                g[key] = g[key] * factor if g[key] > 0 else (0.1 if factor > 1 else 0.0)
                if g == gains or not rl.acceptable(g["kp"], g["ki"], g["kd"], ceiling):
                    continue
                tried.append((float(trial(build(g))), g))
        accepted = False
        for s, g in sorted(tried, key=lambda item: item[0]):
            if not s < 0.98 * score:
                break
            robust = float(trial(build({k: ROBUSTNESS_GAIN * v for k, v in g.items()})))
            if math.isfinite(robust) and robust <= ROBUSTNESS_RATIO * s:
                gains, score, ratio, accepted = g, s, robust / s, True
                moves.append({**g, "mse": s})
                break
        if not accepted:
            break
    if not moves:
        return loop
    triple = (gains["kp"], gains["ki"], gains["kd"])
    margins = [_margins(p, design.dt, triple, design.derivative_cutoff_hz) for p in plants]
    peaks = reached_peak(rl, triple)
    _warn_if_not_met("refine_by_trials", max(peaks), design.max_sensitivity)
    new = replace(
        design,
        **gains,
        sensitivity_peaks=tuple(peaks),
        gain_margins_db=tuple(m[0] for m in margins),
        phase_margins_deg=tuple(m[1] for m in margins),
        crossovers_hz=tuple(m[2] for m in margins),
        refined=tuple(moves),
        robustness_ratio=ratio,
    )
    out = build(gains)
    out.design = new
    return out


def _rebuilder(loop: Any) -> Callable[[dict[str, float]], Any]:
    """gains -> a TipLoop like ``loop`` (same feedforward settings, schedule and limits)."""
    settings = dict(loop._settings)
    feedforward = loop.feedforward

    def build(gains: dict[str, float]) -> Any:
        kwargs = {**settings, **gains}
        return type(loop)(feedforward, **kwargs)

    return build


__all__ = [
    "TipLoopDesign",
    "choose_by_trials",
    "refine_by_trials",
    "loop_plant",
    "tune_tip_loop",
    "with_dead_band_scaled",
]
