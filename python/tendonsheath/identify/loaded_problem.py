"""The residual of a :class:`~tendonsheath.models.Loaded` fit: which of the base's parameters
are searched, which are solved by (bounded) linear least squares for every candidate, and the
simulation errors over the recordings.

Linear in the output, so solved for every candidate instead of searched:

- the load's ``gain`` (the tendon's stretch, output per unit load; any sign);
- a Scaled base's ``output_offset`` (any sign);
- the play weights of a Prandtl-Ishlinskii or generalized Prandtl-Ishlinskii base, kept
  non-negative (the first > 0) so the fitted operator stays invertible: their regressors are
  the base's output changes per unit weight (exact, the output is linear in the weights),
  the sign of the output set by a Scaled base's ``output_gain`` (held). The thresholds then
  move together, by one log-scale factor (``thresholds*``); the generalized model's rising
  envelope keeps its amplitude and level (the weights carry the output's scale and level).
"""

from __future__ import annotations

import numpy as np

from ..models import GeneralizedPrandtlIshlinskii, HysteresisModel, PrandtlIshlinskii, Scaled
from ..models.loaded import Loaded, play, play_radius

#: the play's terms searched by least squares (gain is solved in closed form)
SEARCHED = ("slack", "slack_load", "friction")
_WEIGHTED = (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii)
_SCALE = "thresholds*"  # the pseudo-parameter: log of the thresholds' common factor
#: how far (log) the thresholds' factor may move from the base's own: a factor 20 either way
#: (unbounded, the plays can shrink to nothing while the load's play takes their loop)
_SPREAD = 3.0


def weighted(base: HysteresisModel) -> bool:
    """Whether the base's output is a non-negative weighting of plays (PI, GPI)."""
    inner = base.inner if isinstance(base, Scaled) else base
    return isinstance(inner, _WEIGHTED)


def prefix(base: HysteresisModel) -> str:
    """The name prefix of the inner model's parameters (``inner.`` in a Scaled base)."""
    return "inner." if isinstance(base, Scaled) else ""


def _held(base: HysteresisModel) -> set[str]:
    """Parameters neither searched nor moved: solved linearly, or redundant with those."""
    if not weighted(base):
        return {"output_offset"} if isinstance(base, Scaled) else set()
    p = prefix(base)
    held = {"output_offset", "output_gain", "input_offset", "input_scale"}
    held |= {f"{p}weights", f"{p}thresholds", f"{p}rising_a", f"{p}rising_d"}
    return held


def base_vector(base: HysteresisModel) -> tuple[list[str], np.ndarray]:
    """The base's float parameters that are searched (names, values; a list parameter item by
    item as ``name[i]``; a weighted base's thresholds as one factor): the linear ones, a
    discrete setting or an integer exponent stay out."""
    held = _held(base)
    names, values = [], []
    if weighted(base):
        names, values = [_SCALE], [0.0]
    for k, v in base.params.items():
        if k in held:
            continue
        items = list(enumerate(v)) if isinstance(v, list) else [(None, v)]
        for i, vi in items:
            if not isinstance(vi, float) or not np.isfinite(vi):
                continue
            name = k if i is None else f"{k}[{i}]"
            try:
                with_values(base, [name], [vi * (1.0 + 1e-6) + 1e-9])
            except (ValueError, TypeError):
                continue
            names.append(name)
            values.append(vi)
    return names, np.asarray(values, dtype=float)


def with_values(base: HysteresisModel, names: list[str], values) -> HysteresisModel:
    """``base`` with the named parameters (``name``, ``name[i]`` or the thresholds' log
    factor) set to ``values``."""
    if not names:
        return base
    params = base.params
    changes: dict = {}
    for name, value in zip(names, values, strict=True):
        if name == _SCALE:
            key = f"{prefix(base)}thresholds"
            changes[key] = [float(r * np.exp(value)) for r in params[key]]
        elif name.endswith("]"):
            key, index = name[:-1].split("[")
            changes.setdefault(key, list(params[key]))[int(index)] = float(value)
        else:
            changes[name] = float(value)
    return base.with_params(**changes)


