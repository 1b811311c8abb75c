"""Motor models between a command and the plant input (C++ core: plant/motor.hpp)."""

from __future__ import annotations

import inspect
from typing import Any

import numpy as np

from .._util.args import core_errors_as, number
from .._util.arrays import as_timed_signal, checked_dt
from .._util.param_table import TABLE, table_defaults
from .._util.pyobject import PythonObject, bound_attribute
from .._util.typing import ArrayLike
from .._util.units import warn_unit_slips
from ..simulation_result import SimulationResult
from ..status import Status
from . import _bound as core


def _motor_params(kind, who: str, arguments: dict):
    """MotorParams of ``kind`` from a constructor's ``locals()`` (each argument names a field),
    each checked to be a number."""
    p = core.MotorParams()
    p.kind = kind
    for name, value in arguments.items():
        if name != "cls":
            setattr(p, name, number(who, name, value))
    return p


def _motor_from_fields(fields: dict) -> Motor:
    """A motor whose parameter struct has ``fields``."""
    p = core.MotorParams()
    for key, value in fields.items():
        setattr(p, key, value)
    return Motor(p)


# the fields of core.MotorParams (its readable and writable properties)
_FIELDS = tuple(
    name
    for name, d in vars(core.MotorParams).items()
    if isinstance(d, property) and d.fset is not None
)


