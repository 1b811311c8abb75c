"""Recordings for identification: normalisation and checks of the user's arrays."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._util.arrays import as_vector
from .._util.units import CURVE_ANGLE, warn_if_unit_slip
from ..plant.route import Route, check_curve_angle
from ._bound import RecordingSet

MIN_SAMPLES = 20  # fitted samples per fit (after warm-up), at the very least


@dataclass
class Recording:
    """One experiment: times (or None), input, measured output, curve angle per sample (or None)
    and, when the route's shape was sensed, the route (held over the recording; curve_angle is
    then its total angle)."""

    t: np.ndarray | None
    x: np.ndarray
    y: np.ndarray
    curve_angle: np.ndarray | None = None
    skip: int = 0  # leading samples simulated but not counted (on top of the warm-up)
    route: Route | None = None
    load: np.ndarray | None = None  # the measured load of every sample (a Loaded model's)

    @property
    def n(self) -> int:
        return int(self.x.size)

    @property
    def angle_input(self) -> Route | np.ndarray | None:
        """What a model that takes the curve angle is given: the route, else the angles."""
        return self.route if self.route is not None else self.curve_angle

    def take(self, index, skip: int = 0) -> Recording:
        """The samples at ``index`` (a slice or an index array), as a recording of their own."""
        return Recording(
            None if self.t is None else self.t[index],
            self.x[index],
            self.y[index],
            None if self.curve_angle is None else self.curve_angle[index],
            skip,
            self.route,
            None if self.load is None else self.load[index],
        )

    def angle(self) -> float | None:
        """The recording's curve angle when it is constant, else None."""
        if self.route is not None:
            return float(self.route.curve_angle)
        if self.curve_angle is None:
            return None
        first = float(self.curve_angle[0])
        return first if np.all(self.curve_angle == first) else None


def _vector(values, what: str) -> np.ndarray:
    arr = as_vector(values, what)
    bad = np.flatnonzero(~np.isfinite(arr))
    if bad.size:
        raise ValueError(f"{what} has a non-finite value ({arr[bad[0]]}) at sample {bad[0]}")
    return arr


def _unpack(item, index: int):
    """(t, x, y[, curve_angle]) or an object with t, x, y[, curve_angle] attributes."""
    if hasattr(item, "x") and hasattr(item, "y"):
        route = getattr(item, "route", None)  # a Recording's sensed route, when it has one
        angle = getattr(item, "curve_angle", None) if route is None else route
        return item.t, item.x, item.y, angle
    if not isinstance(item, tuple | list) or len(item) not in (3, 4):
        raise ValueError(
            f"recording {index} must be (t, x, y) or (t, x, y, curve_angle), "
            f"got {type(item).__name__}"
        )
    return (*item, None) if len(item) == 3 else tuple(item)


def make_recordings(
    t=None,
    x=None,
    y=None,
    *,
    recordings: Sequence | None = None,
    curve_angle=None,
) -> list[Recording]:
    """Normalise the two calling forms of identify() into checked Recordings."""
    if recordings is None:
        if x is None or y is None:
            raise ValueError("give x and y (and t), or recordings=[(t, x, y), ...]")
        items = [(t, x, y, curve_angle)]
    else:
        if x is not None or y is not None:
            raise ValueError("give either x and y or recordings, not both")
        if isinstance(recordings, tuple) and len(recordings) in (3, 4):
            recordings = [recordings]
        items = [_unpack(item, i) for i, item in enumerate(recordings)]
        skips = [int(getattr(item, "skip", 0)) for item in recordings]
        loads = [getattr(item, "load", None) for item in recordings]
        if curve_angle is not None:
            items = [(a, b, c, curve_angle if d is None else d) for a, b, c, d in items]
    if not items:
        raise ValueError("no recordings given")
    if recordings is None:
        skips, loads = [0], [None]
    out = []
    for i, (ti, xi, yi, ai) in enumerate(items):
        who = "" if len(items) == 1 else f"recording {i}: "
        xs = _vector(xi, f"{who}input x")
        ys = _vector(yi, f"{who}output y")
        if ys.size != xs.size:
            raise ValueError(f"{who}x and y have different lengths ({xs.size} and {ys.size})")
        _check_scale(xs, f"{who}input x")
        _check_scale(ys, f"{who}output y")
        if np.array_equal(xs, ys):
            raise ValueError(
                f"{who}the output y is the input x, sample for sample (the same column read "
                "twice?): a fit would be the identity, not the drive; read the output from "
                "its own column"
            )
        ts = None
        if ti is not None:
            ts = _vector(ti, f"{who}time t")
            if ts.size != xs.size:
                raise ValueError(f"{who}t and x have different lengths ({ts.size} and {xs.size})")
            steps = np.diff(ts)
            bad = np.flatnonzero(~(steps > 0))
            if bad.size:
                k = bad[0] + 1
                raise ValueError(
                    f"{who}time is not strictly increasing at sample {k} "
                    f"(t[{k}] = {ts[k]} after t[{k - 1}] = {ts[k - 1]})"
                )
        theta, route = _angles(ai, xs.size, who)
        load = None
        if loads[i] is not None:
            load = _vector(loads[i], f"{who}load")
            if load.size != xs.size:
                raise ValueError(f"{who}load and x have different lengths ({load.size}, {xs.size})")
        out.append(Recording(ts, xs, ys, theta, skips[i], route, load))
    return out


