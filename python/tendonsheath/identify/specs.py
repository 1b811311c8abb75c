"""What identification needs to know about each model: default bounds and parameterisation.

Bounds are derived from the data's scale when the user gives none. Parameters listed in
``log_names`` are searched on a log scale. Models with a linear-in-parameters part also
describe it (``separable``): the search then covers only the nonlinear parameters and the
linear ones follow from (bounded) linear least squares for every candidate.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..models import (
    Backlash,
    BoucWen,
    BoucWenBacklash,
    CurveAngleModel,
    GeneralizedPrandtlIshlinskii,
    HystereticOscillator,
    PrandtlIshlinskii,
)
from .data import Recording


@dataclass
class Scale:
    """The data's scale, from which default bounds are derived."""

    x_range: float
    y_range: float
    slope: float  # least-squares slope of y on x (absolute value, > 0)
    duration: float | None
    sample_time: float | None
    x_mid: float = 0.0

    @classmethod
    def of(cls, recs: list[Recording]) -> Scale:
        x = np.concatenate([r.x for r in recs])
        y = np.concatenate([r.y for r in recs])
        xr = float(np.ptp(x))
        yr = float(np.ptp(y))
        xc = x - x.mean()
        slope = abs(float(np.dot(xc, y - y.mean()) / max(np.dot(xc, xc), 1e-300)))
        if not slope > 0:
            slope = yr / xr
        duration = sample_time = None
        times = [r.t for r in recs if r.t is not None]
        if len(times) == len(recs):
            duration = float(max(t[-1] - t[0] for t in times))
            sample_time = float(np.median(np.concatenate([np.diff(t) for t in times])))
        return cls(xr, yr, slope, duration, sample_time, float(0.5 * (x.max() + x.min())))


class ModelSpec:
    """Defaults of one model class (subclass per model)."""

    model_class: type
    kind: str | None = None  # suffix of the batched C++ functions
    default_fixed: tuple[str, ...] = ()
    log_names: frozenset[str] = frozenset()
    search_names: tuple[str, ...] = ()
    separable = False
    # numerical options used during the global search only (see HystereticOscillatorSpec)
    search_options: dict = {}

    def bounds(self, s: Scale, fixed: dict[str, float]) -> dict[str, tuple[float, float]]:
        raise NotImplementedError


class BacklashSpec(ModelSpec):
    model_class = Backlash
    kind = "Backlash"

    def bounds(self, s, fixed):
        c = (0.2 * s.slope, 5.0 * s.slope)
        b = (0.0, 0.5 * s.x_range)
        return {"c_r": c, "c_l": c, "B_r": b, "B_l": b}


class BoucWenBacklashSpec(ModelSpec):
    """Separable: w depends on (rho, sigma, n) only and

    y = c_r [phi x] + (c_r B_r) [-phi] + c_l [(1 - phi) x] + (c_l B_l) [1 - phi],

    so (c_r, c_r B_r, c_l, c_l B_l) are solved by least squares with c > 0 and c B >= 0
    (this also absorbs a constant output offset into B_r and B_l).
    """

    model_class = BoucWenBacklash
    kind = "BoucWenBacklash"
    log_names = frozenset({"rho"})
    separable = True
    search_names = ("rho", "sigma", "n")
    # the global search integrates with RK4 sub-steps of rho |dx| <= 0.1 (the model's own
    # 0.05 in the refinement and the fit): half the work, the same basin on the shared
    # recordings and the plant data (benchmarks/realdata.py)
    search_options = {"max_step": 0.1}

    def bounds(self, s, fixed):
        c = (0.2 * s.slope, 5.0 * s.slope)
        b = (0.0, 0.5 * s.x_range)
        return {
            "c_r": c,
            "c_l": c,
            "B_r": b,
            "B_l": b,
            "rho": (0.5 / s.x_range, 500.0 / s.x_range),
            "sigma": (0.5, 5.0),
            "n": (1.0, 12.0),
        }

    def search_bounds(self, s, fixed):
        b = self.bounds(s, fixed)
        return {k: b[k] for k in self.search_names}

    def nonlinear(self, values: dict[str, np.ndarray]) -> np.ndarray:
        return np.column_stack([values["rho"], values["sigma"], values["n"]])

    def linear_bounds(self, s):
        tiny = 1e-9 * s.slope
        return np.array([tiny, 0.0, tiny, 0.0]), np.full(4, np.inf)

    def public(self, values: dict[str, float], theta: np.ndarray) -> dict[str, float]:
        c_r, cb_r, c_l, cb_l = (float(v) for v in theta)
        return {
            "c_r": c_r,
            "c_l": c_l,
            "B_r": max(cb_r / c_r, 0.0),
            "B_l": max(cb_l / c_l, 0.0),
            **{k: float(values[k]) for k in self.search_names},
        }


