"""Plausible angles: a curve angle or a joint angle far past its physical range was most likely
given in degrees; a warning names the bound, its reason and the value converted. And the check
of a curve angle given to a setter outside real time (finite, >= 0)."""

from __future__ import annotations

import math
import warnings

# Spec section 1: the total curve angle of an endoscope's sheath lies in 0 to 4 pi (two full
# coils). A curve angle given past it is most likely in degrees (180 for a U-turn of pi rad).
PLAUSIBLE_CURVE_ANGLE = 4 * math.pi
# A distal joint (a wrist, a bending section) turns less than a full turn either way; a joint
# angle or amplitude past it is most likely in degrees too.
PLAUSIBLE_JOINT_ANGLE = 2 * math.pi


class UnitWarning(UserWarning):
    """An angle far outside its physical range, most likely given in degrees where radians are
    meant; the message names the bound, its reason and the value converted from degrees."""


def warn_if_degrees(
    value: float, who: str, name: str, bound: float, reason: str, stacklevel: int = 3
) -> None:
    """A :class:`UnitWarning` when ``|value|`` (rad) is above ``bound`` (rad), ``reason`` saying
    why the bound holds, e.g. "Route.uniform: curve_angle 180 rad is above 4 pi = 12.57 rad (two
    full coils, ...); did you give degrees? 180 deg = 3.142 rad".

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
    stacklevel : int, default 3
        Where the warning points (3: the caller of the function that calls this one).
    """
    if abs(value) > bound:
        warnings.warn(
            f"{who}: {name} {value:g} rad is above {bound:.4g} rad ({reason}); did you give "
            f"degrees? {value:g} deg = {math.radians(value):.4g} rad",
            UnitWarning,
            stacklevel=stacklevel,
        )


def warn_if_curve_angle_in_degrees(value: float, who: str, name: str = "curve_angle") -> None:
    """:func:`warn_if_degrees` for a route's total curve angle (bound 4 pi, spec section 1).

    Parameters
    ----------
    value : float
        The curve angle given (rad).
    who : str
        The class or function it was given to.
    name : str, default "curve_angle"
        The argument's name.
    """
    reason = "4 pi, two full coils: the most an endoscope's sheath takes, spec section 1"
    warn_if_degrees(value, who, name, PLAUSIBLE_CURVE_ANGLE, reason, stacklevel=4)


def checked_curve_angle(who: str, value: float) -> float:
    """A curve angle given to a setter (rad): finite and >= 0, else a ValueError naming it (the
    C++ cores keep the last angle and report input_clamped; outside real time we say so)."""
    if not (math.isfinite(value) and value >= 0):
        raise ValueError(f"{who}: curve_angle must be finite and >= 0 (got {value:g})")
    return value
