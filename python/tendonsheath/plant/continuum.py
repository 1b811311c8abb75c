"""ContinuumPlant: the pull-pull pair bending a continuum segment (Lau et al. 2015); output the
bending angle (rad)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .._util.args import core_errors_as
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
    _CONTINUUM_NUMBERS,
    _PAIR_EFFECTS,
    _check_elements,
    _check_route,
    _options,
    _set_effects,
    _set_numbers,
)
from .pull_pull import _PairPlant


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
    friction : float, default 0.1
        Friction coefficient mu (of sheath 1 for a pair).
    stiffness : float, default 2.4e4
        Tendon axial stiffness EA (N) (of tendon 1 for a pair).
    pretension : float, default 10.0
        Pretension T0 of both tendons (N).
    proximal_radius : float, default 5e-3
        Proximal (motor) pulley radius r_p (m).
    bending_stiffness : float, default 4e-4
        Backbone bending stiffness EI (N m^2).
    tendon_offset : float, default 2e-3
        Distance r_t of the tendons from the backbone (m).
    backbone_length : float, default 0.03
        Length l of the segment (m).
    elements : int, default 100
        Elements N per sheath, >= 2.
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
    distal_inertia : float, optional
        J_d (kg m^2) of a dynamic distal joint (None: off).
    distal_damping : float, optional
        c_d (N m s/rad) of the distal joint (None: off).
    sheath_viscosity : float, optional
        Viscous drag on the sliding tendon (N s/m per metre of sheath; None: off).
    relaxation_fraction : float, optional
        Share r in [0, 1) of EA that relaxes (standard linear solid; None: off).
    relaxation_time : float, optional
        Time constant tau of the relaxation (s).
    friction2 : float, optional
        Friction of sheath 2 (None: as sheath 1).
    stiffness2 : float, optional
        EA of tendon 2 (N) (None: as tendon 1).
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
        friction: float = 0.1,
        stiffness: float = 2.4e4,
        pretension: float = 10.0,
        proximal_radius: float = 5e-3,
        bending_stiffness: float = 4e-4,
        tendon_offset: float = 2e-3,
        backbone_length: float = 0.03,
        elements: int = 100,
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
        effects = {k: v for k, v in locals().items() if k in _PAIR_EFFECTS}
        route = Route.uniform(1.0, math.pi) if route is None else route
        self.route = _check_route(route, "route", cls)
        self.route2 = _check_route(route if route2 is None else route2, "route2", cls)
        c = core.ContinuumParams()
        _set_numbers(c, cls, _CONTINUUM_NUMBERS, locals())
        c.elements = _check_elements(elements, cls)
        c.options = _options(cls, max_increment, fast_path)
        _set_effects(c, cls, _PAIR_EFFECTS, effects)
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