class BoucWenSpec(ModelSpec):
    """Separable: z depends on (A, beta, gamma, n) and y = a [x] + ((1 - a) k) [z].

    A is held at its value (1 by default): (A, beta, gamma, k) have a one-parameter scaling
    symmetry (z -> s z), so only three of them are identifiable. The search runs over the
    ultimate state z_u = (A/(beta + gamma))^(1/n), the ratio g = gamma/beta in [-0.95, 1] and n,
    which keeps |gamma| <= beta; a in [0, 1] and (1 - a) k are solved by least squares.
    """

    model_class = BoucWen
    kind = "BoucWen"
    default_fixed = ("A",)
    log_names = frozenset({"beta", "z_u"})
    separable = True
    search_names = ("z_u", "g", "n")

    def bounds(self, s, fixed):
        A = fixed.get("A", 1.0)
        half = 0.5 * s.x_range
        return {
            "A": (0.01 * A, 100.0 * A),
            "beta": (1e-3 / half, 1e3 / half),
            "gamma": (-1e3 / half, 1e3 / half),
            "n": (1.0, 6.0),
            "alpha": (0.0, 1.0),
            "k": (0.05 * s.slope, 20.0 * s.slope),
        }

    def search_bounds(self, s, fixed):
        return {"z_u": (s.x_range / 200.0, 2.0 * s.x_range), "g": (-0.95, 1.0), "n": (1.0, 6.0)}

    def nonlinear(self, values):
        A = values["A"]
        n = values["n"]
        beta = A * values["z_u"] ** (-n) / (1.0 + values["g"])
        return np.column_stack([np.broadcast_to(A, np.shape(n)), beta, values["g"] * beta, n])

    def linear_bounds(self, s):
        return np.array([0.0, -np.inf]), np.array([1.0, np.inf])

    def public(self, values, theta):
        nl = self.nonlinear({k: np.atleast_1d(v) for k, v in values.items()})[0]
        alpha = float(theta[0])
        k = float(theta[1]) / (1.0 - alpha) if alpha < 1.0 - 1e-12 else 1.0
        return {"A": nl[0], "beta": nl[1], "gamma": nl[2], "n": nl[3], "alpha": alpha, "k": k}


class HystereticOscillatorSpec(ModelSpec):
    """beta is held at its value (1 by default): beta enters only as beta*gamma and beta*delta.

    During the global search the RK4 sub-steps per sample are capped at 64: candidates that
    need more (a resonance or a damping time constant far beyond the sampling) are unstable
    there and rejected; the refinement and the fitted model use the model's own options.
    """

    model_class = HystereticOscillator
    kind = "HystereticOscillator"
    default_fixed = ("beta",)
    log_names = frozenset({"m", "c"})
    search_options = {"max_substeps": 64}

    def bounds(self, s, fixed):
        # x is the force, y the displacement: the static stiffness k + alpha ~ force/displacement.
        k_tot = s.x_range / max(s.y_range, 1e-300)
        w_lo = 2 * np.pi * 2.0 / (s.duration or 1.0)
        w_hi = 2 * np.pi / (10.0 * (s.sample_time or 1e-3))
        m_lo, m_hi = k_tot / w_hi**2, k_tot / w_lo**2
        c_ref = np.sqrt(k_tot * np.sqrt(m_lo * m_hi))
        beta = fixed.get("beta", 1.0)
        g = 20.0 * k_tot / (beta * 0.5 * s.x_range)
        return {
            "m": (m_lo, m_hi),
            "c": (1e-4 * c_ref, 10.0 * c_ref),
            "k": (0.0, 2.0 * k_tot),
            "alpha": (0.0, 2.0 * k_tot),
            "beta": (0.1 * beta, 10.0 * beta),
            "gamma": (-g, g),  # any sign: softening loops (gamma + delta < 0) included
            "delta": (-g, g),
            "nu": (1.0, 3.0),
        }


