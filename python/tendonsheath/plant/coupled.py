"""Coupled joints (a cable-driven wrist): each joint a physics plant of its own, and the cables
of some joints running over idler pulleys on the axes of others.

When joint j turns by y_j, a cable of joint i that wraps an idler of radius r_c on joint j's
axis lengthens on one side and shortens on the other by r_c y_j; with joint i's distal pulley
(radius r_d) free to turn, that pulley turns by (r_c / r_d) y_j more than its own drive alone
would turn it. So the joint angles are y = q + K y, q each plant's own output and
K[i, j] = r_c / r_d (signed by the wrap's direction, zero diagonal): y = (I - K)^-1 q.

The coupling is kinematic (the cables' geometry); each joint's transmission (friction,
backlash, creep, distal dynamics) is its own plant's. The joints' angles are read by
``sensors`` (one :class:`~tendonsheath.Sensor` per joint, or None).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._util.arrays import checked_dt
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike, FloatArray
from .sensor import Sensor


def _coupling_matrix(ratios: ArrayLike, joints: int, owner: str) -> FloatArray:
    """A checked (joints x joints) coupling matrix: finite, zero diagonal, I - K invertible."""
    k = np.array(ratios, dtype=np.float64)
    if k.shape != (joints, joints):
        raise ValueError(
            f"{owner}: the coupling must be a {joints} x {joints} matrix (got shape {k.shape})"
        )
    for (i, j), c in np.ndenumerate(k):  # the C++ CoupledFeedforward's rule and messages
        if not math.isfinite(c):
            raise ValueError(f"{owner}: coupling[{i}][{j}] must be finite (got {c:g})")
        if i == j and c != 0.0:
            raise ValueError(
                f"{owner}: the coupling's diagonal must be zero (a joint's own gain is its "
                f"model's; got coupling[{i}][{i}] = {c:g})"
            )
    if abs(np.linalg.det(np.eye(joints) - k)) < 1e-9:
        raise ValueError(f"{owner}: I - coupling is singular (the joints' angles are undefined)")
    return k


def _joint_matrix(values: ArrayLike, joints: int, name: str, owner: str) -> FloatArray:
    """Samples of ``joints`` signals as an (n, joints) float array (checked finite)."""
    a = np.asarray(values, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != joints:
        raise ValueError(
            f"{owner}: {name} must have shape (n, {joints}), one column per joint (got {a.shape})"
        )
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{owner}: {name} must be finite")
    return np.ascontiguousarray(a)


@dataclass(frozen=True)
class CoupledSimulation:
    """A run of a :class:`CoupledPlant`: arrays of shape (n, joints). Like a single plant's
    :class:`~tendonsheath.SimulationResult` it also names its command ``input`` and its q_out
    ``output``.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times (s), shape (n,).
    command : numpy.ndarray
        The commands (rad).
    q_in : numpy.ndarray
        Each drive's proximal pulley angle (after its motor, if any).
    drive : numpy.ndarray
        Each plant's own output q (what its pulley would turn without the coupling).
    q_out : numpy.ndarray
        The joint angles y = (I - K)^-1 q.
    measured : numpy.ndarray
        The joint angles as the sensors read them (q_out where a joint has no sensor).
    """

    t: FloatArray
    command: FloatArray
    q_in: FloatArray
    drive: FloatArray
    q_out: FloatArray
    measured: FloatArray

    @property
    def input(self) -> FloatArray:
        """The commands (= ``command``), as every result names what the run was given."""
        return self.command

    @property
    def output(self) -> FloatArray:
        """The joint angles (= ``q_out``), as every result names what the run produced."""
        return self.q_out


class CoupledPlant(PythonObject):
    """Joints driven by their own physics plants, coupled through their cables' idlers.

    Parameters
    ----------
    plants : sequence of plants
        One plant per joint (e.g. :class:`~tendonsheath.PullPullPlant`), each with its own
        route, effects and motor; their own sensors are not used.
    coupling : array_like, shape (joints, joints)
        K[i, j] = r_c / r_d: the idler radius on joint j's axis that joint i's cable wraps,
        over joint i's distal pulley radius (signed; zero diagonal).
    sensors : sequence of Sensor or None, optional
        One per joint (None: that joint read exactly); None: all exact.

    Raises
    ------
    ValueError
        No plants, a coupling of the wrong shape, not finite, with a non-zero diagonal or
        I - K singular, or a sensors list of the wrong length.
    TypeError
        A sensor that is not a :class:`~tendonsheath.Sensor`.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    plants: list
    coupling: FloatArray
    sensors: list[Sensor | None]

    def __init__(
        self,
        plants: Sequence,
        coupling: ArrayLike,
        sensors: Sequence[Sensor | None] | None = None,
    ):
        self.plants = list(plants)
        if not self.plants:
            raise ValueError("CoupledPlant: give at least one plant")
        n = len(self.plants)
        self.coupling = _coupling_matrix(coupling, n, "CoupledPlant")
        self.sensors = [None] * n if sensors is None else list(sensors)
        if len(self.sensors) != n:
            raise ValueError(f"CoupledPlant: {n} plants but {len(self.sensors)} sensors")
        for s in self.sensors:
            if s is not None and not isinstance(s, Sensor):
                raise TypeError(
                    f"CoupledPlant: a sensor must be a tendonsheath.Sensor or None "
                    f"(got {type(s).__name__})"
                )
        self._solve = np.linalg.inv(np.eye(n) - self.coupling)

    @property
    def joints(self) -> int:
        """The number of joints."""
        return len(self.plants)

    def joint_angles(self, drive: ArrayLike) -> FloatArray:
        """The joint angles y = (I - K)^-1 q of the drives' outputs q.

        Parameters
        ----------
        drive : array_like of float, shape (joints,) or (n, joints)
            The drives' own outputs q.

        Returns
        -------
        numpy.ndarray of float
            The joint angles, shaped as drive.
        """
        q = np.asarray(drive, dtype=np.float64)
        return q @ self._solve.T

    def simulate(self, t: ArrayLike, command: ArrayLike) -> CoupledSimulation:
        """Every drive from rest on its commands, then the coupling and the sensors (each
        sensor restarted from its seed).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing.
        command : array_like of float, shape (n, joints)
            One column of commands per joint (as each plant's ``simulate`` takes them).

        Returns
        -------
        CoupledSimulation
            The commands, drive inputs and outputs, joint angles and readings.

        Raises
        ------
        ValueError
            Commands of the wrong shape or not finite, or what a plant's simulate rejects.
        """
        ts = np.asarray(t, dtype=np.float64)
        u = _joint_matrix(command, self.joints, "command", "CoupledPlant.simulate")
        if ts.shape != (u.shape[0],):
            raise ValueError(
                f"CoupledPlant.simulate: t has {ts.size} samples, the commands {u.shape[0]}"
            )
        runs = [p.simulate(ts, u[:, i]) for i, p in enumerate(self.plants)]
        drive = np.column_stack([np.asarray(r, dtype=np.float64) for r in runs])
        q_in = np.column_stack([np.asarray(r.q_in, dtype=np.float64) for r in runs])
        y = self.joint_angles(drive)
        measured = y.copy()
        for i, s in enumerate(self.sensors):
            if s is not None:
                s.reset()
                measured[:, i] = s.measure(y[:, i], t=ts)
        return CoupledSimulation(ts, u, q_in, drive, y, measured)

    def reset(self) -> None:
        """Every drive and sensor back to rest."""
        for p in self.plants:
            p.reset()
        for s in self.sensors:
            if s is not None:
                s.reset()

    def step(self, command: ArrayLike, dt: float = 0.0) -> FloatArray:
        """One sample of every drive; returns the joint angles (shape (joints,)), exact (read
        them with :meth:`measure`).

        Parameters
        ----------
        command : array_like of float, shape (joints,)
            One command per joint.
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        numpy.ndarray of float, shape (joints,)
            The joint angles.
        """
        dt = checked_dt(dt)
        u = np.asarray(command, dtype=np.float64).reshape(-1)
        if u.size != self.joints:
            raise ValueError(f"CoupledPlant.step: {self.joints} commands needed (got {u.size})")
        q = np.array([p.step(float(c), dt) for p, c in zip(self.plants, u, strict=True)])
        return self.joint_angles(q)

    def measure(self, angles: ArrayLike, dt: float = 0.0) -> FloatArray:
        """The sensors' readings of one sample of joint angles (exact where no sensor).

        Parameters
        ----------
        angles : array_like of float, shape (joints,)
            Joint angles (from :meth:`step`).
        dt : float, default 0.0
            Time since the previous reading (s).

        Returns
        -------
        numpy.ndarray of float, shape (joints,)
            The readings.
        """
        y = np.asarray(angles, dtype=np.float64).reshape(-1)
        pairs = zip(self.sensors, y, strict=True)
        return np.array([v if s is None else s.measure(float(v), dt=dt) for s, v in pairs])


__all__ = ["CoupledPlant", "CoupledSimulation"]
