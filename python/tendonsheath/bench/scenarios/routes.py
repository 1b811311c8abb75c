"""Random routes for robustness studies."""

from __future__ import annotations

import numpy as np

from ...plant.route import Route


def random_arcs(length: float, curve_angle: float, pieces: int, seed: int) -> Route:
    """A route of ``pieces`` arcs with random lengths and a random share of the total angle
    each (Dirichlet(1) splits, from ``seed``); ``pieces=1`` is the uniform route."""
    pieces = int(pieces)
    if pieces <= 1:
        return Route.uniform(length, curve_angle)
    rng = np.random.default_rng(int(seed))
    lengths = rng.dirichlet(np.ones(pieces)) * length
    angles = rng.dirichlet(np.ones(pieces)) * curve_angle
    return Route.arcs(list(zip(lengths.tolist(), angles.tolist(), strict=True)))


__all__ = ["random_arcs"]