class CurveAngleModelSpec(ModelSpec):
    """pretension, length and the radii are held known; EA, mu and the load are identified.

    The load stiffness is held too (0 by default); free it with ``free=["load_stiffness"]``.
    """

    model_class = CurveAngleModel
    kind = "CurveAngleModel"
    default_fixed = (
        "pretension",
        "length",
        "proximal_radius",
        "distal_radius",
        "load_stiffness",
        "play",
    )
    log_names = frozenset({"stiffness"})

    def bounds(self, s, fixed):
        t0 = fixed.get("pretension", 10.0)
        length = fixed.get("length", 1.2)
        r_p = fixed.get("proximal_radius", 5e-3)
        ref = max(t0, 1e-3) * length / (r_p * s.x_range)  # EA giving a dead zone ~ x_range
        return {
            "friction": (0.01, 0.6),
            "stiffness": (0.02 * ref, 1e5 * ref),
            "pretension": (0.1 * t0, 10.0 * t0),
            "length": (0.1 * length, 10.0 * length),
            "load_force": (-2.0 * max(t0, 1e-3), 2.0 * max(t0, 1e-3)),
            "load_stiffness": (0.0, 1e5 * ref / length),
            "proximal_radius": (0.1 * r_p, 10.0 * r_p),
            "distal_radius": (0.1 * fixed.get("distal_radius", 5e-3), 10.0 * r_p),
            "play": (0.0, 0.2 * s.x_range),
        }


class PrandtlIshlinskiiSpec(ModelSpec):
    """Thresholds r_i = scale * pattern_i (pattern from the initial model, default 10 evenly
    spaced plays); the scale is searched and the weights are solved by least squares on the
    partial sums P_j = w_0 + ... + w_j >= 0 (so the fitted operator stays invertible).
    """

    model_class = PrandtlIshlinskii
    kind = "PrandtlIshlinskii"
    separable = True
    search_names = ("scale",)
    log_names = frozenset({"scale"})

    def __init__(self, pattern: np.ndarray):
        self.pattern = np.asarray(pattern, dtype=float)

    def bounds(self, s, fixed):
        return {"scale": (s.x_range / 100.0, s.x_range)}

    def search_bounds(self, s, fixed):
        return self.bounds(s, fixed)

    def nonlinear(self, values):
        return np.outer(values["scale"], self.pattern)

    def linear_bounds(self, s):
        k = self.pattern.size
        return np.full(k, 1e-9 * s.slope), np.full(k, np.inf)

    @staticmethod
    def to_partial_sums(features: np.ndarray) -> np.ndarray:
        """Regressors of the partial sums P_j: G_j = F_j - F_{j+1} (F_K = 0)."""
        g = features.copy()
        g[:, :-1] -= features[:, 1:]
        return g

    def public(self, values, theta):
        partial = np.asarray(theta, dtype=float)
        weights = np.diff(np.r_[0.0, partial])
        return {
            "thresholds": (float(values["scale"]) * self.pattern).tolist(),
            "weights": weights.tolist(),
        }


