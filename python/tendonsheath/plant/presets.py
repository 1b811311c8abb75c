"""Plant presets: the physical effects a real drive has beyond the quasi-static capstan pair.

A quasi-static pull-pull pair with no load *is* a classic backlash, so a compensator built on a
backlash model would be judged inside its own model class. The ``realistic`` preset turns on
what the seed papers' rigs have and no compensator models:

=====================  =====================  ==================================================
effect                 value                  reason (rig of the seed papers)
=====================  =====================  ==================================================
distal joint           J_d = 2e-5 kg m^2,     a 15 mm aluminium pulley with an encoder disk (Do
                       c_d = 2e-3 N m s/rad   et al.): rings at about 40 Hz after a reversal
sheath viscosity       8 N s/m^2              viscous drag of the lubricated coil: about 20 % of
                                              the Coulomb friction at 1 Hz, as much at 5 Hz
                                              (measured drives widen their loops with rate)
tendon creep           8 % of EA relaxing,    polymer-coated steel rope: a standard linear solid
                       tau = 1.5 s            that creeps under a held load
unequal pair           sheath 2 friction      two sheaths and two tendons are never identical:
                       +15 %, tendon 2 EA     manufacturing tolerances
                       -10 %
motor friction         0.01 N m Coulomb,      geared DC motor (Faulhaber 3863 with a 14:1
                       1e-3 N m s/rad         gearhead, Lau et al.)
gear backlash          0.5 deg                the gearhead's output play
servo compliance       reflected inertia      the position loop feels the tendons' torque
                       1e-4 kg m^2            through the rotor and gear inertia
position servo         "pid": integral time   servo amplifiers cascade a PI velocity loop inside
(default "pid")        T_i = 5 / w_n          the position loop (Faulhaber Motion Controllers,
                                              Maxon EPOS, Copley): a constant load leaves no
                                              steady error; G. Ellis, Control System Design
                                              Guide, puts the integral break well below the
                                              bandwidth (here a fifth of w_n = 2 pi f_n).
                       "pd": no integral      the yielding servo: a torque tau deflects it by
                                              tau / (J w^2) (stiffness 14 N m/rad at 60 Hz)
=====================  =====================  ==================================================

These values are choices within the ranges of such rigs, not measurements; each is an argument
so a study can vary it. The default servo is the PID one because that is what the amplifiers
of such rigs run (the provenance above), whatever either servo does to a benchmark figure.
Example::

    plant = ts.PullPullPlant(route, pretension=20.0, **presets.realistic_plant(friction=0.1,
                             stiffness=5e3), motor=presets.realistic_motor(bandwidth_hz=60))
"""

from __future__ import annotations

import inspect
import math
import numbers
from typing import Any

from .motor import Motor
from .population import (
    PRIORS,
    PlantDraw,
    random_continuum_plant,
    random_realistic_plant,
    random_single_tendon_plant,
)

#: The realistic effects, relative where a plant's own value sets the scale.
REALISTIC = {
    "distal_inertia": 2e-5,
    "distal_damping": 2e-3,
    "sheath_viscosity": 8.0,
    "relaxation_fraction": 0.08,
    "relaxation_time": 1.5,
    "friction2_ratio": 1.15,
    "stiffness2_ratio": 0.9,
    "motor_inertia": 1e-4,
    "motor_coulomb_friction": 0.01,
    "motor_viscous_friction": 1e-3,
    "gear_backlash": math.radians(0.5),
    "servo_integral_ratio": 5.0,
}

#: The position servos :func:`realistic_motor` offers.
SERVOS = ("pid", "pd")


def realistic_plant(
    friction: float = 0.1, stiffness: float = 2.4e4, **overrides: Any
) -> dict[str, Any]:
    """Keyword arguments for :class:`~tendonsheath.PullPullPlant` (or ``ContinuumPlant``) that
    turn the realistic effects on: ``friction`` and ``stiffness`` (tendon 1) with sheath 2 and
    tendon 2 off by the preset ratios, distal joint inertia and damping, sheath viscosity and
    tendon creep. ``overrides`` replace any of the returned values (e.g. ``distal_inertia=0``).

    Parameters
    ----------
    friction : float, default 0.1
        Friction coefficient of sheath 1.
    stiffness : float, default 2.4e4
        Axial stiffness EA of tendon 1 (N).
    **overrides
        Replacements for any of the returned keywords.

    Returns
    -------
    dict
        Keyword arguments for the plant: friction, stiffness, friction2, stiffness2,
        distal_inertia, distal_damping, sheath_viscosity, relaxation_fraction,
        relaxation_time.

    Raises
    ------
    TypeError
        An override that is not one of the returned keywords.
    """
    kwargs = {
        "friction": float(friction),
        "stiffness": float(stiffness),
        "friction2": REALISTIC["friction2_ratio"] * float(friction),
        "stiffness2": REALISTIC["stiffness2_ratio"] * float(stiffness),
        "distal_inertia": REALISTIC["distal_inertia"],
        "distal_damping": REALISTIC["distal_damping"],
        "sheath_viscosity": REALISTIC["sheath_viscosity"],
        "relaxation_fraction": REALISTIC["relaxation_fraction"],
        "relaxation_time": REALISTIC["relaxation_time"],
    }
    unknown = set(overrides) - set(kwargs)
    if unknown:
        raise TypeError(
            f"realistic_plant: unknown override(s) {sorted(unknown)}; known: {sorted(kwargs)}"
        )
    kwargs.update(overrides)
    return kwargs


