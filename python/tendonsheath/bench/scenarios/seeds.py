"""The bench protocol for random routes: a figure is the median and the minimum over seeds.

One random route schedule is one draw: the same compensator's MSE reduction varied up to 4x
between schedules in the lead's trials. :func:`over_route_seeds` runs every compensator on the
schedules of several seeds and :func:`spread` summarises a factor by its median and minimum (the
worst schedule), the way every random-route figure of the bench is reported.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from .common import ratio

#: route-schedule seeds per random-route figure (the protocol's minimum)
ROUTE_SEEDS = 5


def over_route_seeds(
    seeds: Sequence[int], run_all: Callable[[int], dict[str, Any]]
) -> dict[int, dict[str, Any]]:
    """``run_all(seed)`` (compensator -> bench Result on that seed's route schedule) for each
    seed: seed -> its runs."""
    return {int(s): run_all(int(s)) for s in seeds}


def factors(runs_by_seed: dict[int, dict[str, Any]], baseline: str = "none") -> dict[str, list]:
    """compensator -> its MSE reduction over ``baseline`` on each seed (in seed order)."""
    out: dict[str, list[float]] = {}
    for runs in runs_by_seed.values():
        base = runs[baseline].metrics["mse"]
        for name, result in runs.items():
            out.setdefault(name, []).append(ratio(base, result.metrics["mse"]))
    return out


def spread(values: Sequence[float]) -> dict[str, Any]:
    """Median, minimum and maximum of a figure over seeds, and the values themselves.

    Parameters
    ----------
    values : sequence of float
        The figure on each seed.

    Returns
    -------
    dict
        median, min, max, values and seeds (the count).
    """
    v = np.asarray(values, dtype=float)
    return {
        "median": float(np.median(v)),
        "min": float(v.min()),
        "max": float(v.max()),
        "values": [float(x) for x in v],
        "seeds": int(v.size),
    }


__all__ = ["ROUTE_SEEDS", "factors", "over_route_seeds", "spread"]
