"""The adaptive controller's bandwidth and derivative filter from the identified loop dynamics.

:meth:`AdaptiveController.from_model` scales every gain from a closed-loop bandwidth and the
corner of the filtered derivative of the tip reading. Both must stay clear of what the
calibration runs identified (:class:`~tendonsheath.identify.loop_dynamics.LoopDynamics`):

* the derivative filter's corner at the lowest distal resonance f_res (a higher corner passes
  the resonance into s, and the robust term's high gain on s limit-cycles near it);
* the bandwidth at most f_res / 10, and at most what the sensor's delay tau allows: its phase
  lag at the bandwidth, 360 f tau degrees, at most 15 deg (f <= 1 / (24 tau)).

With a ``trial`` (a run on the calibration shapes) the bandwidth is chosen among f_res / 20,
f_res / 10 and f_res / 6 (each capped by the delay); a design whose bandwidth would fall below
0.2 Hz is refused. A shape whose logs showed no resonance within the excitation's band stands
for f_res with the band's upper edge (``LoopDynamics.design_limit_hz``: the highest frequency
the logs speak of), and the design says so.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..identify.loop_dynamics import LoopDynamics

#: The most phase (deg) the sensor's delay may take at the loop's bandwidth.
DELAY_PHASE_DEG = 15.0
#: The least bandwidth (Hz) worth a tip loop.
MIN_BANDWIDTH_HZ = 0.2
#: The bandwidths tried with a trial, as fractions of the lowest resonance.
TRIAL_FRACTIONS = (1.0 / 20.0, 1.0 / 10.0, 1.0 / 6.0)


@dataclass(frozen=True)
class AdaptiveDesign:
    """What an adaptive controller was designed from, and the choice made.

    Parameters
    ----------
    bandwidth_hz : float
        The closed-loop bandwidth chosen (Hz).
    derivative_cutoff_hz : float
        The derivative filter's corner (Hz).
    resonance_hz : float
        The lowest identified distal resonance (Hz), or the band's upper edge of a shape with
        none identified within its excitation's band if that is lower (see
        ``resonance_identified``).
    delay : float
        The longest identified sensor delay (s).
    dynamics : tuple of LoopDynamics
        The identified loop of each calibration shape.
    trials : dict of float to float, optional
        bandwidth (Hz) -> trial mean squared error, when chosen by trials.
    """

    bandwidth_hz: float
    derivative_cutoff_hz: float
    resonance_hz: float
    delay: float
    dynamics: tuple[LoopDynamics, ...]
    trials: dict[float, float] = field(default_factory=dict)

    @property
    def resonances_hz(self) -> tuple[float, ...]:
        """The identified distal resonance of each calibration shape (Hz; inf where none was
        identified within the excitation's band)."""
        return tuple(d.resonance_hz for d in self.dynamics)

    @property
    def resonance_identified(self) -> bool:
        """Whether ``resonance_hz`` is an identified resonance (not a band's upper edge)."""
        return any(d.resonance_identified and d.resonance_hz == self.resonance_hz
                   for d in self.dynamics)  # fmt: skip

    @property
    def delays(self) -> tuple[float, ...]:
        """The identified tip-sensor delay of each calibration shape (s)."""
        return tuple(d.delay for d in self.dynamics)

    def as_dict(self) -> dict[str, Any]:
        """The design as a JSON-ready dict.

        Returns
        -------
        dict
            Bandwidth, filter corner, resonances, delays, trials and dynamics.
        """
        return {
            "bandwidth_hz": self.bandwidth_hz,
            "derivative_cutoff_hz": self.derivative_cutoff_hz,
            "resonance_hz": self.resonance_hz,
            "resonance_identified": self.resonance_identified,
            "delay_s": self.delay,
            "resonances_hz": [f if math.isfinite(f) else None for f in self.resonances_hz],
            "delays_s": list(self.delays),
            "trials": [{"bandwidth_hz": f, "mse": v} for f, v in self.trials.items()],
            "dynamics": [d.as_dict() for d in self.dynamics],
        }

    def summary(self) -> str:
        """One line: the choice and what it came from.

        Returns
        -------
        str
            Bandwidth, derivative corner, resonance and delay.
        """
        source = (
            f"resonance {self.resonance_hz:.3g} Hz"
            if self.resonance_identified
            else f"{self.resonance_hz:.3g} Hz, the excitation band's upper edge (no resonance "
            "identified within the band)"
        )
        return (
            f"adaptive: bandwidth {self.bandwidth_hz:.3g} Hz, derivative filter "
            f"{self.derivative_cutoff_hz:.3g} Hz; designed from {source}, delay "
            f"{1e3 * self.delay:.3g} ms"
        )


def adaptive_limits(dynamics: Sequence[LoopDynamics]) -> tuple[float, float, float]:
    """(lowest resonance Hz, longest delay s, the largest bandwidth Hz they allow).

    Raises
    ------
    ValueError
        No dynamics, or a bandwidth below ``MIN_BANDWIDTH_HZ``.
    """
    if not dynamics:
        raise ValueError("AdaptiveController.from_calibration: no loop dynamics")
    f_res = min(d.design_limit_hz for d in dynamics)
    delay = max(d.delay for d in dynamics)
    cap = f_res / 10.0
    if delay > 0:
        cap = min(cap, DELAY_PHASE_DEG / (360.0 * delay))
    if not cap >= MIN_BANDWIDTH_HZ:
        raise ValueError(
            f"AdaptiveController.from_calibration: the identified loop (resonance {f_res:.3g} "
            f"Hz, delay {1e3 * delay:.3g} ms) leaves a bandwidth of {cap:.3g} Hz, below "
            f"{MIN_BANDWIDTH_HZ:g} Hz: no adaptive design is stable on this drive"
        )
    return f_res, delay, cap


def choose_bandwidth(
    dynamics: Sequence[LoopDynamics],
    build: Callable[[float, float], Any],
    trial: Callable[[Any], float] | None,
) -> Any:
    """The controller built (``build(bandwidth_hz, derivative_cutoff_hz)``) at the bandwidth the
    identified loop allows, or the best of the trial bandwidths; ``design`` set."""
    f_res, delay, cap = adaptive_limits(dynamics)
    if trial is None:
        ctrl = build(cap, f_res)
        ctrl.design = AdaptiveDesign(cap, f_res, f_res, delay, tuple(dynamics))
        return ctrl
    scores: dict[float, float] = {}
    best, best_score = None, math.inf
    for bw in sorted({min(f_res * k, DELAY_PHASE_DEG / (360.0 * delay)) if delay > 0 else
                      f_res * k for k in TRIAL_FRACTIONS}):  # fmt: skip
        ctrl = build(bw, f_res)
        score = float(trial(ctrl))
        scores[bw] = score
        if score < best_score:
            best, best_score, chosen = ctrl, score, bw
    if best is None:
        raise ValueError("AdaptiveController.from_calibration: every trial run failed")
    best.design = AdaptiveDesign(chosen, f_res, f_res, delay, tuple(dynamics), scores)
    return best


__all__ = ["AdaptiveDesign", "adaptive_limits", "choose_bandwidth"]
