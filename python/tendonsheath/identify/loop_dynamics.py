"""A tip-feedback loop's dynamics from calibration logs: servo, distal resonance, sensor delay.

A controller closed on a tip sensor is tuned on the whole path from the servo command to the
sensor's reading. :func:`identify_loop_dynamics` splits that path at the motor encoder and fits
both parts from the logs of one calibration run (command, motor encoder, tip sensor):

* the servo, command -> encoder, by :func:`~tendonsheath.identify.servo.identify_servo` (a
  PD or PID second/third-order form plus a transport delay, chosen by BIC);
* the distal part, encoder -> tip, always as a second-order mode plus a delay of ``d``
  samples (the sensor's latency and any transport delay; the motor encoder is taken as
  undelayed)::

      tip = offset + gain * w^2 / (s^2 + 2 damping w s + w^2) * encoder(t - d dt)

  (w = 2 pi resonance_hz). The encoder is a sampled continuous signal, not a held command, so
  this part is discretised with a first-order hold (linear between samples); a zero-order
  hold would read it half a sample early and bias the delay by half a sample.

Both parts are fitted on the signals high-passed zero-phase above ``highpass_hz`` (the
tendons' slow stretch and creep drop out; the filter applied to both sides keeps the linear
relation), by least squares with variable projection (the gain solved inside), for every delay
in [0, max_delay]; the delay with the least squared residual is kept. Standard errors: of
resonance and damping linearised at the optimum; of the delay from the profile of the residual
over the neighbouring delays (the delay whose residual rises by one noise variance), combined
with the whole-sample resolution (dt / sqrt(12)).

The excitation: a chirp on a monotonic ramp (the tendons never reverse through their dead
zone), :func:`tendonsheath.bench.loop_calibration.loop_calibration_input`.

A resonance is only reported within the excitation's band (``band_hz``: the chirp's, or where
the command's speed spectrum lies within 30 dB of its peak): logs say nothing of a mode the
command never excited. A drive whose distal part shows no mode within the band (a stiff or
light joint) makes the second-order fit put one beyond it, a number the logs do not support;
it is then refused: ``resonance_hz`` is inf (``resonance_identified`` False; the refused fit
is kept as ``rejected_resonance_hz``), the distal part is its gain and delay alone, and a
:class:`ResonanceOutOfBandWarning` says so. A design takes the band's upper edge as the highest
frequency it knows (``design_limit_hz``). A mode below the band is refused with a ValueError
(excite lower).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.arrays import as_timed_signal
from .._util.typing import ArrayLike
from ..control_interop import require_control
from .servo import (
    ServoFit,
    _band,
    _best_delay,
    _one_blas_thread,
    _standard_errors,
    _uniform_step,
    _unit_response,
    identify_servo,
    servo_filter,
)

if TYPE_CHECKING:
    import control

_NAME = "identify_loop_dynamics"
#: Dampings of the coarse grid that starts the distal fit (a resonant mode: light damping).
_DISTAL_DAMPINGS = (0.03, 0.08, 0.2, 0.5, 1.0)
#: The least fraction of the high-passed tip's variance the distal fit must explain.
_MIN_EXPLAINED = 0.05
#: Where the band is inferred from the command: its speed spectrum within this many dB of
#: its peak (a log chirp's falls as 1/f: 14 dB over 5-120 Hz; beyond its last frequency it
#: drops by 60 dB and more within a few Hz).
_BAND_DB = 30.0


class ResonanceOutOfBandWarning(UserWarning):
    """The distal fit put its mode outside the excitation's band: no resonance is reported
    (``LoopDynamics.resonance_identified`` is False) and designs take the band's upper edge
    as the highest frequency they know."""


@dataclass(frozen=True)
class LoopDynamics:
    """A tip-feedback loop's dynamics identified from logs (see the module).

    Parameters
    ----------
    servo : ServoFit
        The servo, command -> motor encoder.
    resonance_hz : float
        Natural frequency of the distal mode (Hz).
    damping : float
        Damping ratio of the distal mode.
    gain : float
        Gain of the distal part, tip per encoder (fitted in the high-passed band).
    delay_samples : int
        The distal part's delay (samples): the sensor's latency and any transport delay.
    dt : float
        Sample time of the logs (s).
    bandwidth_hz : float
        The -3 dB frequency of command -> tip (Hz; the Nyquist frequency when the response
        never falls 3 dB below its static gain).
    rmse : float
        Root-mean-square error of the distal fit on the high-passed tip (unit of the tip).
    nrmse : float
        rmse over the high-passed tip's range.
    standard_errors : dict of str to float
        resonance_hz, damping and delay (s; see the module).
    delay_profile : dict of int to float
        The distal fit's sum of squared residuals at each delay tried (samples).
    band_hz : tuple of float, optional
        The excitation's band (Hz) the resonance was sought in.
    rejected_resonance_hz : float, optional
        The mode the second-order fit put outside ``band_hz`` (Hz), refused: nothing is
        designed from it (``resonance_hz`` is then inf and ``damping`` NaN).
    """

    servo: ServoFit
    resonance_hz: float
    damping: float
    gain: float
    delay_samples: int
    dt: float
    bandwidth_hz: float
    rmse: float
    nrmse: float
    standard_errors: dict[str, float] = field(default_factory=dict)
    delay_profile: dict[int, float] = field(default_factory=dict)
    band_hz: tuple[float, float] | None = None
    rejected_resonance_hz: float | None = None

    @property
    def delay(self) -> float:
        """The distal part's delay (s): delay_samples * dt."""
        return self.delay_samples * self.dt

    @property
    def resonance_identified(self) -> bool:
        """Whether a distal resonance was identified (within the excitation's band)."""
        return math.isfinite(self.resonance_hz)

    @property
    def design_limit_hz(self) -> float:
        """The frequency a design takes as the distal part's limit (Hz): the resonance, or,
        with none identified within the band, the band's upper edge (the highest frequency
        the logs speak of; the Nyquist frequency when no band is known)."""
        if self.resonance_identified:
            return self.resonance_hz
        return float(self.band_hz[1]) if self.band_hz is not None else 0.5 / self.dt

    def resonance_text(self) -> str:
        """The resonance in words.

        Returns
        -------
        str
            e.g. "42.6 Hz", or "none within the 5-120 Hz band (120 Hz taken as the limit)".
        """
        if self.resonance_identified:
            return f"{self.resonance_hz:.3g} Hz"
        band = f"{self.band_hz[0]:.3g}-{self.band_hz[1]:.3g} Hz " if self.band_hz else ""
        return f"none within the {band}band ({self.design_limit_hz:.3g} Hz taken as the limit)"

    def distal_discrete(self, dt: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The distal part encoder -> tip in z^-1 (first-order hold, the delay included, rounded
        to whole samples of ``dt``; default the logs').

        Parameters
        ----------
        dt : float, optional
            Sample time (s), > 0.

        Returns
        -------
        num, den : numpy.ndarray of float
            Coefficients in z^-1 (den[0] = 1).
        """
        step = self._step(dt)
        d = int(round(self.delay / step))
        if not self.resonance_identified:  # gain and delay alone: no mode within the band
            return np.concatenate([np.zeros(d), [self.gain]]), np.ones(1)
        return servo_filter(self.resonance_hz, self.damping, self.gain, d, step, 0.0, "foh")

    def discrete(self, dt: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """command -> tip in z^-1 at sample time ``dt`` (default the logs'): the servo (zero-order
        hold, as :meth:`ServoFit.discrete`) times the distal part (first-order hold) times the
        delays, each rounded to whole samples of ``dt``.

        Parameters
        ----------
        dt : float, optional
            Sample time (s), > 0.

        Returns
        -------
        num, den : numpy.ndarray of float
            Coefficients in z^-1 (den[0] = 1).
        """
        step = self._step(dt)
        sv = self.servo
        ds = int(round(sv.delay * sv.dt / step))
        ns, dens = servo_filter(sv.frequency, sv.damping, sv.gain, ds, step, sv.integral_time)
        nd, dend = self.distal_discrete(step)
        return np.convolve(ns, nd), np.convolve(dens, dend)

    def frequency_response(self, f_hz: ArrayLike, dt: float | None = None) -> np.ndarray:
        """command -> tip at the frequencies ``f_hz``: the exact response of :meth:`discrete`
        (z = exp(2 pi j f dt), at the logs' dt by default), which is what a sampled loop and an
        empirical estimate from the logs (:func:`empirical_response`) see.

        Parameters
        ----------
        f_hz : array_like of float
            Frequencies (Hz), >= 0.
        dt : float, optional
            Sample time (s), > 0.

        Returns
        -------
        numpy.ndarray of complex
            The response, shaped as f_hz.
        """
        step = self._step(dt)
        num, den = self.discrete(step)
        return _response(num, den, np.asarray(f_hz, dtype=float), step)

    def to_control(self, dt: float | None = None) -> control.TransferFunction:
        """command -> tip as a discrete-time python-control transfer function, sample time
        ``dt`` (default the logs').

        Parameters
        ----------
        dt : float, optional
            Sample time (s), > 0.

        Returns
        -------
        control.TransferFunction
            The transfer function in z.
        """
        ct = require_control()
        step = self._step(dt)
        num, den = self.discrete(step)
        n = max(num.size, den.size)
        return ct.tf(np.pad(num, (0, n - num.size)), np.pad(den, (0, n - den.size)), step)

    def as_dict(self) -> dict[str, Any]:
        """The dynamics as a JSON-ready dict.

        Returns
        -------
        dict
            Every field, the servo's as a dict, and the delay in seconds.
        """
        found = self.resonance_identified
        return {
            "servo": self.servo.as_dict(),
            "resonance_hz": self.resonance_hz if found else None,
            "resonance_identified": found,
            "band_hz": list(self.band_hz) if self.band_hz is not None else None,
            "rejected_resonance_hz": self.rejected_resonance_hz,
            "damping": self.damping if found else None,
            "gain": self.gain,
            "delay": self.delay,
            "delay_samples": self.delay_samples,
            "dt": self.dt,
            "bandwidth_hz": self.bandwidth_hz,
            "rmse": self.rmse,
            "nrmse": self.nrmse,
            "standard_errors": dict(self.standard_errors),
            "delay_profile": {str(k): v for k, v in self.delay_profile.items()},
        }

    def summary(self) -> str:
        """One line: resonance, damping, delay and bandwidth with their standard errors.

        Returns
        -------
        str
            e.g. "resonance 41.2 +- 0.3 Hz, damping 0.18 +- 0.01, delay 1 +- 0.3 ms, ..."
        """
        se = self.standard_errors

        def pm(key: str, scale: float = 1.0) -> str:
            return f" +- {scale * se[key]:.2g}" if key in se else ""

        if self.resonance_identified:
            mode = (
                f"resonance {self.resonance_hz:.4g}{pm('resonance_hz')} Hz, damping "
                f"{self.damping:.3g}{pm('damping')}"
            )
        else:
            rejected = self.rejected_resonance_hz
            mode = f"resonance {self.resonance_text()}" + (
                f" (the fit's mode at {rejected:.3g} Hz refused)" if rejected else ""
            )
        return (
            f"{mode}, delay {1e3 * self.delay:.3g}{pm('delay', 1e3)} ms "
            f"({self.delay_samples} samples), bandwidth {self.bandwidth_hz:.3g} Hz "
            f"(command -> tip, -3 dB); servo {self.servo.frequency:.3g} Hz; distal nrmse "
            f"{self.nrmse:.2g}"
        )

    def _step(self, dt: float | None) -> float:
        step = self.dt if dt is None else float(dt)
        if not (math.isfinite(step) and step > 0):
            raise ValueError(f"LoopDynamics: dt must be > 0 (got {dt})")
        return step


@dataclass(frozen=True)
class EmpiricalResponse:
    """A frequency response estimated from logs: H1 = Pxy / Pxx (Welch), with coherence.

    Parameters
    ----------
    frequency_hz : numpy.ndarray of float
        Frequencies (Hz).
    response : numpy.ndarray of complex
        Output over input.
    coherence : numpy.ndarray of float
        Magnitude-squared coherence in [0, 1] (1: the output is linear in the input).
    """

    frequency_hz: np.ndarray
    response: np.ndarray
    coherence: np.ndarray


def empirical_response(
    t: ArrayLike, command: ArrayLike, output: ArrayLike, nperseg: int | None = None
) -> EmpiricalResponse:
    """The H1 estimate Pxy / Pxx of ``output`` over ``command`` (scipy.signal.csd and welch,
    Hann windows, half overlap, each segment's linear trend removed: the ramp), with the
    coherence |Pxy|^2 / (Pxx Pyy).

    Parameters
    ----------
    t : array_like of float, shape (n,)
        Sample times (s), uniform.
    command : array_like of float, shape (n,)
        The input.
    output : array_like of float, shape (n,)
        The output (e.g. the tip sensor), finite.
    nperseg : int, optional
        Samples per segment (default a second's worth, at most n/4): the frequency resolution
        is 1/(nperseg dt).

    Returns
    -------
    EmpiricalResponse
        Frequencies, H1 and coherence (the zero frequency left out).

    Raises
    ------
    ValueError
        Arrays of different lengths, non-finite samples, a non-uniform or too short record.
    """
    from scipy.signal import csd, welch

    ts, u = as_timed_signal(t, command, "command", "empirical_response")
    _, y = as_timed_signal(ts, output, "output", "empirical_response")
    dt = _uniform_step(ts, "empirical_response")
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(y))):
        raise ValueError("empirical_response: command and output must be finite")
    n = nperseg if nperseg is not None else min(int(round(1.0 / dt)), u.size // 4)
    if not (isinstance(n, int) and 16 <= n <= u.size):
        raise ValueError(f"empirical_response: nperseg must be an int in [16, n] (got {n})")
    opts: dict[str, Any] = {"fs": 1.0 / dt, "nperseg": n, "detrend": "linear"}
    f, pxy = csd(u, y, **opts)
    _, pxx = welch(u, **opts)
    _, pyy = welch(y, **opts)
    ok = f > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        h = pxy / pxx
        coh = np.abs(pxy) ** 2 / (pxx * pyy)
    return EmpiricalResponse(f[ok], h[ok], np.nan_to_num(coh[ok].real, nan=0.0))


@_one_blas_thread
def _checked_logs(t, command, encoder, tip, max_delay, highpass_hz):
    """The logs as arrays on a uniform step, each checked (finite, moving; the tip without
    dropouts) with the settings: (t, command, encoder, tip, dt)."""
    ts, u = as_timed_signal(t, command, "command", _NAME)
    _, q = as_timed_signal(ts, encoder, "encoder", _NAME)
    _, y = as_timed_signal(ts, tip, "tip", _NAME)
    dt = _uniform_step(ts, _NAME)
    for name, x in (("command", u), ("encoder", q)):
        if not np.all(np.isfinite(x)):
            raise ValueError(f"{_NAME}: {name} must be finite")
    bad = ~np.isfinite(y)
    if bad.any():
        first = int(np.argmax(bad))
        raise ValueError(
            f"{_NAME}: the tip reading has {int(bad.sum())} non-finite samples (sensor "
            f"dropouts; the first at t = {ts[first]:.6g} s); dropouts are not bridged: cut the "
            "record around them"
        )
    if not np.ptp(u) > 0:
        raise ValueError(f"{_NAME}: the command does not move")
    if not np.ptp(q) > 0:
        raise ValueError(f"{_NAME}: the motor encoder does not move")
    if not np.ptp(y) > 0:
        raise ValueError(f"{_NAME}: the tip reading does not move (no response)")
    if not (isinstance(max_delay, int) and 0 <= max_delay < u.size // 4):
        raise ValueError(f"{_NAME}: max_delay must be an int in [0, n/4) (got {max_delay})")
    if not (math.isfinite(highpass_hz) and 0 <= highpass_hz < 0.25 / dt):
        raise ValueError(f"{_NAME}: highpass_hz must be in [0, {0.25 / dt:g}) Hz")
    return ts, u, q, y, dt


def identify_loop_dynamics(
    t: ArrayLike,
    command: ArrayLike,
    encoder: ArrayLike,
    tip: ArrayLike,
    max_delay: int = 20,
    highpass_hz: float = 2.0,
    band_hz: tuple[float, float] | None = None,
) -> LoopDynamics:
    """Identify a tip-feedback loop from a calibration run's logs (see the module).

    Parameters
    ----------
    t : array_like of float, shape (n,)
        Sample times (s), uniform.
    command : array_like of float, shape (n,)
        The commands sent to the servo (rad).
    encoder : array_like of float, shape (n,)
        The motor encoder (rad).
    tip : array_like of float, shape (n,)
        The tip sensor's reading, finite: sensor dropouts (NaN) are rejected, not bridged
        (cut the record around them).
    max_delay : int, default 20
        The largest delay tried for the distal part (samples), >= 0; the servo's goes to
        min(max_delay, 10).
    highpass_hz : float, default 2.0
        The dynamics are fitted above this frequency (Hz; 0: the whole record, the mean
        removed).
    band_hz : tuple of float, optional
        The excitation's band (low, high) in Hz, e.g. the chirp's (5, 120); default inferred
        from the command (where its speed spectrum is within 30 dB of its peak, above
        ``highpass_hz``). No resonance is reported outside it (see the module).

    Returns
    -------
    LoopDynamics
        The servo, the distal mode (or none within the band) and delay, the loop's bandwidth.

    Raises
    ------
    ValueError
        Arrays of different lengths, non-finite samples (naming the first sensor dropout), a
        non-uniform or too short record, a command that does not move, a tip that does not
        respond to the encoder, a distal mode below the excitation's band, or an argument
        out of range.

    Warns
    -----
    ResonanceOutOfBandWarning
        The fit's mode lies above the band: no resonance is reported.
    """
    ts, u, q, y, dt = _checked_logs(t, command, encoder, tip, max_delay, highpass_hz)
    band = _excitation_band(u, dt, highpass_hz) if band_hz is None else _checked_band(band_hz, dt)
    servo = identify_servo(ts, u, q, max_delay=min(max_delay, 10), highpass_hz=highpass_hz)
    qb, yb = _band(q, dt, highpass_hz), _band(y, dt, highpass_hz)
    edge = min(int(round(1.0 / (max(highpass_hz, 1e-9) * dt))), u.size // 8)
    keep = slice(edge, u.size - edge)
    fits, profile = _distal_fits(qb, yb, dt, keep, max_delay)
    sse, d, f, z, _, res, r = min(fits, key=lambda item: item[0])
    ys = yb[keep]
    explained = 1.0 - sse / float(np.sum((ys - ys.mean()) ** 2))
    if not explained >= _MIN_EXPLAINED:
        raise ValueError(
            f"{_NAME}: the tip does not respond to the encoder (the best fit explains "
            f"{100 * max(explained, 0.0):.2g} % of the high-passed tip's variance): no sensor "
            "signal, or an excitation buried in the noise"
        )
    if f < band[0]:
        raise ValueError(
            f"{_NAME}: the distal fit's mode at {f:.3g} Hz lies below the excitation's band "
            f"({band[0]:.3g}-{band[1]:.3g} Hz): no resonance identified within the band; start "
            "the excitation lower (f_start) to identify it"
        )
    rejected = None
    if f > band[1]:
        rejected = f
        warnings.warn(
            f"{_NAME}: no resonance identified within the {band[0]:.3g}-{band[1]:.3g} Hz "
            f"excitation band (the fit's mode at {f:.3g} Hz lies above it and is refused); the "
            f"distal part is taken as its gain and delay, and {band[1]:.3g} Hz as the highest "
            "frequency a design knows",
            ResonanceOutOfBandWarning,
            stacklevel=2,
        )
        sse, d, gain, res, profile = _static_distal(qb, yb, keep, max_delay)
        f, z, errors = math.inf, math.nan, {}
    else:
        gain = _gain(qb, yb, f, z, d, dt, keep)
        errors = {
            "resonance_hz" if k == "frequency" else k: v
            for k, v in _standard_errors(r, res, f, z).items()
        }
    errors["delay"] = dt * _delay_error(profile, d, res.size)
    rmse = math.sqrt(sse / res.size)
    dyn = LoopDynamics(
        servo=servo,
        resonance_hz=f,
        damping=z,
        gain=gain,
        delay_samples=d,
        dt=dt,
        bandwidth_hz=math.nan,
        rmse=rmse,
        nrmse=rmse / float(np.ptp(ys)),
        standard_errors=errors,
        delay_profile=profile,
        band_hz=band,
        rejected_resonance_hz=rejected,
    )
    return _with_bandwidth(dyn)


def _excitation_band(u: np.ndarray, dt: float, highpass_hz: float) -> tuple[float, float]:
    """(low, high) Hz where the command's speed spectrum (Tukey-windowed, smoothed over 1 Hz)
    is within ``_BAND_DB`` of its peak, at or above ``highpass_hz``."""
    from scipy.ndimage import uniform_filter1d
    from scipy.signal.windows import tukey

    v = np.diff(u)
    v = (v - v.mean()) * tukey(v.size, 0.1)
    power = np.abs(np.fft.rfft(v)) ** 2
    f = np.fft.rfftfreq(v.size, dt)
    power = uniform_filter1d(power, max(1, int(round(1.0 / f[1]))))  # 1 Hz
    above = f >= max(highpass_hz, f[1])
    if not np.any(above & (power > 0)):
        return float(f[1]), 0.5 / dt
    on = f[above & (power >= power[above].max() * 10 ** (-_BAND_DB / 10))]
    return float(on.min()), float(on.max())


def _checked_band(band_hz, dt: float) -> tuple[float, float]:
    try:
        lo, hi = (float(b) for b in band_hz)
    except (TypeError, ValueError):
        raise ValueError(f"{_NAME}: band_hz must be (low, high) in Hz (got {band_hz!r})") from None
    if not (0 <= lo < hi <= 0.5 / dt):
        raise ValueError(
            f"{_NAME}: band_hz must satisfy 0 <= low < high <= {0.5 / dt:g} Hz (got {band_hz!r})"
        )
    return lo, hi


def _static_distal(u: np.ndarray, y: np.ndarray, keep: slice, max_delay: int):
    """The distal part as a gain and a delay (no mode): (sse, delay, gain, residual,
    {delay: sse}) of the least-squares gain and offset at each delay in [0, max_delay]."""
    fits = {}
    for d in range(max_delay + 1):
        s = np.concatenate([np.full(d, u[0]), u[: u.size - d]])[keep]
        A = np.column_stack([s, np.ones_like(s)])
        (g, c), *_ = np.linalg.lstsq(A, y[keep], rcond=None)
        res = y[keep] - (g * s + c)
        fits[d] = (float(res @ res), d, float(g), res)
    sse, d, g, res = min(fits.values(), key=lambda item: item[0])
    return sse, d, g, res, {k: v[0] for k, v in fits.items()}


def _distal_fits(u: np.ndarray, y: np.ndarray, dt: float, keep: slice, max_delay: int):
    """The second-order fits (first-order hold) of the distal part: a coarse grid of
    frequency and damping at every delay in [0, max_delay] (a delay only shifts a response,
    so the grid is filtered once), least squares from the grid's best at its three best
    delays, then at the neighbours of the best fit until none is better. Returns the fits
    (sse, delay, f, z, ti, residual, result) and the profile {delay: sse} of those fitted."""
    grid = [(f, z) for f in np.geomspace(1.0, 0.4 / dt, 48) for z in _DISTAL_DAMPINGS]
    base = np.array([_unit_response(f, z, u, 0, dt, hold="foh") for f, z in grid])
    yk = y[keep] - y[keep].mean()
    yy = float(yk @ yk)
    best_grid = []
    for d in range(max_delay + 1):
        shifted = np.concatenate([np.repeat(base[:, :1], d, axis=1), base[:, : u.size - d]], 1)
        s = shifted[:, keep]
        s = s - s.mean(axis=1, keepdims=True)
        ss = np.einsum("ij,ij->i", s, s)
        sse = yy - np.einsum("ij,j->i", s, yk) ** 2 / np.where(ss > 0, ss, np.inf)
        i = int(np.argmin(sse))
        best_grid.append((float(sse[i]), d, np.log(grid[i])))
    fits: dict[int, tuple] = {}

    def fit(d: int) -> None:
        if d not in fits and 0 <= d <= max_delay:
            start = best_grid[d][2]
            fits[d] = _best_delay(u, y, dt, keep, start, [d], hold="foh", min_damping=0.005)

    for _, d, _ in sorted(best_grid, key=lambda item: item[0])[:3]:
        fit(d)
    while True:
        d = min(fits.values(), key=lambda item: item[0])[1]
        if d - 1 in fits or d - 1 < 0:
            if d + 1 in fits or d + 1 > max_delay:
                break
        fit(d - 1)
        fit(d + 1)
    return list(fits.values()), {d: item[0] for d, item in sorted(fits.items())}


def _gain(u, y, f: float, z: float, d: int, dt: float, keep: slice) -> float:
    from scipy.signal import lfilter

    num, den = servo_filter(f, z, 1.0, d, dt, 0.0, "foh")
    s = lfilter(num, den, u - u[0])[keep]
    A = np.column_stack([s, np.ones_like(s)])
    (g, _), *_ = np.linalg.lstsq(A, y[keep], rcond=None)
    return float(g)


def _delay_error(profile: dict[int, float], d: int, n: int) -> float:
    """The delay's standard error (samples): the curvature of the residual's profile around
    its minimum in units of the noise variance (a rise of one variance: one standard error),
    combined with the whole-sample resolution 1/sqrt(12)."""
    s2 = profile[d] / max(n - 4, 1)
    rises = [(profile[k] - profile[d]) / s2 for k in (d - 1, d + 1) if k in profile]
    curvature = float(np.mean(rises)) if rises else 0.0
    profile_var = 1.0 / curvature if curvature > 0 else math.inf
    return math.sqrt(profile_var + 1.0 / 12.0)


def _response(num: np.ndarray, den: np.ndarray, f_hz: np.ndarray, dt: float) -> np.ndarray:
    zinv = np.exp(-2j * math.pi * f_hz * dt)
    return np.polyval(num[::-1], zinv) / np.polyval(den[::-1], zinv)


def _with_bandwidth(dyn: LoopDynamics) -> LoopDynamics:
    """``dyn`` with its bandwidth: the first frequency where |command -> tip| falls 3 dB below
    its static value (log-interpolated on a 0.1 %-spaced grid), else the Nyquist frequency."""
    nyquist = 0.5 / dyn.dt
    f = np.geomspace(1e-3 * nyquist, nyquist, 7000)
    num, den = dyn.discrete()
    static = abs(_response(num, den, np.zeros(1), dyn.dt)[0])
    mag = np.abs(_response(num, den, f, dyn.dt)) / static
    below = np.nonzero(mag < 1.0 / math.sqrt(2.0))[0]
    if below.size == 0 or below[0] == 0:
        return replace(dyn, bandwidth_hz=nyquist if below.size == 0 else float(f[0]))
    i = int(below[0])
    a, b = 20 * math.log10(mag[i - 1]), 20 * math.log10(mag[i])
    frac = (-10 * math.log10(2.0) - a) / (b - a)
    return replace(dyn, bandwidth_hz=float(f[i - 1] * (f[i] / f[i - 1]) ** frac))


__all__ = [
    "EmpiricalResponse",
    "LoopDynamics",
    "ResonanceOutOfBandWarning",
    "empirical_response",
    "identify_loop_dynamics",
]
