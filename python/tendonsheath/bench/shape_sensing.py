"""Shape sensing of a sheath's route (an FBG fibre, bending-knob readings), with noise, delay
and a reading rate: the curve angle only, or the curvature profile.

What a reading reports is a ROUTE: ``Route.uniform(L, sensed angle)`` when only the total
curve angle is sensed (``segments=0``), or ``Route.arcs`` of K equal-length arcs with the
sensed bend angle of each (``segments=K``): the curvature profile that the shape integrals
g, G (spec A.2) and the dead zone of a non-uniform route (spec A5/A6) need. A compensator
that follows the route computes g, G of the sensed route with its own friction.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._util.units import ANGLE_NOISE, DELAY, warn_if_unit_slip
from ..plant.physics import route_shape
from ..plant.route import Route

#: The first seed of the sensing noise (kept from the first ShapeSensing: readings repeat).
_SEED_BASE = 10_000


def _first_route(route: Any) -> Route:
    """The route of a plant's sheath 1: routes callables may return (route1, route2)."""
    return route[0] if isinstance(route, tuple | list) else route


@dataclass
class ShapeSensing:
    """Shape sensing of the route: a new reading every 1/``rate_hz`` s of the route as it was
    ``delay`` seconds earlier, with Gaussian noise.

    ``segments=0`` senses the total curve angle only (noise ``noise_std`` rad): a compensator
    that takes a route gets a uniform-curvature route of that angle. ``segments=K >= 1``
    senses the curvature profile as K equal-length arcs: arc i's bend angle is the true
    route's accumulated angle over that arc (:meth:`Route.angle_at`) plus noise of std
    ``noise_std / sqrt(K)`` (so the total angle's noise is ``noise_std`` for any K), each
    clipped at >= 0.

    Parameters
    ----------
    noise_std : float, default 0.05
        Standard deviation of the sensed total angle (rad), >= 0.
    delay : float, default 0.1
        Delay of the readings (s), >= 0.
    rate_hz : float, default 10.0
        Readings per second, > 0.
    seed : int, default 0
        Seed of the noise.
    segments : int, default 0
        0: the curve angle only; K >= 1: the curvature profile as K equal arcs.

    Raises
    ------
    ValueError
        A value out of the ranges above.
    """

    noise_std: float = 0.05
    delay: float = 0.1
    rate_hz: float = 10.0
    seed: int = 0
    segments: int = 0

    def __post_init__(self) -> None:
        for name, ok in (
            ("noise_std", self.noise_std >= 0),
            ("delay", self.delay >= 0),
            ("rate_hz", self.rate_hz > 0),
        ):
            value = getattr(self, name)
            if not (ok and math.isfinite(value)):
                raise ValueError(f"ShapeSensing: {name} out of range (got {value!r})")
        warn_if_unit_slip(self.noise_std, "ShapeSensing", "noise_std", ANGLE_NOISE)
        warn_if_unit_slip(self.delay, "ShapeSensing", "delay", DELAY)
        segments = self.segments
        if isinstance(segments, bool) or int(segments) != segments or segments < 0:
            raise ValueError(f"ShapeSensing: segments must be an integer >= 0 (got {segments!r})")
        self.segments = int(segments)

    def describe(self) -> str:
        """One line saying what is sensed, and how (for the provenance records).

        Returns
        -------
        str
            What is sensed (the curve angle or the profile in K arcs), noise, delay and rate.
        """
        timing = f"delay {self.delay:g} s, {self.rate_hz:g} Hz readings"
        if self.segments == 0:
            return f"sensed curve angle (noise {self.noise_std:g} rad, {timing})"
        per_arc = self.noise_std / math.sqrt(self.segments)
        return (
            f"sensed curvature profile, {self.segments} equal arcs (noise {self.noise_std:g} "
            f"rad on the curve angle, {per_arc:.3g} rad per arc, {timing})"
        )

    # -- the curve angle (segments = 0 and the old API) ----------------------------------------
    def readings(
        self, t: np.ndarray, angle_at: Callable[[float], float], seed_offset: int = 0
    ) -> tuple[np.ndarray, np.ndarray]:
        """(sample index of each reading, sensed curve angle of each reading) over times t:
        the total angle only, whatever ``segments`` is.

        Parameters
        ----------
        t : array_like of float
            The run's sample times (s).
        angle_at : callable
            Time (s) -> the true curve angle (rad).
        seed_offset : int, default 0
            Added to the seed, so that runs get different noise.

        Returns
        -------
        index : numpy.ndarray of int
            The sample index of each reading.
        sensed : numpy.ndarray of float
            The sensed angle of each reading (rad, >= 0).
        """
        t = np.asarray(t, dtype=float)
        idx = self._reading_index(t)
        rng = np.random.default_rng(_SEED_BASE + self.seed + seed_offset)
        sensed = np.array([angle_at(self._sensed_time(t, k)) for k in idx], dtype=float)
        sensed = sensed + rng.normal(0.0, self.noise_std, sensed.size)
        return idx, np.maximum(sensed, 0.0)

    def static_reading(self, angle: float, duration: float, seed_offset: int = 0) -> float:
        """The median of the readings over a run on a route held still: the angle a user
        records for a calibration shape.

        Parameters
        ----------
        angle : float
            The true curve angle (rad).
        duration : float
            Length of the run (s).
        seed_offset : int, default 0
            Added to the seed.

        Returns
        -------
        float
            The recorded angle (rad).
        """
        t = np.arange(0.0, duration, 1.0 / self.rate_hz)
        _, sensed = self.readings(t, lambda _t: float(angle), seed_offset)
        return float(np.median(sensed))

    # -- routes ----------------------------------------------------------------------------
    def route_readings(
        self, t: np.ndarray, route_at: Callable[[float], Any], seed_offset: int = 0
    ) -> tuple[np.ndarray, list[Route]]:
        """(sample index of each reading, sensed route of each reading) over times t.

        Parameters
        ----------
        t : array_like of float
            The run's sample times (s).
        route_at : callable
            Time (s) -> the true Route (or a (route1, route2) pair: route1 is sensed).
        seed_offset : int, default 0
            Added to the seed, so that runs get different noise.

        Returns
        -------
        index : numpy.ndarray of int
            The sample index of each reading.
        routes : list of Route
            The sensed route of each reading: ``Route.uniform(L, sensed angle)`` with
            ``segments=0`` (the angles of :meth:`readings`, bit for bit), else K equal arcs
            of the sensed bend angles (L: the true route's length).
        """
        t = np.asarray(t, dtype=float)
        if self.segments == 0:
            idx, sensed = self.readings(
                t, lambda tk: _first_route(route_at(tk)).curve_angle, seed_offset
            )
            lengths = [_first_route(route_at(self._sensed_time(t, k))).length for k in idx]
            return idx, [Route.uniform(L, float(a)) for L, a in zip(lengths, sensed, strict=True)]
        idx, lengths, bends = self._profile_readings(t, route_at, seed_offset)
        return idx, [self._arcs(L, b) for L, b in zip(lengths, bends, strict=True)]

    def static_route(self, route: Route, duration: float, seed_offset: int = 0) -> Route:
        """The sensed route of a route held still over a run: the median of the readings, arc
        by arc (the shape a user records for a calibration run).

        Parameters
        ----------
        route : Route
            The true route.
        duration : float
            Length of the run (s).
        seed_offset : int, default 0
            Added to the seed.

        Returns
        -------
        Route
            ``Route.uniform(L, static_reading(...))`` with ``segments=0``, else K equal arcs
            of the median sensed bend angles.
        """
        if self.segments == 0:
            angle = self.static_reading(route.curve_angle, duration, seed_offset)
            return Route.uniform(route.length, angle)
        t = np.arange(0.0, duration, 1.0 / self.rate_hz)
        _, _, bends = self._profile_readings(t, lambda _t: route, seed_offset)
        return self._arcs(route.length, np.median(bends, axis=0))

    def arc_angles(self, route: Route) -> np.ndarray:
        """The true bend angle of each of the K equal arcs of a route (no noise, no delay).

        Parameters
        ----------
        route : Route
            The route.

        Returns
        -------
        numpy.ndarray of float, shape (K,)
            theta at each arc's distal end minus theta at its proximal end (rad); they sum to
            the curve angle.
        """
        if self.segments == 0:
            raise ValueError("ShapeSensing.arc_angles: segments is 0 (the curve angle only)")
        return np.diff(np.asarray(route.angle_at(self._edges(route.length)), dtype=float))

    # -- helpers ---------------------------------------------------------------------------
    def _profile_readings(
        self, t: np.ndarray, route_at: Callable[[float], Any], seed_offset: int
    ) -> tuple[np.ndarray, list[float], np.ndarray]:
        """(reading indices, true lengths, sensed bends (readings x K)) of a profile sensor."""
        idx = self._reading_index(t)
        true = [_first_route(route_at(self._sensed_time(t, k))) for k in idx]
        bends = np.array([self.arc_angles(r) for r in true]).reshape(idx.size, self.segments)
        return idx, [r.length for r in true], self._noisy(bends, seed_offset)

    def _reading_index(self, t: np.ndarray) -> np.ndarray:
        period = 1.0 / self.rate_hz
        times = np.arange(t[0], t[-1] + 0.5 * period, period)
        return np.unique(np.searchsorted(t, times, side="left").clip(0, t.size - 1))

    def _sensed_time(self, t: np.ndarray, k: int) -> float:
        """The time whose route reading k reports: ``delay`` before its sample, >= t[0]."""
        return max(float(t[k]) - self.delay, float(t[0]))

    def _edges(self, length: float) -> np.ndarray:
        edges = np.linspace(0.0, length, self.segments + 1)
        edges[-1] = length
        return edges

    def _noisy(self, bends: np.ndarray, seed_offset: int) -> np.ndarray:
        """Per-arc noise of std noise_std / sqrt(K), clipped at >= 0."""
        rng = np.random.default_rng(_SEED_BASE + self.seed + seed_offset)
        std = self.noise_std / math.sqrt(self.segments)
        return np.maximum(bends + rng.normal(0.0, std, bends.shape), 0.0)

    def _arcs(self, length: float, bends: np.ndarray) -> Route:
        piece = length / self.segments
        return Route.arcs([(piece, float(b)) for b in bends])