class GeneralizedPrandtlIshlinskiiSpec(ModelSpec):
    """Envelopes searched, weights by bounded least squares.

    The output scale is carried by the weights, so the rising envelope's amplitude is held at
    1; a common shift of both envelopes' d is an output offset (times the weights' sum), so
    the rising d is held at 0 and a constant column, solved with the weights, is folded back
    into both d's. Searched: rising b, c; falling a, b, c, d (relative to the rising
    envelope) and ``r_frac``; the thresholds are the grid ``r_max * pattern`` (default
    ``pattern = k/(K-1)``, K = 10 plays) scaled to the data: ``r_max = r_frac * (gamma_r(x_max)
    - gamma_l(x_min)) / 2``, so that with r_frac < 1 every play moves over a full input cycle
    (a play that only moves in the initial transient would get an unidentifiable weight).
    Weights >= 0, with ``weights[0] > 0`` (invertible operator), solved by Lawson-Hanson
    inside the C++ batch.
    """

    model_class = GeneralizedPrandtlIshlinskii
    kind = "GeneralizedPrandtlIshlinskii"
    separable = True
    search_names: tuple[str, ...] = (
        "rising_b",
        "rising_c",
        "falling_a",
        "falling_b",
        "falling_c",
        "falling_d",
    )
    log_names = frozenset({"rising_b", "falling_b", "falling_a", "r_frac"})

    def __init__(self, pattern: np.ndarray):
        self.pattern = np.asarray(pattern, dtype=float)
        self.search_names = (*type(self).search_names, "r_frac")
        self.x_lims = (-1.0, 1.0)

    def r_max(self, values) -> np.ndarray:
        lo, hi = self.x_lims
        up = np.tanh(values["rising_b"] * (hi - values["rising_c"]))
        down = values["falling_a"] * np.tanh(values["falling_b"] * (lo - values["falling_c"]))
        down = down + values["falling_d"]
        return values["r_frac"] * np.maximum(0.5 * (up - down), 1e-9)

    def bounds(self, s, fixed):
        mid = getattr(s, "x_mid", 0.0)
        half = 0.5 * s.x_range
        self.x_lims = (mid - half, mid + half)
        return {
            "rising_b": (0.1 / half, 5.0 / half),
            "rising_c": (mid - half, mid + half),
            "falling_a": (0.33, 3.0),
            "falling_b": (0.1 / half, 5.0 / half),
            "falling_c": (mid - half, mid + half),
            "falling_d": (-1.0, 1.0),
            "r_frac": (0.02, 0.95),
        }

    def search_bounds(self, s, fixed):
        return self.bounds(s, fixed)

    def nonlinear(self, values):
        n = np.size(values["rising_b"])
        one = np.ones(n)
        cols = [
            one,
            values["rising_b"],
            values["rising_c"],
            0.0 * one,
            values["falling_a"],
            values["falling_b"],
            values["falling_c"],
            values["falling_d"],
        ]
        return np.column_stack([*cols, np.outer(self.r_max(values), self.pattern)])

    def linear_bounds(self, s):
        k = self.pattern.size
        lo = np.r_[1e-9 * s.slope, np.zeros(k - 1), -np.inf]
        return lo, np.full(k + 1, np.inf)

    def public(self, values, theta):
        theta = np.asarray(theta, dtype=float)
        weights = np.maximum(theta[:-1], 0.0)
        weights[0] = max(weights[0], 1e-300)
        shift = float(theta[-1]) / float(weights.sum())
        v = {k: float(values[k]) for k in values}
        return {
            "rising": (1.0, v["rising_b"], v["rising_c"], shift),
            "falling": (v["falling_a"], v["falling_b"], v["falling_c"], v["falling_d"] + shift),
            "thresholds": (float(self.r_max(v)) * self.pattern).tolist(),
            "weights": weights.tolist(),
        }