class Motor(PythonObject, core.Motor):  # type: ignore[misc]
    """A drive between the controller and the proximal pulley.

    ``Motor.position(...)``: a position-controlled motor seen as a second-order lag
    q'' = w^2 (q_cmd - q) - 2 zeta w q' (w = 2 pi bandwidth_hz) with speed and acceleration
    limits; it starts at rest at the first command.
    ``Motor.torque(...)``: J q'' + b q' = sat(tau_cmd, max_torque) + tau_tendons, for
    controllers that command torque; the plant supplies the tendon torque on the pulley. It
    starts at rest at q = 0.

    With ``integral_time`` T_i > 0 the position servo is a PID loop, as servo amplifiers that
    cascade a PI velocity loop inside the position loop are:
    q'' = w^2 [(q_cmd - q) + z / T_i] - 2 zeta w q' with z' = q_cmd - q, so a constant load
    torque leaves no steady position error (the PD servo, T_i = 0, yields tau / (J w^2)).

    Drive-train effects (off by default): ``coulomb_friction`` (N m) and ``viscous_friction``
    (N m s/rad) on the motor shaft, and ``gear_backlash`` (rad, total play) between the shaft
    and the proximal pulley. A position motor feels torques (the tendons' and its friction)
    only through its reflected ``inertia`` (kg m^2; 0, the default, is the ideal lag): then
    q'' = w^2 (q_cmd - q) - 2 zeta w q' + (tau_tendons - b_m q' - tau_c sgn q') / J.
    The plant is driven by the pulley angle; a motor encoder reads the shaft
    (``SimulationResult.q_motor``).

    Parameters
    ----------
    params : MotorParams
        The C++ parameter struct; build a motor with :meth:`position` or :meth:`torque`.

    Raises
    ------
    ValueError
        A parameter the C++ core rejects (the message names it).
    """

    def __init__(self, params: core.MotorParams):
        kind = "position" if params.kind == core.MotorKind.Position else "torque"
        with core_errors_as(f"Motor.{kind}"):
            core.Motor.__init__(self, params)  # validates, naming the parameter
        warn_unit_slips(f"Motor.{kind}", params)

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject): the constructor's argument, the C++ struct
        return {"params": self._struct()}

    def _recipe(self):
        # pickled as its parameters: an equal motor at rest (tendonsheath._util.pyobject)
        p = self._struct()
        fields = {k: getattr(p, k) for k in _FIELDS if hasattr(p, k)}
        return _motor_from_fields, (fields,)

    @classmethod
    @table_defaults(core.MotorParams)
    def position(  # type: ignore[override]
        cls,
        bandwidth_hz: float = TABLE,
        damping: float = TABLE,
        max_speed: float = TABLE,
        max_accel: float = TABLE,
        inertia: float = TABLE,
        coulomb_friction: float = TABLE,
        viscous_friction: float = TABLE,
        gear_backlash: float = TABLE,
        integral_time: float = TABLE,
    ) -> Motor:
        """A position-controlled motor (a second-order lag on the commanded angle).

        With ``integral_time`` T_i > 0 the loop has integral action (a PID servo):
        q'' = w^2 [(q_cmd - q) + z / T_i] - 2 zeta w q' + ..., z' = q_cmd - q; the integral is
        held while the speed or acceleration limit cuts the motion (anti-windup). The loop
        s^3 + 2 zeta w s^2 + w^2 s + w^2 / T_i is stable for T_i > 1 / (2 zeta w).

        Returns
        -------
        Motor
            The motor, at rest at its first command.

        Raises
        ------
        ValueError
            A parameter out of range (the message names it).
        """
        return cls(_motor_params(core.MotorKind.Position, "Motor.position", locals()))

    @classmethod
    @table_defaults(core.MotorParams)
    def torque(
        cls,
        inertia: float = 1e-2,
        viscous: float = TABLE,
        max_torque: float = TABLE,
        max_speed: float = TABLE,
        coulomb_friction: float = TABLE,
        gear_backlash: float = TABLE,
    ) -> Motor:
        """A torque-commanded motor: J q'' + b q' = sat(tau_cmd, max_torque) + tau_tendons.

        Parameters
        ----------
        inertia : float, default 1e-2
            Rotor inertia J (kg m^2), > 0.

        Returns
        -------
        Motor
            The motor, at rest at q = 0.

        Raises
        ------
        ValueError
            A parameter out of range (the message names it).
        """
        return cls(_motor_params(core.MotorKind.Torque, "Motor.torque", locals()))

    @property
    def kind(self) -> str:
        """The kind: "position" or "torque"."""
        return "position" if self._struct().kind == core.MotorKind.Position else "torque"

    def _struct(self) -> core.MotorParams:
        """The C++ parameter struct (the bound class's ``params``)."""
        return bound_attribute(self, "params")

    @property
    def params(self) -> dict:  # type: ignore[override]
        """The motor's parameters by the names of :meth:`position` or :meth:`torque`."""
        p = self._struct()
        return {k: getattr(p, k) for k in inspect.signature(getattr(Motor, self.kind)).parameters}

    @property
    def integral(self) -> float:  # type: ignore[override]
        """The position servo's integral of the error, z = int (q_cmd - q) dt (rad s); 0
        without integral action."""
        return core.Motor.integral(self)

    def engine(self) -> core.Motor:
        """A copy of the C++ motor engine this motor built (and validated) once, at rest: what a
        plant steps between command and pulley, and what :func:`tendonsheath.bench.run` runs.

        Returns
        -------
        tendonsheath._core.Motor
            An independent engine (stepping it leaves this motor's own state alone).
        """
        copy = core.Motor(self)
        copy.reset()
        return copy

    def reset(self) -> None:
        """Back to rest: the next step starts afresh."""
        core.Motor.reset(self)

    def step(self, command: float, dt: float, tau_ext: float = 0.0) -> float:
        """Advance by dt; returns the motor position (rad).

        Parameters
        ----------
        command : float
            Commanded angle (rad, position kind) or torque (N m, torque kind).
        dt : float
            Time step (s), >= 0.
        tau_ext : float, default 0.0
            External torque on the pulley from the tendons (N m).

        Returns
        -------
        float
            The pulley angle (rad).
        """
        dt = checked_dt(dt)
        return core.Motor.step(self, float(command), float(dt), float(tau_ext))

    def status(self) -> Status:
        """The last step's :class:`~tendonsheath.Status` (held, clamped, saturated).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        return Status(core.Motor.status(self))

    def simulate(self, t: ArrayLike, command: ArrayLike) -> SimulationResult:
        """Motor position for a command sequence, unloaded (starts from rest).

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        command : array_like of float, shape (n,)
            Commands (rad or N m, by kind).

        Returns
        -------
        SimulationResult
            The pulley angle at each sample (rad), shape (n,), as an array; ``t``, ``input``
            (the command), ``success``/``message`` and ``.plot()`` like every ``simulate``.

        Raises
        ------
        ValueError
            t missing, or samples not finite or of different lengths.
        """
        ts, us = as_timed_signal(t, command, "command", "Motor.simulate")
        m = core.Motor(self._struct())
        out = np.empty_like(us)
        for k in range(us.size):
            out[k] = m.step(us[k], 0.0 if k == 0 else ts[k] - ts[k - 1], 0.0)
        return SimulationResult(out, t=ts, input=us)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v:.6g}" for k, v in self.params.items())
        return f"Motor.{self.kind}({inner})"


__all__ = ["Motor"]
