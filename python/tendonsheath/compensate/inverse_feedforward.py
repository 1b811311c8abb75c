"""Direct inverse feedforward of an identified hysteresis model (seed 002, spec D.2)."""

from __future__ import annotations

from typing import Any

import numpy as np

from .. import _core as core
from .._args import number, python_names
from .._arrays import checked_dt
from .._typing import ArrayLike, FloatArray
from ..models import Backlash, BoucWenBacklash, HysteresisModel, PrandtlIshlinskii, Scaled
from .base import Feedforward
from .limits import CommandLimits, LimitsLike, as_limits


class InverseFeedforward(Feedforward):
    """Motor command that makes `model` produce the desired output, with no distal sensor.

    * ``Backlash`` and ``BoucWenBacklash``: the direct inverse of spec D.2,
      x = [y_d + phi c_r B_r - (1 - phi) c_l B_l] / [phi c_r + (1 - phi) c_l] with
      phi = (1 + tanh(y_d' / smoothing)) / 2; ``smoothing`` (output units per s, about
      2-5 % of the peak desired speed) sets how sharply the command switches branch at a
      reversal (-> 0: the exact backlash inverse, a jump of B_r + B_l).
    * ``PrandtlIshlinskii``: its exact inverse operator (continuous; no smoothing needed).
    * ``Scaled`` (what ``identify`` returns for a negative gain or offsets) around one of
      these: the inner model's inverse in its units, x = x_c + x_s inv((y_d - y_c) / g);
      ``smoothing`` and ``limits`` stay in the raw output and command units.

    ``limits`` (a :class:`CommandLimits`) saturates the command and its rate.

    Parameters
    ----------
    model : HysteresisModel
        A Backlash, BoucWenBacklash or PrandtlIshlinskii, or a Scaled one around them.
    smoothing : float, default 0.05
        Desired-output speed of the branch switch (output units per s), > 0.
    limits : CommandLimits, tuple, dict or None, optional
        Saturation of the command and its rate (see :class:`CommandLimits`).

    Raises
    ------
    ValueError
        A model of another class, or a smoothing or limit the C++ core rejects.
    """

    _saved_settings = ("model", "smoothing", "limits")

    def __init__(self, model: HysteresisModel, smoothing: float = 0.05, limits: LimitsLike = None):
        self.model = model
        self.smoothing = number("InverseFeedforward", "smoothing", smoothing)
        self.limits = as_limits(limits)
        self._settings = {"smoothing": self.smoothing, "limits": self.limits}
        self._map = None
        if isinstance(model, Scaled):
            mp = model.map
            x_c, x_s, y_c, g = (mp[k] for k in mp)
            lim = self.limits
            inner_limits = CommandLimits(
                (lim.min - x_c) / x_s, (lim.max - x_c) / x_s, lim.max_rate / x_s
            )
            self._inner = InverseFeedforward(model.inner, self.smoothing / abs(g), inner_limits)
            self._engine = self._inner._engine
            self._map = (x_c, x_s, y_c, g)
            return
        if isinstance(model, Backlash | BoucWenBacklash):
            p = core.BacklashInverseParams()
            for key in ("c_r", "c_l", "B_r", "B_l"):
                setattr(p, key, model.params[key])
            p.v_eps = self.smoothing
            p.limits = self.limits.to_core()
            with python_names("InverseFeedforward"):
                self._engine = core.BacklashInverseFeedforward(p)
        elif isinstance(model, PrandtlIshlinskii):
            pi = core.PrandtlIshlinskiiParams()
            pi.thresholds = model.params["thresholds"]
            pi.weights = model.params["weights"]
            with python_names("InverseFeedforward"):
                self._engine = core.PrandtlIshlinskiiFeedforward(pi, self.limits.to_core())
        else:
            raise TypeError(
                "InverseFeedforward: model must be a Backlash, BoucWenBacklash or "
                f"PrandtlIshlinskii, or a Scaled one of them (got {type(model).__name__})"
            )

    @property
    def params(self) -> dict:
        """The constructor settings and the model (a copy)."""
        return {**super().params, "model": self.model}

    def to_dict(self) -> dict:
        """The compensator as a dict, its model saved whole.

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` reads back.
        """
        data = super().to_dict()
        return {**data, "model": self.model.to_dict()}

    def step(self, y_d: float, dt: float) -> float:
        """One control cycle (real-time core, no allocation).

        Parameters
        ----------
        y_d : float
            Desired output (the model's output unit).
        dt : float
            Time since the previous cycle (s), >= 0.

        Returns
        -------
        float
            The motor command.
        """
        dt = checked_dt(dt)
        if self._map is None:
            return super().step(y_d, dt)
        x_c, x_s, y_c, g = self._map
        return x_c + x_s * self._engine.step((float(y_d) - y_c) / g, float(dt))

    def command(
        self, t: ArrayLike, y_desired: ArrayLike, status: bool = False
    ) -> FloatArray | tuple[FloatArray, np.ndarray]:
        """Motor commands for a whole trajectory, from the initial state.

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing; required.
        y_desired : array_like of float, shape (n,)
            Desired outputs.
        status : bool, default False
            Also return each cycle's Status flags.

        Returns
        -------
        commands : numpy.ndarray of float, shape (n,)
            Motor commands; ``(commands, flags)`` with ``status=True``, flags each cycle's
            :class:`~tendonsheath.Status` (uint8).

        Raises
        ------
        ValueError
            t missing, or samples not finite or of different lengths.
        """
        if self._map is None:
            return super().command(t, y_desired, status)
        x_c, x_s, y_c, g = self._map
        inner: Any = self._inner.command(t, (np.asarray(y_desired, dtype=float) - y_c) / g, status)
        if status:
            return x_c + x_s * inner[0], inner[1]
        return x_c + x_s * inner

    def _bench_engine(self):
        # the C++ loops know the inner engine only: a Scaled model's map runs in step()
        return self._engine if self._map is None else None

    def __repr__(self) -> str:
        return f"InverseFeedforward({self.model!r}, smoothing={self.smoothing:g})"