def _angles(value, n: int, who: str) -> tuple[np.ndarray | None, Route | None]:
    """(curve angle per sample, route) of a recording's 4th item: None, a number, n numbers,
    or a Route (the sensed shape, held over the recording: its total angle per sample)."""
    if value is None:
        return None, None
    route = value if isinstance(value, Route) else None
    if route is not None:
        theta = np.full(n, float(route.curve_angle))
    elif np.ndim(value) == 0:
        theta = np.full(n, float(value))
        if not np.isfinite(theta[0]):
            raise ValueError(f"{who}curve angle is not finite ({value})")
    else:
        theta = _vector(value, f"{who}curve angle")
        if theta.size != n:
            raise ValueError(
                f"{who}curve angle and x have different lengths ({theta.size} and {n})"
            )
    check_curve_angle(theta, f"{who}curve angle")
    if theta.size:
        top = float(np.max(np.abs(theta)))
        warn_if_unit_slip(top, f"identify: {who}curve_angle", "(largest)", CURVE_ANGLE)
    return theta, route


# squared errors summed over ~1e6 samples stay normal doubles (1e-308 .. 1e308) in this range
_SCALE_RANGE = (1e-150, 1e150)


def _check_scale(values: np.ndarray, what: str) -> None:
    """Magnitudes whose squares under- or overflow make every metric 0, inf or nan."""
    big = float(np.max(np.abs(values))) if values.size else 0.0
    if big > _SCALE_RANGE[1] or 0.0 < big < _SCALE_RANGE[0]:
        raise ValueError(
            f"{what} reaches {big:.3g}: outside {_SCALE_RANGE[0]:g} .. {_SCALE_RANGE[1]:g}, its "
            "squared errors under- or overflow; rescale the data (e.g. to rad or mm)"
        )


def check_for_fit(
    recs: list[Recording], warmup: int, n_params: int, needs_time: bool, needs_angle: bool
) -> None:
    """Reject data from which nothing can be identified, with a reason."""
    if int(warmup) != warmup or warmup < 0:
        raise ValueError(f"warmup must be a number of samples >= 0 (got {warmup})")
    fitted = 0
    for i, r in enumerate(recs):
        who = "" if len(recs) == 1 else f"recording {i}: "
        if needs_time and r.t is None:
            raise ValueError(f"{who}this model is rate-dependent: the time t is required")
        if needs_angle and r.curve_angle is None:
            raise ValueError(f"{who}this model needs the curve angle of every recording")
        if r.n <= warmup + r.skip:
            raise ValueError(f"{who}warm-up ({warmup} samples) leaves none of its {r.n} samples")
        fitted += r.n - warmup - r.skip
    if fitted < max(MIN_SAMPLES, 3 * n_params):
        raise ValueError(
            f"too few samples to identify {n_params} parameters: {fitted} after warm-up "
            f"(at least {max(MIN_SAMPLES, 3 * n_params)} are needed)"
        )
    x_all = np.concatenate([r.x for r in recs])
    y_all = np.concatenate([r.y[warmup:] for r in recs])
    if np.ptp(x_all) == 0.0:
        raise ValueError("the input is constant: it excites nothing to identify")
    if np.ptp(y_all) == 0.0:
        raise ValueError("the output is constant: there is nothing to identify")


def recording_set(recs: list[Recording], warmup: int, with_angle: bool) -> RecordingSet:
    """Pack recordings for the batched C++ evaluation (``with_angle``: the curve angles and
    the routes of the recordings that have one, for a model that takes them)."""
    has_t = all(r.t is not None for r in recs)
    t = np.concatenate([r.t for r in recs]) if has_t else None
    theta = np.concatenate([r.curve_angle for r in recs]) if with_angle else None
    routes = [r.route if with_angle else None for r in recs]
    counts = [0 if r is None else int(r.s.size) for r in routes]
    route_s = route_theta = None
    if any(counts):
        route_s = np.concatenate([r.s for r in routes if r is not None])
        route_theta = np.concatenate([r.theta for r in routes if r is not None])
    return RecordingSet(
        t,
        np.concatenate([r.x for r in recs]),
        np.concatenate([r.y for r in recs]),
        theta,
        [r.n for r in recs],
        [int(warmup) + r.skip for r in recs],
        route_s=route_s,
        route_theta=route_theta,
        route_counts=counts if any(counts) else [],
    )


