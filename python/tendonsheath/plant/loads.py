"""Distal load laws of the plants.

Rotary loads act on the distal pulley of a :class:`~tendonsheath.PullPullPlant` (or on the
bending angle of a :class:`~tendonsheath.ContinuumPlant`); a positive torque resists a positive
output angle q_out:

* ``ConstantTorque(tau)``: tau_L = tau (N m).
* ``TorsionalSpring(k, preload=0)``: tau_L = preload + k q_out (k in N m/rad).
* ``SpringDamper(k, c)``: tau_L = k q_out + c dq_out/dt (c in N m s/rad; needs a time vector).

Linear loads act on the distal end of a :class:`~tendonsheath.SingleTendonPlant` and pull
against the tendon (the tendon tension at rest equals the load at x_out = 0):

* ``ConstantForce(F)``: F_L = F (N, > 0).
* ``LinearSpring(k)``: F_L = k x_out (N/m); the tendon starts at zero tension.
* ``SpringPreload(k, F0)``: F_L = F0 + k x_out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._util.args import number


def _finite(value, name, cls, minimum=None, strict=False):
    v = number(cls, name, value)
    if not math.isfinite(v):
        raise ValueError(f"{cls}: {name} must be finite (got {value!r})")
    if minimum is not None and (v < minimum or (strict and v <= minimum)):
        op = ">" if strict else ">="
        raise ValueError(f"{cls}: {name} must be {op} {minimum:g} (got {value!r})")
    return v


@dataclass(frozen=True)
class ConstantTorque:
    """A constant torque tau (N m) at the distal pulley, resisting positive rotation.

    Parameters
    ----------
    tau : float
        The torque (N m), finite.

    Raises
    ------
    ValueError
        tau not finite.
    """

    tau: float

    def __post_init__(self):
        object.__setattr__(self, "tau", _finite(self.tau, "tau", "ConstantTorque"))

    def rotary(self) -> tuple[float, float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (tau0, k, c): tau_L = tau0 + k q_out + c dq_out/dt, as the C++ plant takes it.
        """
        return self.tau, 0.0, 0.0


@dataclass(frozen=True)
class TorsionalSpring:
    """tau_L = preload + k q_out: a torsional spring k (N m/rad) at the distal pulley.

    Parameters
    ----------
    k : float
        Stiffness (N m/rad), >= 0.
    preload : float, default 0.0
        Torque at q_out = 0 (N m).

    Raises
    ------
    ValueError
        A value not finite, or k < 0.
    """

    k: float
    preload: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "k", _finite(self.k, "k", "TorsionalSpring", 0.0))
        object.__setattr__(self, "preload", _finite(self.preload, "preload", "TorsionalSpring"))

    def rotary(self) -> tuple[float, float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (tau0, k, c): tau_L = tau0 + k q_out + c dq_out/dt, as the C++ plant takes it.
        """
        return self.preload, self.k, 0.0


@dataclass(frozen=True)
class SpringDamper:
    """tau_L = k q_out + c dq_out/dt (k in N m/rad, c in N m s/rad).

    Parameters
    ----------
    k : float
        Stiffness (N m/rad), >= 0.
    c : float
        Damping (N m s/rad), >= 0.

    Raises
    ------
    ValueError
        A value not finite or negative.
    """

    k: float
    c: float

    def __post_init__(self):
        object.__setattr__(self, "k", _finite(self.k, "k", "SpringDamper", 0.0))
        object.__setattr__(self, "c", _finite(self.c, "c", "SpringDamper", 0.0))

    def rotary(self) -> tuple[float, float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (tau0, k, c): tau_L = tau0 + k q_out + c dq_out/dt, as the C++ plant takes it.
        """
        return 0.0, self.k, self.c


@dataclass(frozen=True)
class ConstantForce:
    """A constant force F > 0 (N) pulling the distal end of a single tendon.

    Parameters
    ----------
    F : float
        The force (N), > 0.

    Raises
    ------
    ValueError
        F not finite or not > 0.
    """

    F: float

    def __post_init__(self):
        object.__setattr__(self, "F", _finite(self.F, "F", "ConstantForce", 0.0, strict=True))

    def linear(self) -> tuple[float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (F0, k): F_L = F0 + k x_out, as the C++ plant takes it.
        """
        return self.F, 0.0


@dataclass(frozen=True)
class LinearSpring:
    """F_L = k x_out: a spring k > 0 (N/m) on the distal end, relaxed at x_out = 0.

    Parameters
    ----------
    k : float
        Stiffness (N/m), > 0.

    Raises
    ------
    ValueError
        k not finite or not > 0.
    """

    k: float

    def __post_init__(self):
        object.__setattr__(self, "k", _finite(self.k, "k", "LinearSpring", 0.0, strict=True))

    def linear(self) -> tuple[float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (F0, k): F_L = F0 + k x_out, as the C++ plant takes it.
        """
        return 0.0, self.k


@dataclass(frozen=True)
class SpringPreload:
    """F_L = F0 + k x_out: a preloaded spring (k in N/m, F0 in N).

    Parameters
    ----------
    k : float
        Stiffness (N/m), >= 0.
    F0 : float
        Force at x_out = 0 (N).

    Raises
    ------
    ValueError
        A value not finite, or k < 0.
    """

    k: float
    F0: float

    def __post_init__(self):
        object.__setattr__(self, "k", _finite(self.k, "k", "SpringPreload", 0.0))
        object.__setattr__(self, "F0", _finite(self.F0, "F0", "SpringPreload"))

    def linear(self) -> tuple[float, float]:
        """The load law's coefficients.

        Returns
        -------
        tuple of float
            (F0, k): F_L = F0 + k x_out, as the C++ plant takes it.
        """
        return self.F0, self.k


RotaryLoad = ConstantTorque | TorsionalSpring | SpringDamper
LinearLoad = ConstantForce | LinearSpring | SpringPreload

__all__ = [
    "ConstantForce",
    "ConstantTorque",
    "LinearLoad",
    "LinearSpring",
    "RotaryLoad",
    "SpringDamper",
    "SpringPreload",
    "TorsionalSpring",
]
