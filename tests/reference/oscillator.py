"""An independent reference for the HystereticOscillator: SciPy's DOP853 on the continuous
input (a random-phase multisine or a sine sweep), for identification tests and benchmarks.

Nothing here shares code with the C++ core: the right-hand side is written out again in
Python and integrated by ``scipy.integrate.solve_ivp`` (DOP853, at most dt / 20 per step,
rtol 1e-10) on the input as a function of continuous time.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

# The Bouc-Wen benchmark system (Noel and Schoukens, 2016): a softening loop,
# beta (gamma + delta) < 0, excited by a 5-150 Hz multisine sampled at 750 Hz.
BENCHMARK = dict(m=2.0, c=10.0, k=5e4, alpha=5e4, beta=1e3, gamma=0.8, delta=-1.1, nu=1.0)


@dataclass
class Multisine:
    """u(t) = sum_l a cos(2 pi l f0 t + phi_l) over the lines l with lo <= l f0 <= hi,
    f0 = fs / period (a whole number of samples per period), random phases, RMS ``rms``."""

    fs: float
    period: int
    lo: float
    hi: float
    rms: float
    seed: int

    def __post_init__(self):
        f0 = self.fs / self.period
        lines = np.arange(1, self.period // 2)
        self.lines = lines[(lines * f0 >= self.lo) & (lines * f0 <= self.hi)]
        rng = np.random.default_rng(self.seed)
        self.phases = rng.uniform(0.0, 2 * np.pi, self.lines.size)
        self.amplitude = self.rms * math.sqrt(2.0 / self.lines.size)
        self.omega = 2 * np.pi * f0 * self.lines

    def __call__(self, t):
        t = np.atleast_1d(np.asarray(t, dtype=float))
        return self.amplitude * np.cos(np.outer(t, self.omega) + self.phases).sum(axis=1)

    def scalar(self, t: float) -> float:
        return float(self.amplitude * np.cos(self.omega * t + self.phases).sum())

    def samples(self, periods: int) -> tuple[np.ndarray, np.ndarray]:
        t = np.arange(periods * self.period) / self.fs
        return t, self(t)


@dataclass
class Sweep:
    """u(t) = a sin(phase(t)), a linear sweep from f_lo to f_hi over the record's duration."""

    fs: float
    n: int
    f_lo: float
    f_hi: float
    amplitude: float

    def scalar(self, t: float) -> float:
        T = self.n / self.fs
        ph = 2 * math.pi * (self.f_lo * t + 0.5 * (self.f_hi - self.f_lo) * t * t / T)
        return self.amplitude * math.sin(ph)

    def samples(self) -> tuple[np.ndarray, np.ndarray]:
        t = np.arange(self.n) / self.fs
        return t, np.array([self.scalar(s) for s in t])


def simulate_reference(params: dict, force, t: np.ndarray, settle: float = 1e-8) -> np.ndarray:
    """Displacement at the times t (from rest at t[0]) for the force ``force.scalar(t)``.

    A record of several periods of a :class:`Multisine` is integrated period by period (the
    state carried over); once a period agrees with the one before to ``settle`` times the
    output range (the transient has died out: the response is periodic), the remaining
    periods are copies of it, which integrating them would reproduce to that tolerance
    (1e-8: above the ~1e-9 that restarting DOP853 at rtol 1e-10 leaves, far below the
    models' own discretisation error, ~1e-5 of the range, and the noise, 1e-3)."""
    d = getattr(force, "period", 0)
    if d and t.size > 2 * d and t.size % d == 0:
        return _periodic_reference(params, force, t, d, settle)
    return _integrate(params, force, t, (0.0, 0.0, 0.0))[0]


def _periodic_reference(params, force, t, d, settle):
    y = np.empty(t.size)
    state = (0.0, 0.0, 0.0)
    for p in range(t.size // d):
        span = t[p * d : (p + 1) * d + 1] if (p + 1) * d < t.size else None
        if span is None:  # the last period: integrate to its last sample
            span = t[p * d :]
        yy, state = _integrate(params, force, span, state)
        y[p * d : (p + 1) * d] = yy[:d]
        if p >= 1:
            gap = np.max(np.abs(y[p * d : (p + 1) * d] - y[(p - 1) * d : p * d]))
            if gap <= settle * np.ptp(y[: (p + 1) * d]):
                y[(p + 1) * d :] = np.tile(y[p * d : (p + 1) * d], t.size // d - p - 1)
                break
    return y


def _integrate(params: dict, force, t: np.ndarray, state0):
    """DOP853 over the times t from state0 at t[0]: (y at t, the state at t[-1])."""
    m, c, k = params["m"], params["c"], params["k"]
    alpha, beta, gamma, delta, nu = (params[n] for n in ("alpha", "beta", "gamma", "delta", "nu"))
    u = force.scalar

    def rhs(s, state):
        y, v, z = state
        az = abs(z)
        q = az ** (nu - 1.0) if nu != 1.0 else 1.0
        return (
            v,
            (u(s) - c * v - k * y - z) / m,
            alpha * v - beta * (gamma * abs(v) * q * z + delta * v * q * az),
        )

    dt = float(t[1] - t[0])
    sol = solve_ivp(
        rhs,
        (float(t[0]), float(t[-1])),
        tuple(state0),
        method="DOP853",
        t_eval=t,
        max_step=dt / 20.0,
        rtol=1e-10,
        atol=1e-14,
    )
    if not sol.success:
        raise RuntimeError(f"reference integration failed: {sol.message}")
    return sol.y[0], sol.y[:, -1]