def as_weighted(base: HysteresisModel) -> HysteresisModel:
    """A weighted base inside a Scaled map (identity) so that it has an output offset."""
    return Scaled(base) if weighted(base) and not isinstance(base, Scaled) else base


def _bounded_lstsq(a: np.ndarray, b: np.ndarray, lower: np.ndarray) -> np.ndarray:
    """argmin ||a c - b|| subject to c >= lower, through the normal equations (the Gram
    matrix by einsum: a few columns, no threaded BLAS call on the long side)."""
    from scipy.linalg import solve_triangular
    from scipy.optimize import lsq_linear

    gram = np.einsum("ij,ik->jk", a, a)
    rhs = np.einsum("ij,i->j", a, b)
    gram += np.eye(gram.shape[0]) * (1e-12 * float(np.trace(gram)) + 1e-300)
    chol = np.linalg.cholesky(gram)
    if not np.any(np.isfinite(lower)):
        return np.linalg.solve(gram, rhs)
    z = solve_triangular(chol, rhs, lower=True)  # ||chol^T c - z|| = ||a c - b|| + const
    return lsq_linear(chol.T, z, bounds=(lower, np.inf), method="bvls").x


class LinearPart:
    """The parts of the output solved by least squares: regressors and bounds per candidate."""

    def __init__(self, base: HysteresisModel, fixed_gain: float | None):
        self.weighted = weighted(base)
        self.offset = isinstance(base, Scaled)
        self.fixed_gain = fixed_gain
        if self.weighted:
            self.size = len(base.params[f"{prefix(base)}weights"])

    def outputs(self, base, run) -> list[np.ndarray]:
        """The base's output(s) over one recording's played input: one array, or for a
        weighted base the output at unit weights and its change per unit weight."""
        if not self.weighted:
            return [run(base)]
        key = f"{prefix(base)}weights"
        ones = np.ones(self.size)
        ref = run(base.with_params(**{key: ones.tolist()}))
        cols = []
        for i in range(self.size):
            w = ones.copy()
            w[i] += 1.0
            cols.append(run(base.with_params(**{key: w.tolist()})) - ref)
        return [ref, *cols]

    def solve(self, parts: list[np.ndarray], y: np.ndarray, load: np.ndarray):
        """(fitted output, coefficients): weights (>= 0), offset and gain by least squares."""
        if self.weighted:
            ref, cols = parts[0], parts[1:]
            base_out = ref - np.sum(cols, axis=0)  # the output at zero weights (the offset)
            target = y - base_out
        else:
            cols, target = [], y - parts[0]
        cols = list(cols)
        if self.offset:
            cols.append(np.ones_like(y))
        if self.fixed_gain is None:
            cols.append(load)
        else:
            target = target - self.fixed_gain * load
        if not cols:
            return y - target, np.zeros(0)
        a = np.column_stack(cols)
        lo = np.full(a.shape[1], -np.inf)
        if self.weighted:
            k = self.size
            lo[:k] = 0.0
            lo[0] = 1e-9 * float(np.max(np.abs(target))) / (float(np.max(np.abs(a[:, :k]))) or 1.0)
        coef = _bounded_lstsq(a, target, lo)
        return y - target + a @ coef, coef

    def apply(self, base: HysteresisModel, coef: np.ndarray) -> tuple[HysteresisModel, float]:
        """The base with the solved weights and offset, and the load's gain."""
        rest = [float(c) for c in coef]
        changes: dict = {}
        if self.weighted:
            changes[f"{prefix(base)}weights"] = [max(c, 0.0) for c in rest[: self.size]]
            rest = rest[self.size :]
        if self.offset:
            changes["output_offset"] = float(base.params["output_offset"]) + rest.pop(0)
        gain = rest.pop(0) if self.fixed_gain is None else float(self.fixed_gain)
        return (base.with_params(**changes) if changes else base), gain


