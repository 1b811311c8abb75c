"""Gains of a motor-encoder loop from an identified servo, with their margins stated.

The loop of :class:`~tendonsheath.compensate.EncoderLoop` around an identified servo G(z)
(:class:`~tendonsheath.identify.servo.ServoFit`) has the loop gain L(z) = C(z) G(z), with the
discrete PI(D) of the C++ core,

    C(z) = kp + ki dt / (1 - z^-1) + kd a (1 - z^-1) / (dt (1 - (1 - a) z^-1)),

a = dt / (dt + 1 / (2 pi derivative_cutoff_hz)). The design is MIGO (Astrom, Panagopoulos &
Hagglund, "Design of PI controllers based on non-convex optimization", Automatica 34(5), 1998):
the largest integral gain ki (the best rejection of a slowly varying load: the tendons' pull on
the servo) over kp (and kd) such that the closed loop is stable and the peak of the sensitivity
|1 / (1 + L)| stays below ``max_sensitivity`` Ms. Ms bounds the margins: a gain margin of at
least Ms / (Ms - 1) and a phase margin of at least 2 asin(1 / (2 Ms)) (Ms = 1.7: 2.4, i.e. 7.7 dB,
and 34 deg); the achieved margins are computed from the loop's exact frequency response
(NumPy and SciPy only: python-control is not needed) and stated beside the target.

A servo with integral action of its own (a PID servo, ``ServoFit.integral_time`` > 0) is in the
loop the design closes (its identified third-order form), so the search and the margins are of
the whole loop, the encoder-loop integral on top of the servo's: a double integrator. Whether
that pays depends on the servo: around the demo's fast PID servo (69 Hz, T_i 13.5 ms) it costs
(shape-aware InverseFeedforward MSE ratio 0.00384 with the loop, 0.00313 without), around
lau2015's slow one (11 Hz, T_i 0.15 s) it is what tracks (0.54 % mean error with it, 2.8 %
without). The design says so in its ``note``; ``servo_integral_only=True`` leaves the loop out
(all gains 0) around such a servo.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ._kinds import require_servo

if TYPE_CHECKING:
    from ..identify.servo import ServoFit

_KI_MAX = 1e5  # 1/s: far beyond any servo a 1 kHz loop can close around
_KI_MIN = 1e-3  # 1/s: slower integral action is no loop at all
#: A design meets its bound Ms when its peak sensitivity, on a grid 10 times denser than the
#: search's, is at most this many times Ms: the search's grid may miss a hair of the peak
#: (well under 1 %), which moves the margins Ms implies by less than 0.1 dB and 0.5 deg.
MS_TOLERANCE = 1.01


class MarginNotMetWarning(UserWarning):
    """A tuned loop's peak sensitivity is above the bound it was asked to keep: the design
    states the margins it reached (``as_dict``, ``summary``)."""


def implied_margins(max_sensitivity: float) -> tuple[float, float]:
    """(gain margin dB, phase margin deg) a peak sensitivity Ms guarantees: Ms / (Ms - 1) and
    2 asin(1 / (2 Ms)).

    Parameters
    ----------
    max_sensitivity : float
        The bound Ms, > 1.

    Returns
    -------
    tuple of float
        The least gain margin (dB) and phase margin (deg) of a loop within Ms.
    """
    ms = float(max_sensitivity)
    return 20.0 * math.log10(ms / (ms - 1.0)), math.degrees(2.0 * math.asin(0.5 / ms))


@dataclass(frozen=True)
class EncoderLoopDesign:
    """Gains of an encoder loop and the margins of its identified loop.

    Parameters
    ----------
    kp : float
        Proportional gain.
    ki : float
        Integral gain (1/s).
    kd : float
        Derivative gain (s).
    derivative_cutoff_hz : float
        Corner of the derivative filter (Hz).
    max_sensitivity : float
        The design's bound on the peak sensitivity.
    sensitivity_peak : float
        The achieved peak of |1 / (1 + L)|.
    gain_margin_db : float
        Gain margin (dB; inf when the phase never crosses -180 deg).
    phase_margin_deg : float
        Phase margin (deg).
    crossover_hz : float
        Gain-crossover frequency (Hz).
    servo : ServoFit
        The identified servo the design is for.
    dt : float
        The control cycle (s).
    note : str, default ""
        What the design knows of the servo that shapes it: its integral action, and whether
        the loop was left out around it.
    """

    kp: float
    ki: float
    kd: float
    derivative_cutoff_hz: float
    max_sensitivity: float
    sensitivity_peak: float
    gain_margin_db: float
    phase_margin_deg: float
    crossover_hz: float
    servo: ServoFit
    dt: float
    note: str = ""

    @property
    def target_met(self) -> bool:
        """Whether the peak sensitivity reached is within the bound (see ``MS_TOLERANCE``)."""
        return self.sensitivity_peak <= MS_TOLERANCE * self.max_sensitivity

    def gains(self) -> dict[str, float]:
        """The gains as EncoderLoop keywords.

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

    def as_dict(self) -> dict[str, Any]:
        """The design as a JSON-ready dict (the servo it was designed from included).

        Returns
        -------
        dict
            Gains, margins (the target beside the reached), whether the target was met, and
            the servo.
        """
        out = {k: getattr(self, k) for k in self.__dataclass_fields__ if k != "servo"}
        gm, pm = implied_margins(self.max_sensitivity)
        out["target"] = {"sensitivity_peak": self.max_sensitivity, "gain_margin_db": gm,
                         "phase_margin_deg": pm}  # fmt: skip
        out["reached"] = {"sensitivity_peak": self.sensitivity_peak,
                          "gain_margin_db": self.gain_margin_db,
                          "phase_margin_deg": self.phase_margin_deg}  # fmt: skip
        out["target_met"] = self.target_met
        return {**out, "servo": self.servo.as_dict()}

    def summary(self) -> str:
        """One line: the gains and the margins.

        Returns
        -------
        str
            Gains, peak sensitivity, gain and phase margins, crossover.
        """
        met = "met" if self.target_met else "NOT met"
        return (
            f"encoder loop: kp {self.kp:.3g}, ki {self.ki:.4g} 1/s, kd {self.kd:.3g} s; "
            f"Ms {self.sensitivity_peak:.3g} reached (target <= {self.max_sensitivity:g}: "
            f"{met}), gain margin {self.gain_margin_db:.3g} dB, phase margin "
            f"{self.phase_margin_deg:.3g} deg, crossover {self.crossover_hz:.3g} Hz"
            + (f"; {self.note}" if self.note else "")
        )