def realistic_motor(kind: str = "position", *, servo: str = "pid", **kwargs: float) -> Motor:
    """A :class:`~tendonsheath.Motor` with the realistic drive train: Coulomb and viscous
    friction, gear backlash and (position kind) a servo that feels the tendons' torque.

    ``kind="position"``: the other keywords go to :meth:`Motor.position` (e.g. ``bandwidth_hz``,
    ``damping``); ``servo="pid"`` (the default) gives its loop integral action with
    ``integral_time = REALISTIC["servo_integral_ratio"] / (2 pi bandwidth_hz)``, ``servo="pd"``
    none (the servo yields to a load). ``kind="torque"``: the keywords go to
    :meth:`Motor.torque` (``inertia``, ``viscous``, ``max_torque``); it has no position servo.
    Keywords given override the preset's (an explicit ``integral_time`` the servo's).

    Parameters
    ----------
    kind : {"position", "torque"}, default "position"
        The motor's kind.
    servo : {"pid", "pd"}, default "pid"
        The position servo: with integral action (what servo amplifiers run) or without.
    **kwargs
        Keywords of :meth:`Motor.position` or :meth:`Motor.torque`; they override the preset.

    Returns
    -------
    Motor
        The motor.

    Raises
    ------
    ValueError
        An unknown kind or servo, or an invalid motor parameter.
    TypeError
        A keyword the chosen kind does not take.
    """
    if servo not in SERVOS:
        raise ValueError(f"realistic_motor: servo must be 'pid' or 'pd' (got {servo!r})")
    if kind == "position":
        base = {
            "inertia": REALISTIC["motor_inertia"],
            "coulomb_friction": REALISTIC["motor_coulomb_friction"],
            "viscous_friction": REALISTIC["motor_viscous_friction"],
            "gear_backlash": REALISTIC["gear_backlash"],
            **_servo_integral(servo, kwargs),
        }
        return Motor.position(**{**base, **kwargs})
    if kind == "torque":
        base = {
            "coulomb_friction": REALISTIC["motor_coulomb_friction"],
            "gear_backlash": REALISTIC["gear_backlash"],
        }
        return Motor.torque(**{**base, **kwargs})
    raise ValueError(f"realistic_motor: kind must be 'position' or 'torque' (got {kind!r})")


def _servo_integral(servo: str, kwargs: dict[str, Any]) -> dict[str, float]:
    """``{"integral_time": T_i}`` of the "pid" servo at the bandwidth of ``kwargs`` (that of
    :meth:`Motor.position` when not given); empty for "pd", with an explicit integral_time, or
    when the bandwidth is no positive number (Motor.position then names it)."""
    if servo != "pid" or "integral_time" in kwargs:
        return {}
    bandwidth = _given_or_default(kwargs, "bandwidth_hz")
    damping = _given_or_default(kwargs, "damping")
    if bandwidth is None or not 0.0 < bandwidth < math.inf:
        return {}
    ratio = REALISTIC["servo_integral_ratio"]
    if damping is not None and 0.0 < damping <= 0.5 / ratio:
        raise ValueError(
            f"realistic_motor: servo='pid' (integral time {ratio:g} / w_n) is stable only for "
            f"damping > {0.5 / ratio:g} (got {damping:g}); use servo='pd' or give integral_time"
        )
    return {"integral_time": ratio / (2.0 * math.pi * bandwidth)}


def _given_or_default(kwargs: dict[str, Any], name: str) -> float | None:
    """A :meth:`Motor.position` argument as given in ``kwargs`` or its default; None when it
    is no number (Motor.position then names it)."""
    value = kwargs.get(name, inspect.signature(Motor.position).parameters[name].default)
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return None
    return float(value)


__all__ = [
    "PRIORS",
    "REALISTIC",
    "SERVOS",
    "PlantDraw",
    "random_continuum_plant",
    "random_realistic_plant",
    "random_single_tendon_plant",
    "realistic_motor",
    "realistic_plant",
]
