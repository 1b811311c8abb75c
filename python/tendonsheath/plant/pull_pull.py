"""PullPullPlant: the bidirectional pair of Sun, Wang & Phee 2015 and Do et al. 2015, a
quasi-static N-element tendon-sheath simulator (spec A.5, C++ core); pulley angle in, pulley
angle out (rad).

Every plant simulates in C++ (``simulate``) or streams (``reset``/``step``); its route may change
at any step (``set_route``, or ``routes=`` a callable of time in ``simulate``). Tensions and the
stick/slip map are readable after any step. Slack (a tendon tension <= 0) invalidates the model:
it is flagged per sample in the full result and raises a
:class:`~tendonsheath.plant.base.SlackWarning`. The other plants:
:mod:`~tendonsheath.plant.continuum`, :mod:`~tendonsheath.plant.single_tendon`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .._util.args import core_errors_as
from .._util.param_table import TABLE, table_constructor
from .._util.pyobject import bound_attribute
from .._util.units import warn_unit_slips
from . import _bound as core
from . import physics
from .loads import (
    ConstantTorque,
    SpringDamper,
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
    _effects_of,
    _options,
    _Plant,
    _row_arguments,
    _set_effects,
    _set_numbers,
)


class _PairPlant(_Plant):
    """What the pull-pull pair and the continuum plant share: two tendons, two routes, the
    pair's parameters and closed forms. Each of the two is also its own bound C++ class (a
    Python class takes one bound base), so this part is plain Python."""

    _rows = 2
    route: Route
    route2: Route
    load: ConstantTorque | TorsionalSpring | SpringDamper | None

    @property
    def effects(self) -> dict:
        """The effects beyond the quasi-static pair (C++ names; 0 or -1 = off / as tendon 1)."""
        return _effects_of(bound_attribute(self, "params"), _row_arguments(type(self))[1])

    # parameters
    @property
    def pretension(self) -> float:
        """Pretension T0 of both tendons (N)."""
        return bound_attribute(self, "params").pretension

    @property
    def proximal_radius(self) -> float:
        """Proximal (motor) pulley radius r_p (m)."""
        return bound_attribute(self, "params").proximal_radius

    @property
    def distal_radius(self) -> float:
        """Distal pulley radius r_d (m); for a continuum plant, the tendon offset r_t."""
        return bound_attribute(self, "params").distal_radius

    @property
    def kinematic_gain(self) -> float:
        """The uncompensated command per unit of desired output: distal_radius /
        proximal_radius (the motor angle for a distal angle)."""
        return self.distal_radius / self.proximal_radius

    def _lengths(self) -> tuple[float, ...]:
        return (self.route.length, self.route2.length)

    def set_route(self, route: Route, route2: Route | None = None) -> None:
        """Bend the sheaths (route2 defaults to route); lengths must not change. Nodes whose
        stored tension gradient exceeds the new friction capacity start to slip at the next
        step (spec A.5).

        Parameters
        ----------
        route : Route
            New route of sheath 1.
        route2 : Route, optional
            New route of sheath 2 (default: route).

        Raises
        ------
        ValueError
            Not a Route, or a length that changed.
        """
        cls = type(self).__name__
        r1 = _check_route(route, "route", cls)
        r2 = r1 if route2 is None else _check_route(route2, "route2", cls)
        self._bound_class.set_route(self, r1, r2)
        self.route, self.route2 = r1, r2

    def _angles_for(self, r):
        cls = type(self).__name__
        if isinstance(r, tuple | list):
            if len(r) != 2:
                raise ValueError(f"{cls}: routes(t) must give a Route or a (route1, route2) pair")
            r1, r2 = (_check_route(x, "routes(t)", cls) for x in r)
        else:
            r1 = r2 = _check_route(r, "routes(t)", cls)
        return self._bound_class.node_angles(self, r1, r2)

    # closed forms ------------------------------------------------------------------
    def load_force(self) -> float:
        """Distal load at rest at the tendon level F_L = tau_L / r_d (N) (springs: preload).

        Returns
        -------
        float
            F_L (N); 0 without a load.
        """
        if self.load is None:
            return 0.0
        return self.load.rotary()[0] / self.distal_radius

    def steady_offsets(self, load_force: float | None = None) -> tuple[float, float]:
        """Full-slip x_in - x_out (m) on the forward and backward branch: (A5)/(A6) with g, G.

        Parameters
        ----------
        load_force : float, optional
            Distal load F_L (N); default :meth:`load_force`.

        Returns
        -------
        forward, backward : float
            The two offsets (m at the tendon level).
        """
        F = self.load_force() if load_force is None else float(load_force)
        return physics.pull_pull_offsets(
            self.route, self.stiffness, self.pretension, self.friction, F, self.route2
        )

    def dead_zone_width(self, load_force: float | None = None) -> float:
        """Input dead-zone width (m at the tendon level; divide by r_p for rad): A7 / g, G.

        Parameters
        ----------
        load_force : float, optional
            Distal load F_L (N); default :meth:`load_force`.

        Returns
        -------
        float
            The width (m).
        """
        f, b = self.steady_offsets(load_force)
        return f - b

    def backlash_half_width(self) -> float:
        """e_b (m): half the dead zone without load (uniform routes: T0 L tanh(a/2)/EA).

        Returns
        -------
        float
            e_b (m).
        """
        return 0.5 * self.dead_zone_width(0.0)

    def closed_form(self) -> dict:
        """Closed-form figures for the current routes and load (m at the tendon level).

        Returns
        -------
        dict
            offset_forward, offset_backward, dead_zone, backlash_half_width, load_offset (m)
            and no_slack_limit (N).
        """
        f, b = self.steady_offsets()
        return {
            "offset_forward": f,
            "offset_backward": b,
            "dead_zone": f - b,
            "backlash_half_width": self.backlash_half_width(),
            "load_offset": 0.5 * (f + b),
            "no_slack_limit": float(
                physics.no_slack_limit(
                    self.pretension,
                    self.friction,
                    max(self.route.curve_angle, self.route2.curve_angle),
                )
            ),
        }


@table_constructor(core.PullPullParams)
class PullPullPlant(_PairPlant, core.PullPullPlant):  # type: ignore[misc]
    """The bidirectional pull-pull pair (Sun, Wang & Phee 2015; Do et al. 2015): angle in and out.

    Two tendons with pretension T0 (N) and axial stiffness EA (``stiffness``, N) run in two
    sheaths (``route`` for tendon 1, the one a positive input pulls; ``route2`` for tendon 2,
    default the same) between a proximal pulley of radius r_p and a distal one of radius r_d
    (m). ``load`` (None, ConstantTorque, TorsionalSpring or SpringDamper) acts on the distal
    pulley. ``elements`` N per sheath; ``friction`` mu.

    Effects beyond the quasi-static capstan pair (all off by default; with none of them and
    no load the pair *is* a classic backlash, see :mod:`tendonsheath.plant.presets` for realistic
    values):

    - ``distal_inertia`` J_d (kg m^2) and ``distal_damping`` c_d (N m s/rad): a dynamic distal
      joint;
    - ``sheath_viscosity`` (N s/m per metre of sheath): viscous drag on the sliding tendon
      besides Coulomb friction, so the hysteresis widens with rate;
    - ``relaxation_fraction`` r in [0, 1) and ``relaxation_time`` tau (s): each tendon element a
      standard linear solid (r EA relaxes with time constant tau), so a held input creeps;
    - ``friction2`` and ``stiffness2``: sheath 2's friction and tendon 2's EA when the pair is
      unequal (None: the same as tendon 1).

    Any of these (or a damped load) makes a step depend on dt, so ``t`` is then required.

    Parameters
    ----------
    route : Route
        Route of the sheath (of tendon 1 for a pair).
    load : ConstantTorque, TorsionalSpring or SpringDamper, optional
        The load on the distal pulley (None: none).
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
        route: Route,
        friction: float = TABLE,
        stiffness: float = TABLE,
        pretension: float = TABLE,
        proximal_radius: float = TABLE,
        distal_radius: float = TABLE,
        elements: int = TABLE,
        load: ConstantTorque | TorsionalSpring | SpringDamper | None = None,
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
        numbers, effect_names = _row_arguments(PullPullPlant)
        effects = {k: v for k, v in locals().items() if k in effect_names}
        self.route = _check_route(route, "route", cls)
        self.route2 = _check_route(route if route2 is None else route2, "route2", cls)
        if load is not None and not isinstance(
            load, ConstantTorque | TorsionalSpring | SpringDamper
        ):
            raise TypeError(
                f"{cls}: load must be None, ConstantTorque, TorsionalSpring or SpringDamper "
                f"(got {type(load).__name__})"
            )
        self.load = load
        p = core.PullPullParams()
        _set_numbers(p, cls, numbers, locals())
        p.elements = _check_elements(elements, cls)
        if load is not None:
            p.load_torque, p.load_stiffness, p.load_damping = load.rotary()
        p.options = _options(cls, max_increment, fast_path)
        _set_effects(p, cls, effect_names, effects)
        with core_errors_as(cls):
            core.PullPullPlant.__init__(self, p, self.route, self.route2)
        warn_unit_slips(cls, p)
        self._setup_io(motor, sensor, encoder)


__all__ = ["PullPullPlant"]