def controller_polynomials(
    kp: float, ki: float, kd: float, derivative_cutoff_hz: float, dt: float
) -> tuple[np.ndarray, np.ndarray]:
    """(num, den) of C(z) in z^-1, the discrete PI(D) of the C++ EncoderLoop."""
    a = dt / (dt + 1.0 / (2.0 * math.pi * derivative_cutoff_hz))
    # kp + ki dt/(1 - z^-1) + kd a (1 - z^-1)/(dt (1 - b z^-1)), b = 1 - a, over (1-z^-1)(1-b z^-1)
    b = 1.0 - a
    one = np.array([1.0, -1.0])
    pole = np.array([1.0, -b])
    den = np.convolve(one, pole)
    num = _padded_sum(_padded_sum(kp * den, ki * dt * pole), (kd * a / dt) * np.convolve(one, one))
    return num, den


class RobustLoop:
    """L_i = C P_i on a frequency grid for every plant P_i (in z^-1), and the closed loops'
    stability: one plant for an encoder loop, one per calibration shape for a tip loop."""

    def __init__(
        self, plants: list[tuple[np.ndarray, np.ndarray]], dt: float, cutoff: float,
        points: int = 800,
    ):  # fmt: skip
        self.dt, self.cutoff, self.plants = dt, cutoff, plants
        w = np.geomspace(1e-2, math.pi / dt, points)
        self.zinv = np.exp(-1j * w * dt)
        self.P = [_evaluate(num, den, self.zinv) for num, den in plants]

    def peaks(self, kp: float, ki: float, kd: float) -> list[float]:
        """The peak sensitivity on each plant (inf where the closed loop is unstable)."""
        c_num, c_den = controller_polynomials(kp, ki, kd, self.cutoff, self.dt)
        C = _evaluate(c_num, c_den, self.zinv)
        out = []
        for (g_num, g_den), P in zip(self.plants, self.P, strict=True):
            char = _padded_sum(np.convolve(c_den, g_den), np.convolve(c_num, g_num))
            out.append(float(np.max(np.abs(1.0 / (1.0 + C * P)))) if _stable(char) else math.inf)
        return out

    def acceptable(self, kp: float, ki: float, kd: float, ms: float) -> bool:
        """Stable on every plant, with every peak sensitivity <= ms."""
        return max(self.peaks(kp, ki, kd)) <= ms


