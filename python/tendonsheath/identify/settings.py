"""The settings of an identification: a HystereticOscillator's own ones
(:data:`OSCILLATOR_DEFAULTS`; the others and their defaults are written once, in
:class:`~tendonsheath.identify.estimator.Identifier`'s signature, which
:class:`~tendonsheath.identify.estimator.Options` reads), their checks, and the checked search
settings every identification path takes (:class:`Search`: one object passed down instead of
a dozen keywords).
"""

from __future__ import annotations

import dataclasses
import difflib
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from .refine import TimeBudget

if TYPE_CHECKING:
    from .estimator import Options


#: the settings only a HystereticOscillator's identification reads, with their defaults: an
#: Identifier takes them grouped in its ``oscillator`` dict, identify() as keywords among the
#: others (every other setting and its default is written once, in Identifier's signature)
OSCILLATOR_DEFAULTS: dict[str, Any] = {
    "input_interpolation": None,
    "periodic": None,
    "strategy": "auto",
}
OSCILLATOR_NAMES: tuple[str, ...] = tuple(OSCILLATOR_DEFAULTS)


def check_names(names, owner: str, known: tuple[str, ...]) -> None:
    """TypeError naming the settings not among ``known`` (with the closest known ones)."""
    unknown = [n for n in names if n not in known]
    if unknown:
        hints = [m for n in unknown for m in difflib.get_close_matches(n, known, 1)]
        hint = f" (did you mean {', '.join(hints)}?)" if hints else ""
        raise TypeError(
            f"{owner}: unknown setting(s) {', '.join(map(repr, unknown))}{hint}; "
            f"known: {', '.join(known)}"
        )


def oscillator_settings(group: Any, owner: str) -> dict[str, Any]:
    """An Identifier's ``oscillator`` group (None or a dict with keys among
    :data:`OSCILLATOR_NAMES`) as the three settings with their defaults; TypeError naming a
    group that is no dict or an unknown key."""
    if group is None:
        group = {}
    if not isinstance(group, dict):
        raise TypeError(
            f"{owner}: oscillator must be a dict with keys among {list(OSCILLATOR_NAMES)} "
            f"(got {type(group).__name__})"
        )
    check_names(group, f"{owner}: oscillator", OSCILLATOR_NAMES)
    return {n: group.get(n, default) for n, default in OSCILLATOR_DEFAULTS.items()}


def check_search_options(*, maxiter, popsize, tol, workers, warmup) -> None:
    """The global search's settings, checked once with a message naming the option."""
    counts = (("maxiter", maxiter, 0), ("popsize", popsize, 1), ("warmup", warmup, 0))
    for name, value, low in counts:
        if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
            raise ValueError(f"{name} must be an integer >= {low} (got {value!r})")
    if workers is not None and (
        isinstance(workers, bool) or not isinstance(workers, int | np.integer) or workers < 1
    ):
        raise ValueError(f"workers must be an integer >= 1 or None (got {workers!r})")
    if isinstance(tol, bool) or not isinstance(tol, int | float) or not tol >= 0:
        raise ValueError(f"tol must be a number >= 0 (got {tol!r})")


def default_threads() -> int:
    """``TENDONSHEATH_NUM_THREADS`` when set to a positive integer, else 0 (all cores)."""
    value = os.environ.get("TENDONSHEATH_NUM_THREADS", "").strip()
    if not value:
        return 0
    try:
        n = int(value)
    except ValueError:
        raise ValueError(
            f"TENDONSHEATH_NUM_THREADS must be a positive integer (got {value!r})"
        ) from None
    if n < 1:
        raise ValueError(f"TENDONSHEATH_NUM_THREADS must be a positive integer (got {value!r})")
    return n


SE_METHODS = ("linearised", "bootstrap", "bootstrap-recordings", "none")
BOOTSTRAP_DEFAULT = 200


def check_method(standard_errors: str, count: int | None) -> tuple[str, int]:
    """``standard_errors`` (one of :data:`SE_METHODS`) and the bootstrap's resample count
    (``count``, default :data:`BOOTSTRAP_DEFAULT`, at least 2 for a bootstrap), checked."""
    if standard_errors not in SE_METHODS:
        raise ValueError(
            f"standard_errors must be one of {list(SE_METHODS)} (got {standard_errors!r})"
        )
    n = BOOTSTRAP_DEFAULT if count is None else int(count)
    if standard_errors.startswith("bootstrap") and n < 2:
        raise ValueError(f"bootstrap must be at least 2 resamples (got {count})")
    return standard_errors, n


@dataclasses.dataclass(frozen=True)
class Search:
    """The global search, refinement and standard-error settings, checked; ``budget`` is the
    running :class:`TimeBudget` (shared by nested fits)."""

    seed: int | None
    maxiter: int
    popsize: int
    tol: float
    workers: int | None
    polish: bool
    progress: bool
    standard_errors: str
    bootstrap: int
    bootstrap_block: int | None
    budget: TimeBudget

    @property
    def n_workers(self) -> int:
        """The thread count for the batched C++ calls: ``workers``, else the environment's
        ``TENDONSHEATH_NUM_THREADS`` (a sweep's local worker processes set it to their share
        of the cores), else 0 (all cores)."""
        if self.workers is not None:
            return int(self.workers)
        return default_threads()

    @classmethod
    def of(cls, options: Options) -> Search:
        """Check ``options``' search settings (one message naming the option) and start the
        time budget (a TimeBudget given as ``time_budget`` is shared, not restarted)."""
        o = options
        check_search_options(
            maxiter=o.maxiter, popsize=o.popsize, tol=o.tol, workers=o.workers, warmup=o.warmup
        )
        method, count = check_method(o.standard_errors, o.bootstrap)
        for name in ("bootstrap", "bootstrap_block"):
            if getattr(o, name) is not None and not method.startswith("bootstrap"):
                raise ValueError(
                    f"{name}={getattr(o, name)} applies to standard_errors='bootstrap' or "
                    f"'bootstrap-recordings' only (got standard_errors={method!r}): give one "
                    f"of those, or leave {name} out"
                )
        budget = o.time_budget
        if not isinstance(budget, TimeBudget):
            budget = TimeBudget(budget)
        return cls(
            seed=o.seed,
            maxiter=o.maxiter,
            popsize=o.popsize,
            tol=o.tol,
            workers=o.workers,
            polish=o.polish,
            progress=o.progress,
            standard_errors=method,
            bootstrap=count,
            bootstrap_block=o.bootstrap_block,
            budget=budget,
        )


__all__ = [
    "BOOTSTRAP_DEFAULT",
    "OSCILLATOR_DEFAULTS",
    "OSCILLATOR_NAMES",
    "SE_METHODS",
    "Search",
    "check_method",
    "check_names",
    "check_search_options",
    "default_threads",
    "oscillator_settings",
]