def search_windows(
    recs: list[Recording], warmup: int, budget: int, windows: int = 8
) -> tuple[list[Recording], int]:
    """Recordings for the global search of a long record: ``windows`` evenly spaced windows per
    recording, ``budget`` samples in all (in proportion to each recording's length), each
    starting from the model's rest state with a warm-up of max(warmup, a fifth of the window)
    not counted. Returns the windows and their warm-up; recordings already within the budget
    come back whole."""
    total = sum(r.n for r in recs)
    if budget <= 0 or total <= budget:
        return recs, warmup
    out = []
    length = max(1, budget // (windows * len(recs)))
    win_warmup = max(warmup, length // 5)
    for r in recs:
        size = min(r.n, length + win_warmup)
        starts = np.linspace(0, r.n - size, windows).astype(int)
        for s in np.unique(starts):
            sl = slice(int(s), int(s) + size)
            out.append(r.take(sl))
    return out, win_warmup


def fitted_mask(recs: list[Recording], warmup: int) -> np.ndarray:
    """True for the concatenated samples that enter the cost."""
    return np.concatenate([np.arange(r.n) >= warmup + r.skip for r in recs])


#: samples the global search of a rate-independent model runs on (see thin_for_search)
SEARCH_THIN = 2000
#: at most every this-many-th sample is kept (a Bouc-Wen state integrates the input's steps)
MAX_THIN_STEP = 20


def _kept(x: np.ndarray, step: int, first_counted: int) -> np.ndarray:
    """Every ``step``-th sample, the input's turning points, the ends and the first counted
    sample."""
    dx = np.diff(x)
    moving = np.flatnonzero(dx != 0.0)
    turns = moving[1:][np.sign(dx[moving[1:]]) != np.sign(dx[moving[:-1]])]  # reversal at i
    keep = np.zeros(x.size, dtype=bool)
    keep[::step] = True
    keep[turns] = True
    keep[[0, x.size - 1, min(first_counted, x.size - 1)]] = True
    return np.flatnonzero(keep)


#: samples the global search of a dynamic chain runs on (see decimate_for_search)
DYNAMIC_SEARCH_SAMPLES = 4000
#: at most every this-many-th sample (the lag's discretisation on the coarser step)
MAX_DECIMATION = 4


def _search_step(recs: list[Recording], budget: int, most: int) -> int:
    """Every how many samples a global search keeps to see about ``budget`` of them (at most
    every ``most``-th; 1: all)."""
    total = sum(r.n for r in recs)
    return min(int(np.ceil(total / max(budget, 1))), most)


def decimate_for_search(
    recs: list[Recording], warmup: int, budget: int | None = None
) -> tuple[list[Recording], int]:
    """Recordings decimated for the global search of a dynamic chain: every m-th sample
    (m <= MAX_DECIMATION), about ``budget`` samples in all, so the time step stays uniform
    (a linear block needs one; thin_for_search's turning points would break it). The search
    needs the basin; the refinement runs on every sample. Warm-up and skipped samples map to
    the kept ones (returned warm-up 0, per-recording skip); records within the budget come
    back whole (``budget`` default DYNAMIC_SEARCH_SAMPLES)."""
    step = _search_step(recs, DYNAMIC_SEARCH_SAMPLES if budget is None else budget, MAX_DECIMATION)
    if step <= 1:
        return recs, warmup
    out = []
    for r in recs:
        first = int(warmup) + r.skip
        out.append(r.take(slice(0, None, step), int(np.ceil(first / step))))
    return out, 0


def thin_for_search(
    recs: list[Recording], warmup: int, budget: int | None = None
) -> tuple[list[Recording], int]:
    """Recordings thinned for the global search of a rate-independent model: about
    ``budget`` samples in all (every m-th sample, m <= MAX_THIN_STEP), with every turning
    point of the input kept, so an operator's state at the kept samples is (almost) the
    one the whole record builds: the search needs the basin, and the refinement uses every
    sample. Warm-up and skipped samples map to the kept ones (returned warm-up 0,
    per-recording skip). Records within the budget, or of which more than 3/4 would be
    kept (turning points everywhere: a noisy input), come back whole."""
    total = sum(r.n for r in recs)
    step = _search_step(recs, SEARCH_THIN if budget is None else budget, MAX_THIN_STEP)
    if step <= 1:
        return recs, warmup
    out = []
    for r in recs:
        first = int(warmup) + r.skip
        idx = _kept(r.x, step, first)
        out.append(r.take(idx, int(np.searchsorted(idx, first))))
    if sum(r.n for r in out) > 0.75 * total:
        return recs, warmup
    return out, 0


__all__ = [
    "DYNAMIC_SEARCH_SAMPLES",
    "MAX_DECIMATION",
    "MAX_THIN_STEP",
    "MIN_SAMPLES",
    "Recording",
    "SEARCH_THIN",
    "check_for_fit",
    "decimate_for_search",
    "fitted_mask",
    "make_recordings",
    "recording_set",
    "search_windows",
    "thin_for_search",
]
