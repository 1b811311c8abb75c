"""SingleTendonPlant: one tendon in its sheath, proximal displacement in, distal displacement
out (m) (spec A.5)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._util.args import core_errors_as
from .._util.param_table import TABLE, table_constructor
from .._util.units import warn_unit_slips
from . import _bound as core
from . import physics
from .loads import (
    ConstantForce,
    LinearSpring,
    SpringPreload,
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
    _Plant,
    _row_arguments,
    _set_effects,
    _set_numbers,
)


@table_constructor(core.SingleTendonParams)
class SingleTendonPlant(_Plant, core.SingleTendonPlant):  # type: ignore[misc]
    """One tendon in one sheath: proximal displacement in (m), distal displacement out (m).

    ``load`` is a :class:`~tendonsheath.plant.loads.ConstantForce`, ``LinearSpring`` or
    ``SpringPreload`` pulling the distal end (default ConstantForce(10 N)).

    Parameters
    ----------
    route : Route
        Route of the sheath.
    load : ConstantForce, LinearSpring or SpringPreload, optional
        The distal load (default ConstantForce(10.0)).
    motor : Motor, optional
        A drive between the command and the proximal pulley.
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

    # attributes set by __init__ (tendonsheath._util.pyobject: declared, else refused)
    route: Route
    load: ConstantForce | LinearSpring | SpringPreload

    _rows = 1

    def __init__(
        self,
        route: Route,
        friction: float = TABLE,
        stiffness: float = TABLE,
        elements: int = TABLE,
        load: ConstantForce | LinearSpring | SpringPreload | None = None,
        motor: Motor | None = None,
        sensor: Sensor | None = None,
        max_increment: float | None = None,
        fast_path: bool = True,
        sheath_viscosity: float | None = None,
        relaxation_fraction: float | None = None,
        relaxation_time: float | None = None,
        encoder: Sensor | None = None,
    ):
        self._keep_arguments(locals())
        cls = type(self).__name__
        numbers, effect_names = _row_arguments(SingleTendonPlant)
        effects = {k: v for k, v in locals().items() if k in effect_names}
        self.route = _check_route(route, "route", cls)
        load = ConstantForce(10.0) if load is None else load
        if not isinstance(load, ConstantForce | LinearSpring | SpringPreload):
            raise TypeError(
                f"{cls}: load must be ConstantForce, LinearSpring or SpringPreload "
                f"(got {type(load).__name__})"
            )
        self.load = load
        p = core.SingleTendonParams()
        _set_numbers(p, cls, numbers, locals())
        p.elements = _check_elements(elements, cls)
        p.load_force, p.load_stiffness = load.linear()
        p.options = _options(cls, max_increment, fast_path)
        _set_effects(p, cls, effect_names, effects)
        with core_errors_as(cls):
            core.SingleTendonPlant.__init__(self, p, route)
        warn_unit_slips(cls, p)
        self._setup_io(motor, sensor, encoder)

    @property
    def kinematic_gain(self) -> float:
        """The uncompensated command per unit of desired output: 1 (m of proximal displacement
        per m of distal displacement)."""
        return 1.0

    def _lengths(self) -> tuple[float, ...]:
        return (self.route.length,)

    def set_route(self, route: Route) -> None:  # type: ignore[override]
        """Bend the sheath to a new route (same length); over-capacity nodes slip next step.

        Parameters
        ----------
        route : Route
            The new route, of the same length.

        Raises
        ------
        ValueError
            Not a Route, or of another length.
        """
        core.SingleTendonPlant.set_route(self, _check_route(route, "route", type(self).__name__))
        self.route = route

    def _angles_for(self, r):
        return core.SingleTendonPlant.node_angles(
            self, _check_route(r, "routes(t)", type(self).__name__)
        )

    def closed_form(self) -> dict:
        """Capstan ratio and (A4) dead zone for the current route and load at rest (m).

        Returns
        -------
        dict
            ``capstan_ratio`` and ``dead_zone`` (m).
        """
        F0, _ = self.load.linear()
        return {
            "capstan_ratio": float(physics.capstan_ratio(self.friction, self.route.curve_angle)),
            "dead_zone": physics.single_tendon_dead_zone(
                self.route, self.stiffness, F0, self.friction
            ),
        }


__all__ = ["SingleTendonPlant"]
