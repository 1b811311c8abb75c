"""The one rule for "did you mean degrees / mm / ms?": an angle, a length or a time far past its
physical range was most likely given in the smaller unit (degrees for rad, mm for m, ms for s).
A :class:`UnitWarning` names the entry point, the argument, the bound and its reason, and the
value converted from the smaller unit. Every entry point that takes such a quantity calls
:func:`warn_if_unit_slip` (a value), :func:`warn_unit_slips` (a C++ parameter struct: its
table's units say which fields are angles, lengths or times) or one of the named quantities
below; ``tests/test_units.py`` walks them.

And the check of a curve angle given to a setter outside real time (finite, >= 0).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import Any

from .args import caller_outside_package


class UnitWarning(UserWarning):
    """An angle, a length or a time far outside its physical range, most likely given in
    degrees, mm or ms where rad, m or s are meant; the message names the bound, its reason and
    the value converted from the smaller unit."""


@dataclass(frozen=True)
class Quantity:
    """A kind of quantity with a plausible bound: past it, the value was most likely given in
    ``slip`` (a unit ``factor`` times the SI one).

    Parameters
    ----------
    unit : str
        The SI unit the library takes ("rad", "m", "s").
    bound : float
        The largest plausible magnitude, in ``unit``.
    reason : str
        Why no real value goes past the bound.
    slip : str
        The smaller unit a user most likely gave ("deg", "mm", "ms").
    slip_name : str
        Its name in words ("degrees").
    factor : float
        One ``slip`` in ``unit``.
    """

    unit: str
    bound: float
    reason: str
    slip: str
    slip_name: str
    factor: float


_DEG = ("deg", "degrees", math.pi / 180)
_MM = ("mm", "millimetres", 1e-3)
_MS = ("ms", "milliseconds", 1e-3)

# Spec section 1: the total curve angle of an endoscope's sheath lies in 0 to 4 pi (two coils).
CURVE_ANGLE = Quantity(
    "rad", 4 * math.pi, "4 pi, two full coils: the most an endoscope's sheath takes", *_DEG
)
# A distal joint (a wrist, a bending section) turns less than a full turn either way.
JOINT_ANGLE = Quantity("rad", 2 * math.pi, "a full turn: a distal joint turns less", *_DEG)
# A play, a dead band, a correction's or a sensor's noise: a fraction of a turn.
ANGLE = Quantity("rad", 2 * math.pi, "a full turn", *_DEG)
# A sensed curve angle's noise of 30 degrees senses nothing.
ANGLE_NOISE = Quantity(
    "rad", 0.5, "0.5 rad, about 30 deg: a shape sensor that noisy senses nothing", *_DEG
)
# Endoscopes and catheters are 1 to 3 m long.
LENGTH = Quantity("m", 10.0, "10 m: longer than any endoscope's or catheter's sheath", *_MM)
# A pulley's radius, a tendon's offset, a bending section: centimetres.
SMALL_LENGTH = Quantity(
    "m", 0.5, "0.5 m: a pulley, a tendon offset or a bending section is cm", *_MM
)
# A lag's time constant, a loop's integral time: well under a second for these drives.
TIME = Quantity("s", 10.0, "10 s: the drive's lags and loop times are below a second", *_MS)
# A delay, a latency, a sample step: milliseconds.
DELAY = Quantity("s", 1.0, "1 s: a delay, a latency or a sample step is milliseconds", *_MS)
# A calibration or a trial run: seconds to minutes.
DURATION = Quantity(
    "s", 3600.0, "an hour: a calibration or trial run lasts seconds to minutes", *_MS
)
# The tendon's stress relaxation: seconds to a minute.
RELAXATION_TIME = Quantity("s", 100.0, "100 s: a tendon relaxes within a minute", *_MS)

# a parameter table's unit -> the quantity of a field with that unit, unless named below
_BY_UNIT = {"rad": ANGLE, "m": LENGTH, "s": TIME}
# a field's name -> its quantity where the unit's default does not fit
_BY_NAME: dict[str, Quantity | None] = {
    "curve_angle": CURVE_ANGLE,
    "proximal_radius": SMALL_LENGTH,
    "distal_radius": SMALL_LENGTH,
    "tendon_offset": SMALL_LENGTH,
    "backbone_length": SMALL_LENGTH,
    "delay": DELAY,
    "table_dt": DELAY,
    "relaxation_time": RELAXATION_TIME,
    "noise_std": ANGLE_NOISE,
    # a gain whose unit is s (u = kd de/dt), not a duration
    "kd": None,
    # the PlantModel's friction angle mu * theta: its table bounds it at 20 rad already
    "friction_angle": None,
    # the PlantModel's viscous time: identified up to the record's duration, so a long one is
    # a finding of the search (which builds many), not a unit slip
    "viscous_time": None,
}


# (struct, field) pairs not checked: the curve-angle model and the feedforwards built from an
# identified one hold their geometry in the data's units (the radii's ratio is the
# transmission, a radius or a backbone near 1 is the normalisation), so any size is plausible
_NORMALISED = {
    ("CurveAngleParams", "proximal_radius"),
    ("CurveAngleParams", "distal_radius"),
    ("CurveAngleFeedforwardParams", "proximal_radius"),
    ("CurveAngleFeedforwardParams", "distal_radius"),
    ("ContinuumFeedforwardParams", "proximal_radius"),
    ("ContinuumFeedforwardParams", "tendon_offset"),
    ("ContinuumFeedforwardParams", "backbone_length"),
}


def quantity_of(name: str, unit: str, struct: str = "") -> Quantity | None:
    """The quantity of a field named ``name`` in ``unit`` (a parameter table's row), or None
    when no unit slip is checked for it (not an angle, a length or a time; or a gain in s).

    Parameters
    ----------
    name : str
        The field's (the Python argument's) name.
    unit : str
        Its unit as the parameter table gives it.
    struct : str, optional
        The parameter struct's name (some of its fields are in normalised units).

    Returns
    -------
    Quantity or None
        The quantity whose bound applies.
    """
    if (struct, name) in _NORMALISED:
        return None
    if name in _BY_NAME:
        q = _BY_NAME[name]
        return q if q is not None and q.unit == unit else None
    return _BY_UNIT.get(unit)


def warn_if_unit_slip(
    value: float, who: str, name: str, quantity: Quantity, stacklevel: int | None = None
) -> None:
    """A :class:`UnitWarning` when ``|value|`` is above the quantity's bound, e.g.
    "Route.uniform: curve_angle 180 rad is above 12.57 rad (4 pi, ...); did you give degrees?
    180 deg = 3.142 rad". A value that is not a finite number is left to the caller's checks.

    Parameters
    ----------
    value : float
        The value given (in the quantity's SI unit).
    who : str
        The class or function it was given to.
    name : str
        The argument's name.
    quantity : Quantity
        Its kind: the bound and the unit it was most likely given in.
    stacklevel : int, optional
        Where the warning points; by default the first frame outside the package (the user's
        line).
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        return
    if not math.isfinite(v) or abs(v) <= quantity.bound:
        return
    q = quantity
    warnings.warn(
        f"{who}: {name} {v:g} {q.unit} is above {q.bound:.4g} {q.unit} ({q.reason}); did you "
        f"give {q.slip_name}? {v:g} {q.slip} = {v * q.factor:.4g} {q.unit}",
        UnitWarning,
        stacklevel=caller_outside_package() - 1 if stacklevel is None else stacklevel,
    )


def warn_unit_slips(who: str, struct: Any) -> None:
    """:func:`warn_if_unit_slip` for every field of a C++ parameter struct that its table gives
    in rad, m or s (``type(struct).fields()``): a field added to a table is checked at once.

    Parameters
    ----------
    who : str
        The Python class that built the struct.
    struct : object
        A bound ``...Params`` struct of ``tendonsheath._core``.
    """
    for row in type(struct).fields():
        q = quantity_of(row["name"], row["unit"], type(struct).__name__)
        value = getattr(struct, row["name"], None)
        if q is not None and isinstance(value, float | int):
            warn_if_unit_slip(value, who, row["name"], q)


def warn_if_degrees(
    value: float, who: str, name: str, bound: float, reason: str, stacklevel: int | None = None
) -> None:
    """:func:`warn_if_unit_slip` for an angle (rad) with its own ``bound`` and ``reason``.

    Parameters
    ----------
    value : float
        The angle given (rad).
    who : str
        The class or function it was given to.
    name : str
        The argument's name.
    bound : float
        The largest plausible magnitude (rad).
    reason : str
        Why no real value goes past the bound.
    stacklevel : int, optional
        Where the warning points (default: the user's line).
    """
    warn_if_unit_slip(value, who, name, Quantity("rad", bound, reason, *_DEG), stacklevel)


def warn_if_curve_angle_in_degrees(value: float, who: str, name: str = "curve_angle") -> None:
    """:func:`warn_if_unit_slip` for a route's total curve angle (bound 4 pi, spec section 1).

    Parameters
    ----------
    value : float
        The curve angle given (rad).
    who : str
        The class or function it was given to.
    name : str, default "curve_angle"
        The argument's name.
    """
    warn_if_unit_slip(value, who, name, CURVE_ANGLE)


def checked_curve_angle(who: str, value: float) -> float:
    """A curve angle given to a setter (rad): finite and >= 0, else a ValueError naming it (the
    C++ cores keep the last angle and report input_clamped; outside real time we say so)."""
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"{who}: curve_angle must be finite and >= 0 (got {value:g})")
    return value