def loop_plant(servo: ServoFit, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """The servo as the loop sees it: the encoder read at cycle k shows the command of cycle
    k - 1 (the servo's q_k = G u_k, one cycle later), so G z^-1, in z^-1."""
    num, den = servo.discrete(dt)
    return np.concatenate([[0.0], num]), den


def _evaluate(num: np.ndarray, den: np.ndarray, zinv: np.ndarray) -> np.ndarray:
    """num(z^-1) / den(z^-1) at the points zinv (coefficients in rising powers of z^-1)."""
    return np.polyval(num[::-1], zinv) / np.polyval(den[::-1], zinv)


def _padded_sum(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    n = max(a.size, b.size)
    return np.pad(a, (0, n - a.size)) + np.pad(b, (0, n - b.size))


def _stable(char: np.ndarray) -> bool:
    """All closed-loop poles inside the unit circle: char(z^-1) = 0 in z^-1 means z = 1/root;
    as a polynomial in z (coefficients reversed) every root has |z| < 1."""
    coeffs = np.trim_zeros(char, "b")
    if coeffs.size <= 1:
        return True
    return bool(np.all(np.abs(np.roots(coeffs)) < 1.0 - 1e-12))


def largest_ki(
    loop: RobustLoop, kp: float, kd: float, ms: float, tolerance: float = 1.002
) -> float:
    """The largest ki with the loop stable and within ms (bisection in log(ki) down to the
    ratio ``tolerance``; 0 when none)."""
    lo, hi = _KI_MIN, _KI_MAX
    if not loop.acceptable(kp, lo, kd, ms):
        return 0.0
    while hi / lo > tolerance:
        mid = math.sqrt(lo * hi)
        if loop.acceptable(kp, mid, kd, ms):
            lo = mid
        else:
            hi = mid
    return lo


def _search(loop: RobustLoop, servo: ServoFit, ms: float, derivative: bool):
    """MIGO: the (kp, ki, kd) of largest ki over a grid of kp (and kd)."""
    g = abs(servo.gain) if servo.gain else 1.0
    w_n = 2.0 * math.pi * servo.frequency
    kps = np.linspace(0.0, 3.0 / g, 31)
    kds = np.linspace(0.0, 4.0 / (g * w_n), 9) if derivative else np.zeros(1)
    best = (0.0, 0.0, 0.0)
    for kd in kds:
        for kp in kps:
            ki = largest_ki(loop, float(kp), float(kd), ms)
            if ki > best[1]:
                best = (float(kp), ki, float(kd))
    return best


def loop_margins(
    plant: tuple[np.ndarray, np.ndarray],
    dt: float,
    gains: tuple[float, float, float],
    cutoff: float,
) -> tuple[float, float, float]:
    """(gain margin dB, phase margin deg, crossover Hz) of C P (P in z^-1), from the loop's
    exact frequency response (:func:`frequency_margins`; no python-control needed)."""
    kp, ki, kd = gains
    c_num, c_den = controller_polynomials(kp, ki, kd, cutoff, dt)
    return frequency_margins(np.convolve(c_num, plant[0]), np.convolve(c_den, plant[1]), dt)


def frequency_margins(
    num: np.ndarray, den: np.ndarray, dt: float, points: int = 4000
) -> tuple[float, float, float]:
    """(gain margin dB, phase margin deg, gain crossover Hz) of the discrete loop num/den (in
    z^-1) from its frequency response L(e^{j w dt}), w from 1e-2 rad/s to the Nyquist
    frequency.

    The crossings are bracketed on a ``points``-point logarithmic grid and solved by Brent's
    method on the exact response: |L| = 1 (gain crossovers) and Im L = 0 with Re L < 0 (phase
    crossovers, the Nyquist frequency included where L is negative there). As
    python-control's ``stability_margins``, the gain margin is the crossing's 1/|L| closest to
    1 in log (inf dB when the phase never crosses -180 deg), the phase margin the crossover's
    that is smallest in magnitude (inf, and a NaN crossover, when |L| never crosses 1).

    Parameters
    ----------
    num, den : numpy.ndarray of float
        The loop's coefficients in z^-1.
    dt : float
        The sample time (s).
    points : int, default 4000
        Grid points bracketing the crossings.

    Returns
    -------
    tuple of float
        Gain margin (dB), phase margin (deg), gain-crossover frequency (Hz).
    """
    from scipy.optimize import brentq

    nyquist = math.pi / dt

    def L(w):
        return _evaluate(num, den, np.exp(-1j * np.asarray(w, dtype=float) * dt))

    w = np.geomspace(1e-2, nyquist, points)
    w[-1] = nyquist
    h = L(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        mag = np.abs(h) - 1.0
    crossings = [brentq(lambda x: float(abs(L(x)) - 1.0), w[i], w[i + 1])
                 for i in np.nonzero(np.diff(np.sign(mag)) != 0)[0]
                 if np.isfinite(mag[i]) and np.isfinite(mag[i + 1])]  # fmt: skip
    phase_w = [brentq(lambda x: float(L(x).imag), w[i], w[i + 1])
               for i in np.nonzero(np.diff(np.sign(h.imag)) != 0)[0]
               if np.isfinite(h[i]) and np.isfinite(h[i + 1])]  # fmt: skip
    phase_w = [x for x in phase_w if L(x).real < 0]
    if h[-1].real < 0 and abs(h[-1].imag) <= 1e-9 * abs(h[-1]) and nyquist not in phase_w:
        phase_w.append(nyquist)  # L is real at the Nyquist frequency: a crossing there
    gm_db = math.inf
    if phase_w:
        with np.errstate(divide="ignore"):
            gms = [-20.0 * math.log10(abs(complex(L(x)))) if abs(L(x)) > 0 else math.inf
                   for x in phase_w]  # fmt: skip
        gm_db = min(gms, key=abs)
    if not crossings:
        return gm_db, math.inf, math.nan
    pms = [float(np.remainder(np.angle(complex(L(x)), deg=True), 360.0) - 180.0)
           for x in crossings]  # fmt: skip
    i = min(range(len(pms)), key=lambda k: abs(pms[k]))
    return gm_db, pms[i], crossings[i] / (2.0 * math.pi)


def reached_peak(loop: RobustLoop, gains: tuple[float, float, float]) -> list[float]:
    """Each plant's peak sensitivity on a grid 10 times denser than the search's, from the
    same lowest frequency to the Nyquist frequency (inf where the closed loop is unstable):
    the peak a design states it reached."""
    dense = RobustLoop(loop.plants, loop.dt, loop.cutoff, points=10 * loop.zinv.size)
    return dense.peaks(*gains)


def _warn_if_not_met(who: str, reached: float, target: float, stacklevel: int = 3) -> None:
    if reached > MS_TOLERANCE * target:
        gm, pm = implied_margins(target)
        warnings.warn(
            f"{who}: the design's peak sensitivity {reached:.3g} is above its target "
            f"{target:g} (which guarantees {gm:.2g} dB and {pm:.2g} deg): the margins it "
            "reached are stated in its design",
            MarginNotMetWarning,
            stacklevel=stacklevel,
        )


def tune_encoder_loop(
    servo: ServoFit,
    dt: float = 1e-3,
    max_sensitivity: float = 1.7,
    derivative: bool = False,
    servo_integral_only: bool = False,
) -> EncoderLoopDesign:
    """PI(D) gains of an encoder loop around an identified servo (MIGO, see the module).

    Parameters
    ----------
    servo : ServoFit
        The servo identified from a motor calibration run.
    dt : float, default 1e-3
        The control cycle (s), > 0.
    max_sensitivity : float, default 1.7
        The bound on the peak sensitivity, > 1 (1.4-2 are usual; lower is more robust).
    derivative : bool, default False
        Also search a derivative gain (filtered at a tenth of the sample rate).
    servo_integral_only : bool, default False
        Around a servo with integral action of its own, leave the loop out (all gains 0, the
        reason in ``note``) rather than add a second integral (see the module).

    Returns
    -------
    EncoderLoopDesign
        The gains and the margins they achieve on the identified servo.

    Warns
    -----
    MarginNotMetWarning
        The peak sensitivity reached is above ``max_sensitivity`` (the design states both).

    Raises
    ------
    ValueError
        dt or max_sensitivity out of range, or no gains that keep the loop stable within
        ``max_sensitivity`` (the identified servo cannot be closed at this cycle time).
    """
    require_servo("tune_encoder_loop", servo)
    dt, ms = float(dt), float(max_sensitivity)
    if not (math.isfinite(dt) and dt > 0):
        raise ValueError(f"tune_encoder_loop: dt must be > 0 (got {dt})")
    if not (math.isfinite(ms) and ms > 1.0):
        raise ValueError(f"tune_encoder_loop: max_sensitivity must be > 1 (got {ms})")
    cutoff = 0.1 / dt
    plant = loop_plant(servo, dt)
    loop = RobustLoop([plant], dt, cutoff)
    note = ""
    if servo.integral_time > 0:
        if servo_integral_only:
            note = (
                f"no loop: the identified servo has integral action of its own (T_i "
                f"{servo.integral_time:.3g} s) and holds its command (servo_integral_only)"
            )
            return EncoderLoopDesign(0.0, 0.0, 0.0, cutoff, ms, 1.0, math.inf, math.inf,
                                     math.nan, servo, dt, note)  # fmt: skip
        note = (
            f"around a servo with integral action of its own (T_i {servo.integral_time:.3g} s): "
            "the loop's integral makes a double integrator, its margins those of the whole loop "
            "(servo_integral_only=True leaves the loop out)"
        )
    kp, ki, kd = _search(loop, servo, ms, derivative)
    if not ki > 0:
        raise ValueError(
            f"tune_encoder_loop: no PI{'D' if derivative else ''} gains keep the loop around the "
            f"identified servo ({servo.summary()}) stable with a peak sensitivity <= {ms:g} at "
            f"dt = {dt:g} s; the encoder loop cannot be closed on this drive"
        )
    (peak,) = reached_peak(loop, (kp, ki, kd))
    gm, pm, fc = loop_margins(plant, dt, (kp, ki, kd), cutoff)
    _warn_if_not_met("tune_encoder_loop", peak, ms)
    return EncoderLoopDesign(kp, ki, kd, cutoff, ms, peak, gm, pm, fc, servo, dt, note)


__all__ = [
    "MS_TOLERANCE",
    "EncoderLoopDesign",
    "MarginNotMetWarning",
    "frequency_margins",
    "implied_margins",
    "reached_peak",
    "RobustLoop",
    "controller_polynomials",
    "largest_ki",
    "loop_margins",
    "loop_plant",
    "tune_encoder_loop",
]