def sensed_route_schedule(
    shape: ShapeSensing,
    t: np.ndarray,
    routes: Callable[[float], Any],
    friction: float,
    seed_offset: int = 0,
) -> tuple[np.ndarray, list[Route], np.ndarray]:
    """What a compensator that follows the route is told during a run: the sensed routes and
    one (g, G, Theta) row per reading, g and G of the sensed route at ``friction`` (the
    compensator's own).

    Parameters
    ----------
    shape : ShapeSensing
        The shape sensor (the curve angle only, or the profile in K arcs).
    t : array_like of float
        The run's sample times (s).
    routes : callable
        Time (s) -> the true Route (or a (route1, route2) pair: route1 is sensed).
    friction : float
        The friction coefficient g and G are computed with.
    seed_offset : int, default 0
        Added to the sensor's seed.

    Returns
    -------
    index : numpy.ndarray of int
        The sample index of each reading.
    sensed : list of Route
        The sensed route of each reading.
    rows : numpy.ndarray of float, shape (readings, 3)
        g, G and Theta of each sensed route (C-contiguous).
    """
    idx, sensed = shape.route_readings(t, routes, seed_offset)
    rows = []
    for route in sensed:
        # a uniform reading's g, G do not depend on its length: computed on a unit length, as
        # sensed_schedule does, so that segments=0 gives its rows bit for bit
        of = Route.uniform(1.0, route.curve_angle) if shape.segments == 0 else route
        s = route_shape(of, friction)
        rows.append([s.g, s.G, s.curve_angle])
    return idx, sensed, np.ascontiguousarray(rows, dtype=float).reshape(-1, 3)


def sensed_schedule(shape: ShapeSensing, t, routes: Callable, friction: float, seed_offset=0):
    """What a curve-angle compensator is told during a test run: sample indices and one
    (g, G, Theta) row per reading, for a uniform route of the sensed angle."""

    def angle_at(tk: float) -> float:
        r = routes(tk)
        r = r[0] if isinstance(r, tuple | list) else r
        return float(r.curve_angle)

    idx, sensed = shape.readings(t, angle_at, seed_offset)
    rows = []
    for a in sensed:
        s = route_shape(Route.uniform(1.0, float(a)), friction)
        rows.append([s.g, s.G, s.curve_angle])
    return idx, sensed, np.ascontiguousarray(rows, dtype=float)


__all__ = ["sensed_schedule", "ShapeSensing", "sensed_route_schedule"]
