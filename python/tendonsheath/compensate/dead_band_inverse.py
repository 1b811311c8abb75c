"""The inverse of a dead zone (Tao and Kokotovic 1994), built on the C++ ``DeadBandInverse``."""

from __future__ import annotations

from . import _bound as core
from .base import Feedforward
from .from_table import feedforward_from_table


@feedforward_from_table  # the signature, the saved keys and the Parameters section
class DeadBandInverse(Feedforward, core.DeadBandInverse):
    """Desired output in, command out: the command a dead zone maps to the desired output.

    The dead zone: y = c_r (u - d_r) for u > d_r, 0 for -d_l <= u <= d_r, c_l (u + d_l) for
    u < -d_l. Its inverse: u = y_d / c_r + d_r for y_d > 0, y_d / c_l - d_l for y_d < 0, the
    dead zone's middle (d_r - d_l) / 2 at 0; with ``eps`` > 0 straight lines join that middle to
    the branches at +-eps (a continuous command, without chattering about 0; exact outside
    |y_d| < eps, the output of the same sign and no larger inside).

    Raises
    ------
    TypeError
        A value that is not a number, or an unknown argument.
    ValueError
        A value out of range (the message names the argument and the value).
    """

    _core_params = core.DeadBandInverseParams


__all__ = ["DeadBandInverse"]