class TableSpec(ModelSpec):
    """The bounds of a model with no spec of its own, from its C++ parameter table: each
    identifiable parameter's unit scales its range to the data and its valid range clips it.

    By unit: ``output/input`` a slope of 0.2-5 times the data's (of either sign when the table
    allows it), ``input`` and ``output`` up to half the data's span, ``1/input`` 0.5-500 over the
    input's span (searched on a log scale), any other a decade either side of the table's
    default (log-scaled when positive). A model whose parameters are not scalars, or whose
    batched C++ kernels are missing, needs a spec of its own.
    """

    def __init__(self, model_class: Any) -> None:
        self.model_class = model_class
        self.kind = model_class.__name__
        rows = {f["name"]: f for f in model_class._core_params.fields()}
        self.rows = [rows[n] for n in model_class.param_names]
        self.log_names = frozenset(
            f["name"]
            for f in self.rows
            if f["unit"] == "1/input" or (f["unit"] not in _DATA_UNITS and _decade(f)[2])
        )
        for f in self.rows:
            if not isinstance(f["default"], int | float) or isinstance(f["default"], bool):
                raise ValueError(
                    f"cannot identify {self.kind}: its parameter {f['name']!r} is not a "
                    "number, so its bounds cannot follow from the parameter table; give it a "
                    "spec of its own in tendonsheath/identify/specs.py"
                )

    def bounds(self, s, fixed):
        return {f["name"]: _clip(f, _scaled(f, s)) for f in self.rows}


_DATA_UNITS = ("output/input", "input", "output", "1/input")


def _scaled(row: dict, s: Scale) -> tuple[float, float]:
    unit, lo = row["unit"], row["lo"]
    if unit == "output/input":
        return (0.2 * s.slope, 5.0 * s.slope) if lo >= 0 else (-5.0 * s.slope, 5.0 * s.slope)
    if unit in ("input", "output"):
        half = 0.5 * (s.x_range if unit == "input" else s.y_range)
        return (0.0, half) if lo >= 0 else (-half, half)
    if unit == "1/input":
        return 0.5 / s.x_range, 500.0 / s.x_range
    a, b, _ = _decade(row)
    return a, b


def _decade(row: dict) -> tuple[float, float, bool]:
    """A decade either side of the default (log-scaled when the range is positive), else the
    default +- 10 times its size (at least 1)."""
    d = float(row["default"]) if isinstance(row["default"], int | float) else 0.0
    if d > 0 and row["lo"] >= 0:
        return d / 10.0, d * 10.0, True
    w = 10.0 * max(abs(d), 1.0)
    return d - w, d + w, False


def _clip(row: dict, b: tuple[float, float]) -> tuple[float, float]:
    return max(b[0], row["lo"]), min(b[1], row["hi"])


def spec_for(model_class: type) -> ModelSpec:
    """The identification spec of a model class: its own where it has one, else the
    :class:`TableSpec` read from its parameter table.

    Parameters
    ----------
    model_class : type
        A :class:`~tendonsheath.models.HysteresisModel` subclass with a C++ core.

    Returns
    -------
    ModelSpec
        Its bounds, log-scaled names and batched kernel kind.

    Raises
    ------
    ValueError
        A model with neither a spec nor a parameter table of numbers.
    """
    own = SPECS.get(model_class)
    if own is not None:
        return own()
    if getattr(model_class, "_core_params", None) is None:
        raise ValueError(f"cannot identify {model_class.__name__}: it has no C++ parameter table")
    return TableSpec(model_class)


SPECS: dict[type, type[ModelSpec]] = {
    Backlash: BacklashSpec,
    BoucWenBacklash: BoucWenBacklashSpec,
    BoucWen: BoucWenSpec,
    HystereticOscillator: HystereticOscillatorSpec,
    CurveAngleModel: CurveAngleModelSpec,
    PrandtlIshlinskii: PrandtlIshlinskiiSpec,
    GeneralizedPrandtlIshlinskii: GeneralizedPrandtlIshlinskiiSpec,
}


__all__ = [
    "BacklashSpec",
    "BoucWenBacklashSpec",
    "BoucWenSpec",
    "CurveAngleModelSpec",
    "GeneralizedPrandtlIshlinskiiSpec",
    "HystereticOscillatorSpec",
    "ModelSpec",
    "PrandtlIshlinskiiSpec",
    "SPECS",
    "Scale",
    "TableSpec",
    "spec_for",
]
