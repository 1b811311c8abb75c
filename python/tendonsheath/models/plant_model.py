"""The pull-pull plant as a grey-box model: a few identifiable physical groups, not a copy of
any plant's parameters."""

from __future__ import annotations

import math
import warnings
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.typing import ArrayLike
from ..simulation_result import SimulationResult
from ..status import Status
from . import _bound as core
from ._param_table import checked_values, from_table, table_rows
from .base import HysteresisModel

if TYPE_CHECKING:
    from ..plant import PullPullPlant

#: wrap angle of the internal uniform route (rad); only friction * wrap angle matters on it
WRAP = 2.0 * math.pi


class _GreyBox(HysteresisModel):
    """The grey-box model's parameters, checked against the table and held here (it runs a
    PullPullPlant; the C++ PlantModel, ModelInverse's, takes the same table)."""

    _core_params = core.PlantModelParams

    def __init__(self, **values: Any):
        unknown = sorted(set(values) - set(self.param_names) - set(self.option_names))
        if unknown:
            raise TypeError(
                f"PlantModel: unknown parameter(s) {unknown}; "
                f"expected {list(self.param_names + self.option_names)}"
            )
        rows = table_rows(type(self))
        given = {r["name"]: values.get(r["name"], r["default"]) for r in rows}
        checked = checked_values("PlantModel", rows, given)
        if checked["gain"] == 0.0:  # the table's "finite and != 0": the zero by hand
            raise ValueError("PlantModel: gain must be finite and not 0 (got 0)")
        self._values = {k: float(checked[k]) for k in self.param_names}
        self._elements: int = int(checked["elements"])
        self._plant: PullPullPlant = self._make_plant()

    def _make_plant(self) -> PullPullPlant:
        from ..plant import PullPullPlant
        from ..plant.route import Route

        v = self._values
        compliance = v["backlash"] / math.tanh(0.5 * v["friction_angle"])  # L/EA at T0 = 1
        # the pulleys' radius r is a free scale (e_b = T0 L tanh(a/2) / (EA r)), chosen so that
        # the rest strain T0 / EA = compliance r stays <= 1e-3 (the plant's bound: < 0.05)
        radius = min(1.0, 1e-3 / compliance)
        stiffness = 1.0 / (compliance * radius)  # EA with L = 1 m, T0 = 1 N
        viscosity = v["viscous_time"] * stiffness  # c_v = tau EA / L^2
        return PullPullPlant(
            route=Route.uniform(length=1.0, curve_angle=WRAP),
            friction=v["friction_angle"] / WRAP,
            stiffness=stiffness,
            pretension=1.0,
            proximal_radius=radius,
            distal_radius=radius,
            elements=self._elements,
            sheath_viscosity=viscosity if viscosity > 0 else None,
        )


@from_table  # param_names, option_names, the signature, the defaults, the Parameters section
class PlantModel(_GreyBox):
    """A :class:`~tendonsheath.PullPullPlant` reduced to the groups its input/output data can
    identify, in the data's own units (the pulley angle *is* the input):

    - ``friction_angle`` mu Theta (rad): the capstan exponent, which shapes the transition
      after a reversal (the route is a uniform arc; only the product matters on it);
    - ``backlash`` e_b: half the dead zone, in input units; the tendon compliance follows as
      L / EA = e_b / (T0 tanh(mu Theta / 2)) (spec A7; pretension, length and radii are
      scale choices that the data cannot separate from it);
    - ``viscous_time`` (s): the sheath's viscous drag relative to the tendon stiffness,
      c_v L^2 / EA, which widens the loop with the rate (0: quasi-static);
    - ``gain`` and ``offset``: the output map y = offset + gain * q_out (any sign, units).

    ``elements`` (an option): the sheath's element count; a small one keeps the
    model cheap enough to identify in a model comparison.

    The tendons are linear springs: where the viscous drag (``viscous_time`` times the speed)
    exceeds the dead zone a tendon's tension passes below zero. The model then goes on as an
    effective one (no :class:`~tendonsheath.plant.SlackWarning`); ``status`` and
    ``simulate(...).status`` flags those samples SLACK.

    Raises
    ------
    ValueError
        A value that is not a number or is out of its range.
    """

    rate_independent = False

    @property
    def params(self) -> dict[str, Any]:
        """The five identifiable groups, as a dict (a copy)."""
        return dict(self._values)

    @property
    def options(self) -> dict[str, Any]:
        """The sheath's element count, as a dict."""
        return {name: self._elements for name in self.option_names}

    def _simulate(self, t: ArrayLike | None, x: ArrayLike) -> SimulationResult:
        """Output for the input samples x at times t (needed), from rest at x[0].

        Parameters
        ----------
        t : array_like of float, shape (n,)
            Sample times (s); required.
        x : array_like of float, shape (n,)
            Input samples (pulley angle, input unit).

        Returns
        -------
        SimulationResult, shape (n,)
            Output samples, with ``status`` each sample's Status flags (SLACK where a tendon
            went slack).
        """
        if t is None:
            raise ValueError("PlantModel is rate-dependent: t is required")
        with warnings.catch_warnings():  # slack: flagged in the status, not warned (above)
            warnings.simplefilter("ignore")
            q = self._plant.simulate(t, x)
        y = self._values["offset"] + self._values["gain"] * np.asarray(q)
        return SimulationResult(y, status=q.status)

    def reset(self) -> None:
        """Forget the streaming state."""
        self._plant.reset()

    def step(self, x: float, dt: float = 0.0) -> float:
        """Advance one sample (streaming).

        Parameters
        ----------
        x : float
            The input sample.
        dt : float, default 0.0
            Time since the previous sample (s).

        Returns
        -------
        float
            The output sample.
        """
        return self._values["offset"] + self._values["gain"] * self._plant.step(x, dt)

    def status(self) -> Status:
        """The last step's Status (SLACK when a tendon's tension passed below zero).

        Returns
        -------
        Status
            The flags of the last :meth:`step`.
        """
        return self._plant.status()

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v:.6g}" for k, v in self._values.items())
        return f"PlantModel({inner}, {self.option_names[0]}={self._elements})"


__all__ = ["PlantModel", "WRAP"]
