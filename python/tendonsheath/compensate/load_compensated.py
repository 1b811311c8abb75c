"""The inverse of a :class:`~tendonsheath.models.Loaded` model, fed the measured load each cycle.

For the desired output y_d and the load L measured this cycle:

1. the base's target is y_d - gain L (the tendon's stretch taken off);
2. the base's inverse (:class:`InverseFeedforward`, real-time C++) gives the play's output z;
3. the play is inverted: x = z + r(L) d, d the direction of travel of z, switched smoothly
   over ``switch`` of z's travel (d = clip(d + dz / switch, -1, 1)): a jump of 2 r(L) at
   every reversal would be a step command.

Without a load sensor, ``load`` may be an estimate (e.g. the motor current or torque times a
calibrated factor): the model's parameters are in the unit of the load it was identified
with, so an estimate must be mapped into that unit first.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from .._util.args import number
from .._util.arrays import as_timed_signal, checked_dt
from .._util.pyobject import PythonObject
from .._util.typing import ArrayLike
from ..models.loaded import Loaded
from ..simulation_result import SimulationResult
from . import _bound as core
from . import persistence
from ._kinds import require_model
from .base import SavedAsJson, command_result
from .inverse_feedforward import InverseFeedforward


class LoadCompensated(PythonObject, SavedAsJson):
    """Commands for a desired output under a measured load, from a Loaded model's inverse.

    Parameters
    ----------
    model : Loaded
        An identified Loaded model.
    switch : float, optional
        The travel of the base's input over which the play's direction switches (input
        unit, > 0); default a quarter of the play's half-width at zero load, at least 1e-6
        times the identified input span.
    **inverse_options
        Passed to the base's :class:`InverseFeedforward` (``smoothing``, ``input_range``...).

    Raises
    ------
    TypeError
        model not a Loaded model.
    ValueError
        switch not > 0.
    """

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    model: Loaded
    switch: float
    inverse: InverseFeedforward

    # the keys of a saved file (to_json), in order: the model whole, the switch and the base
    # inverse's settings (defaults resolved); tendonsheath/io/json_multi_input.hpp reads it
    _saved_settings = (
        "model",
        "switch",
        "smoothing",
        "limits",
        "input_range",
        "range_margin",
        "filter_hz",
    )

    def __init__(self, model: Loaded, switch: float | None = None, **inverse_options: Any):
        require_model("LoadCompensated", model, Loaded)
        self.model = model
        if switch is None:
            span = 1.0
            if model.input_range is not None:
                span = max(model.input_range[1] - model.input_range[0], 1e-300)
            switch = max(0.25 * float(model.radius(0.0)), 1e-6 * span)
        self.switch = number("LoadCompensated", "switch", switch)
        if not (math.isfinite(self.switch) and self.switch > 0):
            raise ValueError(f"LoadCompensated: switch must be > 0 (got {self.switch:g})")
        self.inverse = InverseFeedforward(model.base, **inverse_options)
        self._inverse_options = dict(inverse_options)
        terms = core.LoadTerms()
        for key, value in model.terms.items():
            setattr(terms, key, value)
        terms.switch_travel = self.switch
        self._play = core.LoadPlayInverse(terms)  # the real-time core (C++)
        self.reset()

    @property
    def params(self) -> dict[str, Any]:
        """The constructor's arguments: the model, the switch (resolved) and the options
        given to the base's inverse (a copy)."""
        return {"model": self.model, "switch": self.switch, **self._inverse_options}

    def _configuration(self) -> dict[str, Any]:
        # get_params (tendonsheath._util.pyobject)
        return self.params

    def _recipe(self):
        # pickled as its settings: an equal compensator at rest (tendonsheath._util.pyobject)
        options = self._inverse_options
        return functools.partial(LoadCompensated, self.model, self.switch, **options), ()

    def reset(self) -> None:
        """Forget the streaming state (the base inverse's and the play's)."""
        self.inverse.reset()
        self._play.reset()
        self._load = 0.0

    def step(self, y_d: float, dt: float, load: float) -> float:
        """One control cycle.

        Parameters
        ----------
        y_d : float
            Desired output.
        dt : float
            Time since the previous cycle (s), >= 0.
        load : float
            The load measured (or estimated) this cycle, required as in C++'s
            ``step(y_d, dt, load)``; a non-finite value holds the last finite one (0 before
            the first, as the C++ step, which cannot throw, does).

        Returns
        -------
        float
            The command.
        """
        dt = checked_dt(dt)
        load = float(load)
        if not math.isfinite(load):
            load = self._load
        self._load = load
        z = self.inverse.step(float(y_d) - self.model.terms["gain"] * load, dt)
        return float(self._play.step(float(z), load))

    def command(self, t: ArrayLike, y_desired: ArrayLike, load: ArrayLike) -> SimulationResult:
        """Commands for a whole trajectory under its measured load, from the initial state.

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s), increasing.
        y_desired : array_like of float, shape (n,)
            Desired outputs.
        load : float or array_like of float, shape (n,)
            The measured load of every sample.

        Returns
        -------
        SimulationResult, shape (n,)
            The commands, with ``t``, ``input`` (y_desired) and ``status`` (the base
            inverse's flags of each cycle).

        Raises
        ------
        ValueError
            Samples not finite, or of different lengths.
        """
        ts, ys = as_timed_signal(t, y_desired, "y_desired", "LoadCompensated.command")
        loads = np.broadcast_to(np.asarray(load, dtype=float), ys.shape)
        if not np.all(np.isfinite(loads)):
            raise ValueError("LoadCompensated.command: the load must be finite")
        loads = np.ascontiguousarray(loads)
        z = self.inverse.command(ts, ys - self.model.terms["gain"] * loads)
        u = self._play.command(np.ascontiguousarray(z, dtype=float), loads)
        return command_result(ts, ys, (u, z.status))

    # -- persistence -----------------------------------------------------------------
    def to_dict(self) -> dict:
        """The compensator as a dict (format ``tendonsheath.compensator``): the Loaded model
        whole, the switch and the base inverse's settings, defaults resolved.

        Returns
        -------
        dict
            What :func:`~tendonsheath.compensate.load_compensator` reads back.
        """
        inverse = {k: v for k, v in self.inverse.params.items() if k != "model"}  # its base
        settings = {"model": self.model, "switch": self.switch, **inverse}
        return persistence.compensator_dict("LoadCompensated", settings)

    @classmethod
    def _from_saved(cls, values: dict) -> LoadCompensated:
        settings = dict(values)
        model = settings.pop("model")
        if not isinstance(model, Loaded):
            raise ValueError(
                f"LoadCompensated file: 'model' must be a Loaded model (got {type(model).__name__})"
            )
        return cls(model, **settings)

    def __repr__(self) -> str:
        return f"LoadCompensated({self.model!r}, switch={self.switch:g})"


__all__ = ["LoadCompensated"]