class Problem:
    """The residual: base parameters (``joint``) and play terms in, simulation errors out."""

    def __init__(self, base, recs, loads, warmup: int, fixed: dict[str, float], joint: bool):
        self.base = as_weighted(base)
        self.recs, self.loads = recs, loads
        self.fixed = fixed
        names, values = base_vector(self.base) if joint else ([], np.zeros(0))
        self.base_names, self.base_values = names, np.asarray(values, dtype=float)
        self.free = [k for k in SEARCHED if k not in fixed]
        self.firsts = [int(warmup) + r.skip for r in recs]  # the first sample counted
        self.y = np.concatenate([r.y[k:] for r, k in zip(recs, self.firsts, strict=True)])
        self.load_all = np.concatenate([lo[k:] for lo, k in zip(loads, self.firsts, strict=True)])
        self.linear = LinearPart(self.base, fixed.get("gain"))

    def terms(self, p: np.ndarray) -> dict[str, float]:
        out = dict(self.fixed)
        out.pop("gain", None)
        for k, v in zip(self.free, p[len(self.base_names) :], strict=True):
            out[k] = float(np.exp(v)) if k == "slack_load" else max(float(v), 0.0)
        out.setdefault("slack", 0.0)
        out.setdefault("slack_load", 1.0)
        out.setdefault("friction", 0.0)
        return out

    def fitted(self, p: np.ndarray):
        """(fitted output, linear coefficients, base, play terms), or None for an invalid
        candidate."""
        terms = self.terms(p)
        try:
            base = with_values(self.base, self.base_names, p[: len(self.base_names)])
            stacks: list[list[np.ndarray]] = []
            for r, lo, k in zip(self.recs, self.loads, self.firsts, strict=True):
                radius = play_radius(lo, terms["slack"], terms["slack_load"], terms["friction"])
                z = play(r.x, radius)

                def run(model, r=r, z=z, k=k):
                    return np.asarray(model.simulate(r.t, z), dtype=float)[k:]

                stacks.append(self.linear.outputs(base, run))
        except (ValueError, TypeError):
            return None
        parts = [np.concatenate(col) for col in zip(*stacks, strict=True)]
        if not all(np.all(np.isfinite(c)) for c in parts):
            return None
        out, coef = self.linear.solve(parts, self.y, self.load_all)
        return out, coef, base, terms

    def residual(self, p: np.ndarray) -> np.ndarray:
        got = self.fitted(p)
        if got is None:
            return np.full(self.y.size, 1e3 * (np.ptp(self.y) + 1.0))
        return got[0] - self.y

    def start(self, terms: dict[str, float]) -> np.ndarray:
        """The parameter vector of the current base and the given play terms."""
        play_part = [np.log(terms[k]) if k == "slack_load" else terms[k] for k in self.free]
        return np.asarray([*self.base_values, *play_part], dtype=float)

    def bounds(self, x_span: float, load_scale: float) -> tuple[np.ndarray, np.ndarray]:
        """The search box: base parameters free (a weighted base's thresholds within a factor
        20 of its own); slack in [0, span], slack_load (log) over six decades around the
        median |load|, friction in [0, span / median |load|]."""
        lo = [-_SPREAD if k == _SCALE else -np.inf for k in self.base_names]
        hi = [_SPREAD if k == _SCALE else np.inf for k in self.base_names]
        box = {
            "slack": (0.0, x_span),
            "slack_load": (np.log(load_scale * 1e-3), np.log(load_scale * 1e3)),
            "friction": (0.0, x_span / load_scale),
        }
        for k in self.free:
            lo.append(box[k][0])
            hi.append(box[k][1])
        return np.asarray(lo), np.asarray(hi)

    def identified(self) -> list[str]:
        """The names identified: the base's (alone, then here) and the load terms."""
        out = sorted(f"base.{k}" for k in self.base.params) + self.free
        return out if "gain" in self.fixed else [*out, "gain"]

    def model(self, p: np.ndarray) -> Loaded:
        got = self.fitted(p)
        if got is None:
            raise ValueError("identification failed: the base model rejects the best point")
        _, coef, base, terms = got
        base, gain = self.linear.apply(base, coef)
        return Loaded(base, gain=gain, **terms)


__all__ = [
    "LinearPart",
    "Problem",
    "SEARCHED",
    "as_weighted",
    "base_vector",
    "prefix",
    "weighted",
    "with_values",
]
