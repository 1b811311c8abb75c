"""ContinuumPlant: the pull-pull pair bending a continuum segment (Lau et al. 2015); output the
bending angle (rad)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .._util.args import core_errors_as
from .._util.param_table import TABLE, table_constructor
from .._util.units import warn_unit_slips
from . import _bound as core
from .loads import (
    TorsionalSpring,
)
from .motor import Motor
from .route import Route
from .sensor import Sensor

if TYPE_CHECKING:
    pass
from .base import (
    _check_elements,
    _check_route,
    _options,
    _row_arguments,
    _set_effects,
    _set_numbers,
)
from .pull_pull import _PairPlant


@table_constructor(core.ContinuumParams)
class ContinuumPlant(_PairPlant, core.ContinuumPlant):  # type: ignore[misc]
    """A pull-pull pair bending a continuum segment (Lau et al. 2015, spec C.5); output theta_b.

    Li and Rahn: the tendon force that holds a bending angle theta_b is F = kappa EI/r_t with
    kappa = theta_b / l, and the stroke is x_out = r_t theta_b, so the segment is a spring
    k = EI/(r_t^2 l) on the stroke. Defaults: EI = 4e-4 N m^2, r_t = 2 mm, l = 30 mm and a 1 m
    sheath on a 0.6 m-diameter semicircle (Theta = pi).

    Parameters
    ----------
    route : Route, optional
        Route of sheath 1 (default: 1 m, Theta = pi, uniform).
    motor : Motor, optional
        A drive between the command and the proximal pulley.
    route2 : Route, optional
        Route of sheath 2 (default: route).
    sensor : Sensor, optional
        Reads the output (``SimulationResult.measured``).
    max_increment : float, optional
        Largest input sub-increment of the solver (m); None: the plant chooses.
    fast_path : bool, default True
        Use the solver's exact shortcuts (lazy update while the slip map stays valid).
    encoder : Sensor, optional
        The motor encoder's reading of the motor shaft (resolution, noise): what
        ``SimulationResult.q_motor`` logs and what ``bench.run``'s controllers read (None:
        exact).

    Raises
    ------
    ValueError
        A route, load, motor or sensor of the wrong kind, elements not an integer >= 2, or a
        value the C++ core rejects (the message names it).
    TypeError
        An effect that is not a number.
    """

    def __init__(
        self,
        route: Route | None = None,
        friction: float = TABLE,
        stiffness: float = TABLE,
        pretension: float = TABLE,
        proximal_radius: float = TABLE,
        bending_stiffness: float = TABLE,
        tendon_offset: float = TABLE,
        backbone_length: float = TABLE,
        elements: int = TABLE,
        motor: Motor | None = None,
        route2: Route | None = None,
        sensor: Sensor | None = None,
        max_increment: float | None = None,
        fast_path: bool = True,
        distal_inertia: float | None = None,
        distal_damping: float | None = None,
        sheath_viscosity: float | None = None,
        relaxation_fraction: float | None = None,
        relaxation_time: float | None = None,
        friction2: float | None = None,
        stiffness2: float | None = None,
        encoder: Sensor | None = None,
    ):
        self._keep_arguments(locals())
        cls = type(self).__name__
        numbers, effect_names = _row_arguments(ContinuumPlant)
        effects = {k: v for k, v in locals().items() if k in effect_names}
        route = Route.uniform(1.0, math.pi) if route is None else route
        self.route = _check_route(route, "route", cls)
        self.route2 = _check_route(route if route2 is None else route2, "route2", cls)
        c = core.ContinuumParams()
        _set_numbers(c, cls, numbers, locals())
        c.elements = _check_elements(elements, cls)
        c.options = _options(cls, max_increment, fast_path)
        _set_effects(c, cls, effect_names, effects)
        if c.backbone_length > 0 and not math.isfinite(c.bending_stiffness / c.backbone_length):
            raise ValueError(  # else the core names the derived load_stiffness = inf
                f"{cls}: backbone_length {c.backbone_length:g} m is too small: the backbone's "
                f"stiffness bending_stiffness / backbone_length overflows"
            )
        with core_errors_as(cls):
            core.ContinuumPlant.__init__(self, c, self.route, self.route2)
        warn_unit_slips(cls, c)
        self.load = TorsionalSpring(c.bending_stiffness / c.backbone_length)
        self._setup_io(motor, sensor, encoder)

    @property
    def bending_stiffness(self) -> float:
        """Backbone bending stiffness EI (N m^2)."""
        return self.continuum_params.bending_stiffness

    @property
    def tendon_offset(self) -> float:
        """Distance r_t of the tendons from the backbone (m)."""
        return self.continuum_params.tendon_offset

    @property
    def backbone_length(self) -> float:
        """Length l of the continuum segment (m)."""
        return self.continuum_params.backbone_length

    @property
    def spring_stiffness(self) -> float:
        """k = EI/(r_t^2 l) (N/m): the segment as a spring on the tendon stroke."""
        return self.bending_stiffness / (self.tendon_offset**2 * self.backbone_length)

    def tendon_force(self) -> float:
        """Li and Rahn tendon force F = kappa EI / r_t (N) at the current bending angle.

        Returns
        -------
        float
            F (N).
        """
        return core.ContinuumPlant.tendon_force(self)


__all__ = ["ContinuumPlant"]
