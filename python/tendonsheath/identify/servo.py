"""The motor's position servo identified from its own logs: command in, motor encoder out.

A motor-encoder loop (:class:`~tendonsheath.compensate.EncoderLoop`) is tuned on the servo it
closes around. Its plant is the drive as it is, tendons attached: the servo amplifier's own loop,
the rotor and gear, and the tendons' pull on the pulley. :func:`identify_servo` fits that, from a
calibration run's command and motor encoder, as

    q = offset + gain * w^2 / (s^2 + 2 damping w s + w^2) * command(t - delay)

(w = 2 pi frequency; a PD servo, which yields to a load), or, for a servo with integral action
(a PID servo: no steady error under a constant load), the third-order form

    q = offset + gain * w^2 (s + 1/T_i) / (s^3 + 2 damping w s^2 + w^2 s + w^2/T_i) * command

(``integral_time`` T_i > 0). Both are fitted; the integral is kept when it lowers the Bayesian
information criterion and its corner 1 / (2 pi T_i) lies within the band the dynamics are
fitted in (at or above ``highpass_hz``): a slower integral is no integral action the logs can
show (a PD servo under the tendons' slowly varying pull fits one at T_i ~ 0.8 s, a 0.2 Hz
corner below the 1 Hz high-pass), and the servo is then named PD. The command is held over
each sample (zero-order hold: what a servo receives), ``delay`` whole samples of transport
delay. The excitation should move the servo over its bandwidth without reversing the tendons
(a chirp on a slow ramp,
:func:`tendonsheath.bench.calibration.motor_calibration_input`).

The dynamics are fitted on both signals high-passed (zero phase) above ``highpass_hz``: the
tendons' slowly varying pull shifts the encoder by far more than the servo's fast response
moves it, and a filter applied to both sides keeps the linear relation between them. The
static gain and offset are then fitted on the raw signals with those dynamics.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.arrays import as_timed_signal
from .._util.blas import one_blas_thread
from .._util.typing import ArrayLike
from ..control_interop import require_control

if TYPE_CHECKING:
    import control


@dataclass(frozen=True)
class ServoFit:
    """A position servo identified from a command and a motor encoder (see the module).

    Parameters
    ----------
    frequency : float
        Natural frequency (Hz).
    damping : float
        Damping ratio.
    gain : float
        Static gain, encoder per command.
    offset : float
        Encoder offset (rad).
    delay : int
        Transport delay (samples).
    dt : float
        Sample time of the logs (s).
    rmse : float
        Root-mean-square error of the fit (rad).
    nrmse : float
        rmse over the encoder's range.
    standard_errors : dict of str to float, optional
        Linearised standard errors of frequency and damping.
    integral_time : float, default 0.0
        The servo's integral time T_i (s); 0: no integral action (a PD servo).
    """

    frequency: float
    damping: float
    gain: float
    offset: float
    delay: int
    dt: float
    rmse: float
    nrmse: float
    standard_errors: dict[str, float] = field(default_factory=dict)
    integral_time: float = 0.0

    def discrete(self, dt: float | None = None) -> tuple[np.ndarray, np.ndarray]:
        """The servo's zero-order-hold transfer function in z^-1 at sample time ``dt`` (default
        the logs'), the delay included: q_k = G(z) u_k with u_k held over the step ending at k.

        Parameters
        ----------
        dt : float, optional
            Sample time (s), > 0.

        Returns
        -------
        num, den : numpy.ndarray of float
            Coefficients in z^-1 (den[0] = 1).
        """
        return servo_filter(self.frequency, self.damping, self.gain, self.delay,
                            self.dt if dt is None else float(dt), self.integral_time)  # fmt: skip

    def to_control(self, dt: float | None = None) -> control.TransferFunction:
        """The servo as a discrete-time python-control transfer function (input: command,
        output: encoder), sample time ``dt`` (default the logs').

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
        step = self.dt if dt is None else float(dt)
        num, den = self.discrete(step)
        n = max(num.size, den.size)
        return ct.tf(np.pad(num, (0, n - num.size)), np.pad(den, (0, n - den.size)), step)

    def as_dict(self) -> dict[str, Any]:
        """The fit as a JSON-ready dict.

        Returns
        -------
        dict
            Every field.
        """
        return {
            "frequency_hz": self.frequency,
            "damping": self.damping,
            "gain": self.gain,
            "offset": self.offset,
            "delay_samples": self.delay,
            "integral_time": self.integral_time,
            "dt": self.dt,
            "rmse": self.rmse,
            "nrmse": self.nrmse,
            "standard_errors": dict(self.standard_errors),
        }

    def summary(self) -> str:
        """One line: the identified servo and its fit.

        Returns
        -------
        str
            Natural frequency, damping, gain, delay and the fit's nrmse.
        """
        se = self.standard_errors
        f_se = f" +- {se['frequency']:.2g}" if "frequency" in se else ""
        kind = f"PID (T_i {self.integral_time:.3g} s)" if self.integral_time > 0 else "PD"
        return (
            f"servo ({kind}): {self.frequency:.4g}{f_se} Hz, damping {self.damping:.3g}, gain "
            f"{self.gain:.4g}, delay {self.delay} samples ({1e3 * self.delay * self.dt:.3g} ms); "
            f"nrmse {self.nrmse:.3g}"
        )


def servo_filter(
    frequency: float,
    damping: float,
    gain: float,
    delay: int,
    dt: float,
    integral_time: float = 0.0,
    hold: str = "zoh",
) -> tuple[np.ndarray, np.ndarray]:
    """(num, den) in z^-1 of gain w^2/(s^2 + 2 damping w s + w^2) (with an integral time T_i > 0:
    gain w^2 (s + 1/T_i)/(s^3 + 2 damping w s^2 + w^2 s + w^2/T_i)), zero-order hold at dt, with
    the command of a step acting during that step (q_k from u_k held over (t_k-1, t_k]) and
    ``delay`` samples more. ``hold="foh"``: first-order hold instead (the input a sampled
    continuous signal, linear between samples: q_k from u_k-1 and u_k), for a stage driven by
    a measured signal rather than a held command."""
    from scipy.signal import cont2discrete

    w = 2.0 * math.pi * frequency
    if integral_time > 0:
        wi = 1.0 / integral_time
        tf = ([gain * w * w, gain * w * w * wi], [1.0, 2.0 * damping * w, w * w, w * w * wi])
    else:
        tf = ([gain * w * w], [1.0, 2.0 * damping * w, w * w])
    if hold not in ("zoh", "foh"):
        raise ValueError(f"servo_filter: hold must be 'zoh' or 'foh' (got {hold!r})")
    num, den, _ = cont2discrete(tf, dt, hold)
    num = np.atleast_1d(np.squeeze(num))
    if hold == "zoh":
        num = num[1:]  # drop the leading 0: the step's own command acts
    return np.concatenate([np.zeros(int(delay)), num]), np.asarray(den, dtype=float)


def _unit_response(frequency: float, damping: float, u: np.ndarray, delay: int, dt: float,
                   integral_time: float = 0.0, hold: str = "zoh"):  # fmt: skip
    from scipy.signal import lfilter

    num, den = servo_filter(frequency, damping, 1.0, delay, dt, integral_time, hold)
    shifted = u - u[0]  # from rest at the first command
    return lfilter(num, den, shifted) + u[0]


def _affine(s: np.ndarray, q: np.ndarray) -> tuple[float, float, np.ndarray]:
    """Least-squares gain and offset of q ~ gain * s + offset, and the residual."""
    A = np.column_stack([s, np.ones_like(s)])
    (g, c), *_ = np.linalg.lstsq(A, q, rcond=None)
    return float(g), float(c), q - (g * s + c)


def _band(x: np.ndarray, dt: float, highpass_hz: float) -> np.ndarray:
    from scipy.signal import butter, sosfiltfilt

    if highpass_hz <= 0:
        return x - x.mean()
    sos = butter(2, highpass_hz, btype="highpass", fs=1.0 / dt, output="sos")
    return sosfiltfilt(sos, x)


def _parameters(p: np.ndarray) -> tuple[float, float, float]:
    """(frequency, damping, integral time) from the search vector: the logs of frequency and
    damping, and with an integral the log of 1/T_i (rad/s)."""
    ti = math.exp(-p[2]) if p.size > 2 else 0.0
    return math.exp(p[0]), math.exp(p[1]), ti


def _fit_at_delay(u, q, delay: int, dt: float, start: np.ndarray, keep: slice, *,
                  hold: str = "zoh", min_damping: float = 0.05):  # fmt: skip
    """(frequency, damping, integral time, gain, offset, residual, least_squares result) at one
    delay, on the samples ``keep``; ``start`` has 2 entries (no integral) or 3; the gain and
    offset are solved linearly inside (variable projection). ``hold`` and ``min_damping``: the
    discretisation (see :func:`servo_filter`) and the lower bound of the damping searched."""
    from scipy.optimize import least_squares

    nyquist = 0.5 / dt

    def residual(p):
        f, z, ti = _parameters(p)
        if ti > 0 and 1.0 / ti >= 2.0 * z * 2.0 * math.pi * f:  # Routh: an unstable servo
            return np.full(keep.stop - keep.start, 1e3 * (1.0 + float(np.ptp(q))))
        return _affine(_unit_response(f, z, u, delay, dt, ti, hold)[keep], q[keep])[2]

    lo = [math.log(1e-3), math.log(min_damping), math.log(1e-2)][: start.size]
    hi = [math.log(0.45 * nyquist * 2), math.log(20.0), math.log(2.0 * math.pi * nyquist)]
    x0 = np.clip(start, lo, hi[: start.size])
    r = least_squares(residual, x0, bounds=(lo, hi[: start.size]), x_scale=1.0)
    f, z, ti = _parameters(r.x)
    g, c, res = _affine(_unit_response(f, z, u, delay, dt, ti, hold)[keep], q[keep])
    return f, z, ti, g, c, res, r


def _start(u, q, delay: int, dt: float, keep: slice, *, dampings=(0.3, 0.8, 2.0, 6.0),
           frequencies: int = 24, hold: str = "zoh") -> np.ndarray:  # fmt: skip
    """The best log(frequency), log(damping) of a coarse grid: a start for the least squares."""
    best, arg = math.inf, (1.0, 0.7)
    for f in np.geomspace(0.2, 0.4 / dt, frequencies):
        for z in dampings:
            response = _unit_response(f, z, u, delay, dt, hold=hold)[keep]
            sse = float(np.sum(_affine(response, q[keep])[2] ** 2))
            if sse < best:
                best, arg = sse, (float(f), z)
    return np.log(arg)


def _standard_errors(result, residual: np.ndarray, f: float, z: float) -> dict[str, float]:
    """Linearised standard errors of frequency and damping (the Jacobian is in their logs)."""
    J = np.asarray(result.jac)
    dof = max(residual.size - J.shape[1] - 2, 1)
    s2 = float(residual @ residual) / dof
    try:
        cov = s2 * np.linalg.inv(J.T @ J)
    except np.linalg.LinAlgError:
        return {}
    d = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    return {"frequency": float(f * d[0]), "damping": float(z * d[1])}


#: The fits multiply 3x3 and 4x4 matrices thousands of times (cont2discrete's expm): BLAS
#: threads only contend there (5x slower on a loaded two-core machine), so they run on one.
_one_blas_thread = one_blas_thread()


@_one_blas_thread
def identify_servo(
    t: ArrayLike,
    command: ArrayLike,
    encoder: ArrayLike,
    max_delay: int = 10,
    highpass_hz: float = 1.0,
) -> ServoFit:
    """Identify the position servo from a calibration run: ``command`` in, ``encoder`` out.

    Parameters
    ----------
    t : array_like of float, shape (n,)
        Sample times (s), uniform.
    command : array_like of float, shape (n,)
        The commands sent to the servo (rad).
    encoder : array_like of float, shape (n,)
        The motor encoder (rad).
    max_delay : int, default 10
        The largest transport delay tried (samples), >= 0.
    highpass_hz : float, default 1.0
        The dynamics are fitted above this frequency (Hz; 0: the whole record); an integral
        whose corner lies below it is not identified (a PD servo).

    Returns
    -------
    ServoFit
        The servo, with the delay of the best fit; ``integral_time`` > 0 (named PID) only
        when integral action was identified within the band.

    Raises
    ------
    ValueError
        Arrays of different lengths, non-finite samples, a non-uniform or too short record,
        a command that does not move, or an encoder identical to the command.
    """
    ts, u = as_timed_signal(t, command, "command", "identify_servo")
    _, q = as_timed_signal(ts, encoder, "encoder", "identify_servo")
    dt = _uniform_step(ts)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(q))):
        raise ValueError("identify_servo: command and encoder must be finite")
    if not np.ptp(u) > 0:
        raise ValueError("identify_servo: the command does not move")
    if not (math.isfinite(highpass_hz) and 0 <= highpass_hz < 0.25 / dt):
        raise ValueError(f"identify_servo: highpass_hz must be in [0, {0.25 / dt:g}) Hz")
    if not (isinstance(max_delay, int) and 0 <= max_delay < u.size // 4):
        raise ValueError(f"identify_servo: max_delay must be an int in [0, n/4) (got {max_delay})")
    if np.array_equal(u, q):
        raise ValueError(
            "identify_servo: the encoder is the command, sample for sample (the same signal "
            "logged twice?): a fit would be a servo with no dynamics at a frequency the data "
            "never show; log the motor encoder"
        )
    u_raw, q_raw = u, q
    u, q = _band(u, dt, highpass_hz), _band(q, dt, highpass_hz)
    edge = min(int(round(1.0 / (max(highpass_hz, 1e-9) * dt))), u.size // 8)
    keep = slice(edge, u.size - edge)
    start = _start(u, q, 0, dt, keep)  # a delay of a few samples barely moves the coarse grid
    slowest = highpass_hz if highpass_hz > 0 else 1.0 / (u.size * dt)
    d, f, z, ti, res, r = _best_structure(u, q, dt, keep, start, max_delay, slowest)
    g, c, raw = _affine(_unit_response(f, z, u_raw, d, dt, ti), q_raw)
    rmse = math.sqrt(float(raw @ raw) / u_raw.size)
    span = float(np.ptp(q_raw))
    return ServoFit(
        frequency=f,
        damping=z,
        gain=g,
        offset=c,
        delay=d,
        dt=dt,
        rmse=rmse,
        nrmse=rmse / span if span > 0 else math.inf,
        standard_errors=_standard_errors(r, res, f, z),
        integral_time=ti,
    )


def _best_delay(u, q, dt: float, keep: slice, start: np.ndarray, delays, **options):
    """The fit of the delay (of ``delays``) with the least squared residual: (sse, delay,
    fit...); ``options``: hold and min_damping of :func:`_fit_at_delay`."""
    fits = []
    for d in delays:
        f, z, ti, _, _, res, r = _fit_at_delay(u, q, d, dt, start, keep, **options)
        fits.append((float(res @ res), d, f, z, ti, res, r))
    return min(fits, key=lambda item: item[0])


def _best_structure(u, q, dt: float, keep: slice, start: np.ndarray, max_delay: int,
                    slowest_hz: float = 0.0):  # fmt: skip
    """The PD form, or the PID form when it lowers the Bayesian information criterion
    n ln(sse / n) + k ln(n) (k: 4 or 5 parameters with the gain and offset) and its integral
    corner 1 / (2 pi T_i) is at least ``slowest_hz`` (the band the logs are fitted in); the PID
    search starts from the PD fit (its delay and the ones beside it) with the integral corner
    at 5, 20 and 50 % of its frequency."""
    pd = _best_delay(u, q, dt, keep, start, range(max_delay + 1))
    f_pd, z_pd, near = pd[2], pd[3], range(max(pd[1] - 1, 0), min(pd[1] + 1, max_delay) + 1)
    w = 2.0 * math.pi * f_pd
    starts = [np.array([math.log(f_pd), math.log(z_pd), math.log(w * ratio)])
              for ratio in (0.05, 0.2, 0.5)]  # fmt: skip
    pid = min((_best_delay(u, q, dt, keep, x0, near) for x0 in starts), key=lambda f: f[0])
    n = keep.stop - keep.start
    bic = [n * math.log(max(f[0], 1e-300) / n) + k * math.log(n) for f, k in ((pd, 4), (pid, 5))]
    in_band = pid[4] > 0 and 1.0 / (2.0 * math.pi * pid[4]) >= slowest_hz
    _, d, f, z, ti, res, r = pid if bic[1] < bic[0] and in_band else pd
    return d, f, z, ti, res, r


def _uniform_step(ts: np.ndarray, name: str = "identify_servo") -> float:
    if ts.size < 64:
        raise ValueError(f"{name} needs at least 64 samples (got {ts.size})")
    steps = np.diff(ts)
    dt = float(np.median(steps))
    if not dt > 0 or float(np.max(np.abs(steps - dt))) > 1e-3 * dt:
        raise ValueError(f"{name} needs a uniform, increasing time vector")
    return dt


__all__ = ["ServoFit", "identify_servo", "servo_filter"]
