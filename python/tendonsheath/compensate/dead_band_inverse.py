"""The inverse of a dead zone (Tao and Kokotovic 1994), built on the C++ ``DeadBandInverse``."""

from __future__ import annotations

from .._util.args import core_errors_as, number
from . import _bound as core
from .base import Feedforward


class DeadBandInverse(Feedforward, core.DeadBandInverse):
    """Desired output in, command out: the command a dead zone maps to the desired output.

    The dead zone: y = c_r (u - d_r) for u > d_r, 0 for -d_l <= u <= d_r, c_l (u + d_l) for
    u < -d_l. Its inverse: u = y_d / c_r + d_r for y_d > 0, y_d / c_l - d_l for y_d < 0, the
    dead zone's middle (d_r - d_l) / 2 at 0; with ``eps`` > 0 straight lines join that middle to
    the branches at +-eps (a continuous command, without chattering about 0; exact outside
    |y_d| < eps, the output of the same sign and no larger inside).

    Parameters
    ----------
    c_r : float, default 1.0
        Slope of the dead zone's right branch (output per input), > 0.
    c_l : float, default 1.0
        Slope of the dead zone's left branch (output per input), > 0.
    d_r : float, default 0.0
        Right edge of the dead zone (rad): no output for 0 <= u <= d_r, >= 0.
    d_l : float, default 0.0
        Left edge of the dead zone below 0 (rad): no output for -d_l <= u <= 0, >= 0.
    eps : float, default 0.0
        Smoothing width around y_d = 0, in output units, >= 0; 0: the exact jump.

    Raises
    ------
    TypeError
        A value that is not a number.
    ValueError
        A value out of range (the message names the argument and the value).
    """

    _saved_settings = ("c_r", "c_l", "d_r", "d_l", "eps")

    def __init__(
        self,
        c_r: float = 1.0,
        c_l: float = 1.0,
        d_r: float = 0.0,
        d_l: float = 0.0,
        eps: float = 0.0,
    ):
        who = type(self).__name__
        values = {"c_r": c_r, "c_l": c_l, "d_r": d_r, "d_l": d_l, "eps": eps}
        self._settings = {k: number(who, k, v) for k, v in values.items()}
        with core_errors_as(who):
            core.DeadBandInverse.__init__(self, core.DeadBandInverseParams(**self._settings))


__all__ = ["DeadBandInverse"]
