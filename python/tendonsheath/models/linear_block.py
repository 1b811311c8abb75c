"""Linear dynamic blocks with unit static gain, to chain with a hysteresis model.

``Chain(BoucWenBacklash(), FirstOrderLag(0.05))`` is a Hammerstein model (the hysteresis,
then the dynamics: its loop widens with the rate); ``Chain(SecondOrderLag(8.0, 0.5),
PrandtlIshlinskii())`` a Wiener one. The blocks start at rest at their first input (steady
state), so with unit static gain an affine map commutes with them.

Discretisation: exact for an input linear between samples (first-order hold, SciPy's
``cont2discrete(..., method="foh")``). ``simulate`` needs a uniform sample time (one
``scipy.signal.lfilter`` call in C; resample irregular records with ``resample=``);
``step(x, dt)`` accepts any dt.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import numpy as np

from .._util.args import number
from .._util.arrays import checked_dt
from .._util.typing import ArrayLike, FloatArray
from .._util.units import quantity_of, warn_if_unit_slip
from ._bound import LagInverseParams
from .base import HysteresisModel

# the units of the lags' parameters, from the C++ LagInverse's parameter table
_LAG_UNITS = {row["name"]: row["unit"] for row in LagInverseParams.fields()}

_UNIFORM = 1e-3  # relative spread of the sample time accepted as uniform


def discretise(num, den, dt: float) -> tuple[np.ndarray, np.ndarray]:
    """(b, a) of the transfer function num/den for sample time dt, first-order hold."""
    from scipy.signal import cont2discrete

    b, a, _ = cont2discrete((num, den), dt, method="foh")
    b = np.atleast_1d(np.squeeze(b)).astype(float)
    a = np.asarray(a, dtype=float)
    return b / a[0], a / a[0]


def sample_time(t) -> float:
    """The uniform sample time of t, or a ValueError saying how to get one."""
    if t is None:
        raise ValueError("a linear dynamic block is rate-dependent: t is required")
    dt = np.diff(np.asarray(t, dtype=float))
    if dt.size == 0:
        return 1.0
    med = float(np.median(dt))
    if not med > 0 or float(np.max(np.abs(dt - med))) > _UNIFORM * med:
        raise ValueError(
            "a linear dynamic block needs a uniform sample time: resample the record "
            "(ts.io.read_log(..., resample=RATE) or --resample RATE)"
        )
    return med


class LinearBlock(HysteresisModel):
    """Base of the linear blocks: ``transfer()`` gives (num, den) in s, unit static gain.

    Parameters
    ----------
    **values
        The subclass's parameters (``param_names``), each a real number inside its limits.

    Raises
    ------
    ValueError
        A missing, non-numeric, out-of-range or unknown parameter.
    """

    rate_independent = False
    param_names: ClassVar[tuple[str, ...]] = ()
    _limits: ClassVar[dict[str, tuple[float, float]]] = {}

    def __init__(self, **values: float) -> None:
        if type(self) is LinearBlock:
            raise TypeError(
                "LinearBlock is the base of the linear blocks, with no transfer function of "
                "its own: use FirstOrderLag or SecondOrderLag"
            )
        out: dict[str, float] = {}
        for name in self.param_names:
            v = number(type(self).__name__, name, values.pop(name))  # not "1", not None
            lo, hi = self._limits[name]
            if not (math.isfinite(v) and lo < v < hi):  # as the C++ LagInverse says it
                bound = f"> {lo:g}" if math.isinf(hi) else f"in ({lo:g}, {hi:g})"
                raise ValueError(f"{type(self).__name__}: {name} must be {bound} (got {v:g})")
            out[name] = v
        if values:
            raise TypeError(
                f"{type(self).__name__}: unknown parameter(s) {sorted(values)}; "
                f"expected {list(self.param_names)}"
            )
        self._values = out
        for name, v in out.items():  # the C++ inverse's table gives each one's unit
            q = quantity_of(name, _LAG_UNITS.get(name, ""))
            if q is not None:
                warn_if_unit_slip(v, type(self).__name__, name, q)
        self.reset()

    @property
    def params(self) -> dict[str, Any]:
        """The block's parameters, as a dict (a copy)."""
        return dict(self._values)

    @property
    def options(self) -> dict[str, Any]:
        """No options: an empty dict."""
        return {}

    def transfer(self) -> tuple[list[float], list[float]]:
        """The continuous transfer function (unit static gain); each block defines it.

        Returns
        -------
        num, den : list of float
            Coefficients of the transfer function in s, highest power first.
        """
        raise NotImplementedError

    def filter_coefficients(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """(b, a) for ``scipy.signal.lfilter`` at sample time dt (first-order hold).

        Parameters
        ----------
        dt : float
            Sample time (s), > 0.

        Returns
        -------
        b, a : numpy.ndarray of float
            Numerator and denominator in z^-1, a[0] = 1.
        """
        return discretise(*self.transfer(), dt)

    def _coefficients(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """filter_coefficients, or a one-line ValueError where the block cannot be
        discretised at dt (a time constant of 1e300 s: a singular matrix, an overflow)."""
        try:
            b, a = self.filter_coefficients(dt)
        except (ArithmeticError, np.linalg.LinAlgError):
            b = a = np.array([np.nan])
        finite = np.all(np.isfinite(b)) and np.all(np.isfinite(a))
        # a pole at z = 1 to rounding (no rest state to start from): a(1) = 0
        if not finite or abs(np.sum(a)) <= 1e-12 * np.sum(np.abs(a)):
            raise ValueError(
                f"{type(self).__name__} {self._values} cannot be discretised at a sample "
                f"time of {dt:g} s (a time constant or frequency too far from it)"
            )
        return b, a

    reports_status = False  # a linear filter in Python: no real-time core, no status

    def _simulate(  # a Python filter: no status to report
        self, t: ArrayLike | None, x: ArrayLike
    ) -> FloatArray:
        """Output for the input samples x at uniform times t, from rest at x[0].

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), uniform (a relative spread up to 1e-3).
        x : array_like of float, shape (n,)
            Input samples.

        Returns
        -------
        numpy.ndarray of float, shape (n,)
            Output samples.

        Raises
        ------
        ValueError
            t missing or not uniform, or a block that cannot be discretised at its step.
        """
        x = np.asarray(x, dtype=float)
        if x.size == 0:
            return x.copy()
        b, a = self._coefficients(sample_time(t))
        return apply_filter(b, a, x)

    def reset(self) -> None:
        """Forget the streaming state: the next step starts at rest at its input."""
        self._rest: float | None = None  # the first input (the block starts at rest there)
        self._z: np.ndarray | None = None  # filter state, once the sample time is known
        self._cache: tuple[float | None, Any, Any] = (None, None, None)

    def step(self, x: float, dt: float = 0.0) -> float:
        """One sample; dt > 0 after the first. A dt that changes re-discretises the block
        (the filter state is carried over as is: exact for a constant dt).

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s), > 0 after the first.

        Returns
        -------
        float
            The output sample (x itself on the first).

        Raises
        ------
        ValueError
            dt not > 0 after the first sample.
        """
        from scipy.signal import lfilter, lfilter_zi

        dt = checked_dt(dt)
        x = float(x)
        if self._rest is None:
            self._rest = x
            return x
        if not dt > 0:
            raise ValueError(f"{type(self).__name__}.step needs dt > 0 after the first sample")
        if self._cache[0] != dt:
            b, a = self._coefficients(dt)
            self._cache = (dt, b, a)
        _, b, a = self._cache
        if self._z is None:
            self._z = lfilter_zi(b, a) * self._rest
        y, self._z = lfilter(b, a, [x], zi=self._z)
        return float(y[0])

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v:.6g}" for k, v in self._values.items())
        return f"{type(self).__name__}({inner})"


def apply_filter(b: np.ndarray, a: np.ndarray, x: np.ndarray, axis: int = 0) -> np.ndarray:
    """lfilter from rest at the first sample (steady state), along ``axis``."""
    from scipy.signal import lfilter, lfilter_zi

    x = np.asarray(x, dtype=float)
    zi = lfilter_zi(b, a)
    first = np.take(x, [0], axis=axis)
    shape = [1] * x.ndim
    shape[axis] = zi.size
    y, _ = lfilter(b, a, x, axis=axis, zi=zi.reshape(shape) * first)
    return y


class FirstOrderLag(LinearBlock):
    """1 / (time_constant s + 1): a first-order lag (s), unit static gain.

    Parameters
    ----------
    time_constant : float, default 0.05
        The lag's time constant (s), > 0.
    """

    param_names = ("time_constant",)
    _limits = {"time_constant": (0.0, math.inf)}

    def __init__(self, time_constant: float = 0.05):
        super().__init__(time_constant=time_constant)

    def transfer(self) -> tuple[list[float], list[float]]:
        """1 / (time_constant s + 1).

        Returns
        -------
        num, den : list of float
            Coefficients of the transfer function in s, highest power first.
        """
        return [1.0], [self._values["time_constant"], 1.0]

    def filter_coefficients(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """(b, a) for ``scipy.signal.lfilter`` at sample time dt (first-order hold, closed form).

        Parameters
        ----------
        dt : float
            Sample time (s), > 0.

        Returns
        -------
        b, a : numpy.ndarray of float
            Numerator and denominator in z^-1, a[0] = 1.
        """
        # exact for an input linear between samples: y_k = a y_k-1 + b0 u_k + b1 u_k-1
        r = dt / self._values["time_constant"]
        a = math.exp(-r)
        g = -math.expm1(-r) / r  # (1 - a) tau / dt, accurate for small r
        return np.array([1.0 - g, g - a]), np.array([1.0, -a])


class SecondOrderLag(LinearBlock):
    """w^2 / (s^2 + 2 damping w s + w^2), w = 2 pi frequency (Hz): a resonance or, damped
    beyond 1, two lags; unit static gain.

    Parameters
    ----------
    frequency : float, default 5.0
        Natural frequency (Hz), > 0.
    damping : float, default 0.7
        Damping ratio, > 0.
    """

    param_names = ("frequency", "damping")
    _limits = {"frequency": (0.0, math.inf), "damping": (0.0, math.inf)}

    def __init__(self, frequency: float = 5.0, damping: float = 0.7):
        super().__init__(frequency=frequency, damping=damping)

    def transfer(self) -> tuple[list[float], list[float]]:
        """w^2 / (s^2 + 2 damping w s + w^2), w = 2 pi frequency.

        Returns
        -------
        num, den : list of float
            Coefficients of the transfer function in s, highest power first.
        """
        w = 2.0 * math.pi * self._values["frequency"]
        return [w * w], [1.0, 2.0 * self._values["damping"] * w, w * w]

    def filter_coefficients(self, dt: float) -> tuple[np.ndarray, np.ndarray]:
        """(b, a) for ``scipy.signal.lfilter`` at sample time dt (first-order hold).

        Parameters
        ----------
        dt : float
            Sample time (s), > 0.

        Returns
        -------
        b, a : numpy.ndarray of float
            Numerator and denominator in z^-1, a[0] = 1.
        """
        # SciPy's first-order-hold construction (block matrix exponential) on the 2-state
        # model, with a small Taylor expm: cont2discrete's Pade expm costs ~1 ms per call
        w = 2.0 * math.pi * self._values["frequency"]
        em = np.zeros((4, 4))
        em[0, 1] = dt
        em[1, 0], em[1, 1], em[1, 2] = (
            -w * w * dt,
            -2.0 * self._values["damping"] * w * dt,
            (w * w * dt),
        )
        em[2, 3] = 1.0
        ms = _expm(em)
        ad = ms[:2, :2]
        bd = ms[:2, 2] - ms[:2, 3] + ad @ ms[:2, 3]
        dd = ms[0, 3]
        a1, a2 = -(ad[0, 0] + ad[1, 1]), ad[0, 0] * ad[1, 1] - ad[0, 1] * ad[1, 0]
        k = np.array([[-ad[1, 1], ad[0, 1]], [ad[1, 0], -ad[0, 0]]])
        b = np.array([dd, bd[0] + dd * a1, (k @ bd)[0] + dd * a2])
        return b, np.array([1.0, a1, a2])


def _expm(m: np.ndarray) -> np.ndarray:
    """exp(m) of a small matrix: scaling and squaring with an 18-term Taylor series."""
    norm = float(np.max(np.sum(np.abs(m), axis=1)))
    s = max(0, int(math.ceil(math.log2(norm))) + 1) if norm > 0 else 0
    a = m / 2.0**s
    out = np.eye(m.shape[0])
    term = np.eye(m.shape[0])
    for k in range(1, 19):
        term = term @ a / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


__all__ = [
    "FirstOrderLag",
    "LinearBlock",
    "SecondOrderLag",
    "apply_filter",
    "discretise",
    "sample_time",
]
