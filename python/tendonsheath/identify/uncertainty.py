"""Standard errors (linearised or bootstrap), identifiability diagnostics and identified groups
of a fit, for every model class; and the CurveAngleModel's single-angle reparameterisation.

Called by :func:`~tendonsheath.identify.identify` and the Chain path once the estimate is
known; see :mod:`tendonsheath.identify.diagnostics` for the figures and their limits.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..models import CurveAngleModel, GeneralizedPrandtlIshlinskii, PrandtlIshlinskii
from ..plant.route import Route
from .diagnostics import (
    Diagnostics,
    Entry,
    block_length,
    bootstrap,
    bound_side,
    covariance,
    entries_of,
    fd_jacobian,
    linearised_se,
    moving_block_resample,
    se_dict,
    undetermined_notes,
    vector_of,
    with_vector,
)
from .fit import simulate_model
from .problem import DirectProblem, over_recordings, with_fitted_output
from .settings import BOOTSTRAP_DEFAULT, SE_METHODS, check_method

# names of the linear (solved) coefficients of the separable specs, for the bound check
_LINEAR_NAMES = {
    "BoucWenBacklash": ["c_r", "B_r (c_r B_r)", "c_l", "B_l (c_l B_l)"],
    "BoucWen": ["alpha", "(1 - alpha) k"],
}


# -- the CurveAngleModel at a single curve angle ---------------------------------------------


@dataclass
class SingleAngle:
    """The recordings cover one curve angle (or one sensed route): friction is held, the groups
    are reported."""

    angle: float
    friction_held: bool
    friction: float
    route: Route | None = None

    @property
    def shape(self) -> float | Route:
        """What the groups are evaluated at: the route, else the curve angle."""
        return self.angle if self.route is None else self.route


def single_angle(cls, recs) -> float | Route | None:
    """The common curve angle of all recordings if they cover only one (their common route
    when they all have the same sensed route), else None."""
    if cls is not CurveAngleModel or any(r.curve_angle is None for r in recs):
        return None
    routes = [r.route for r in recs]
    if any(route is not None for route in routes):
        first = routes[0]
        return first if all(route == first for route in routes) else None
    theta = np.concatenate([r.curve_angle for r in recs])
    if np.ptp(theta) > 1e-12 * max(1.0, float(np.max(np.abs(theta)))):
        return None
    return float(theta[0])


def setup_single_angle(cls, recs, held, values, user_fixed, user_bounds, all_bounds, free_names):
    """Hold the friction (at the initial model's value) when the recordings cover a single
    curve angle, and widen the load's bounds so that the groups cover what the default
    friction range would reach (e_L/e_b = F_L/(T0 mu Theta)). Edits ``held``, ``values``,
    ``all_bounds`` and ``free_names`` in place; returns a :class:`SingleAngle` or None."""
    shape = single_angle(cls, recs)
    if shape is None:
        return None
    route = shape if isinstance(shape, Route) else None
    theta = float(shape.curve_angle) if isinstance(shape, Route) else float(shape)
    user_fixed = set(user_fixed or {})
    if "friction" in user_fixed:
        return SingleAngle(theta, False, float(held["friction"]), route)
    mu0 = float(values["friction"])
    held["friction"] = mu0
    values["friction"] = mu0
    if "friction" in free_names:
        free_names.remove("friction")
    mu_lo = float(all_bounds["friction"][0])
    if "load_force" not in (user_bounds or {}) and mu_lo > 0:
        lo, hi = all_bounds["load_force"]
        f = max(1.0, mu0 / mu_lo)
        all_bounds["load_force"] = (f * lo, f * hi)
    return SingleAngle(theta, True, mu0, route)


def curve_angle_groups(model, theta: float | Route) -> dict[str, float]:
    """The identifiable groups of a CurveAngleModel at one curve angle or route (spec B): the
    dead-zone half-width e_b/r_p and the load offset e_L/r_p (rad at the motor), and the gain
    c r_p/r_d of the branches (distal rad per motor rad)."""
    p = model.params
    return {
        "backlash_half_width": float(model.backlash_half_width(theta)),
        "load_offset": float(model.load_offset(theta)),
        "gain": float(model.slope(theta) * p["proximal_radius"] / p["distal_radius"]),
    }


_GROUP_UNITS = {
    "backlash_half_width": "rad at the motor",
    "load_offset": "rad at the motor",
    "gain": "distal rad per motor rad",
}
_GAIN_NAMES = {"load_stiffness", "distal_radius", "proximal_radius", "stiffness"}


# -- everything after the estimate -------------------------------------------------------------


@dataclass
class Layout:
    """How the identified quantities are laid out: names (Jacobian columns), the estimate
    vector of a model, and the standard-error dict built from a vector of errors."""

    names: list[str]
    vector: Callable[[Any], np.ndarray]
    to_dict: Callable[[np.ndarray], dict]
    jacobian: Callable[[], np.ndarray]
    source: str


def _direct_layout(se_problem: DirectProblem, model, depends, free_names) -> Layout:
    def to_dict(se):
        if not depends:
            return {n: float(s) for n, s in zip(free_names, se, strict=True)}
        out: dict = {}
        for p, law, i in se_problem.layout:
            k = 1 if law == "constant" else 2
            out[p] = [float(s) for s in se[i : i + k]]
        if se_problem.tanh:
            out["angle_friction"] = float(se[-1])
        return out

    c = se_problem.coefficients_of(model)
    return Layout(
        list(se_problem.space.names),
        se_problem.coefficients_of,
        to_dict,
        lambda: se_problem.jacobian(c),
        "central differences of the simulation output w.r.t. the identified parameters",
    )


def _generic_layout(model, recs, warmup, names, scales=(), canon=None) -> Layout:
    """Central differences w.r.t. the model's params ``names`` / ``scales``; ``canon`` maps
    any model (e.g. a bootstrap re-fit) to the parameterisation the names refer to."""
    entries = entries_of(model, names, scales)
    canon = canon or (lambda m: m)

    def simulate(m):
        return np.concatenate([simulate_model(m, r.t, r.x, r.angle_input)[warmup:] for r in recs])

    return Layout(
        [e.label for e in entries],
        lambda m: vector_of(canon(m), entries),
        lambda se: se_dict(model, entries, se),
        lambda: fd_jacobian(simulate, model, entries),
        "central differences of the simulation output w.r.t. the model's parameters",
    )


def _entries_names(cls, model, chain_free=None):
    """(names, scales) of the generic layouts: PI, GPI and Chain."""
    if chain_free is not None:
        return [f"first.{n}" for n in chain_free] + ["second.coefficients"], []
    if cls is PrandtlIshlinskii:
        return ["weights"], ["thresholds"]
    # GPI: rising_a is held at 1 (the weights carry the scale)
    names = [
        "rising_b",
        "rising_c",
        "rising_d",
        "falling_a",
        "falling_b",
        "falling_c",
        "falling_d",
        "weights",
    ]
    return names, ["thresholds"]


def assess(
    *,
    cls,
    model,
    problem,
    recs,
    warmup: int,
    values: dict,
    free_names: list[str],
    all_bounds: dict,
    spec,
    options: dict,
    depends: dict,
    workers: int,
    sse: float,
    n_fit: int,
    u_best: np.ndarray,
    use_separable: bool,
    method: str = "linearised",
    count: int = BOOTSTRAP_DEFAULT,
    block: int | None = None,
    seed: int | None = 0,
    angle: SingleAngle | None = None,
    chain_free: list[str] | None = None,
    generic: tuple[list[str], list[str]] | None = None,
    label_of: Callable[[str], str] | None = None,
    canon: Callable[[Any], Any] | None = None,
) -> dict[str, Any]:
    """Standard errors, diagnostics, groups and the bootstrap record of a fitted model.

    ``generic`` ((names, scales) of the model's params) takes the Jacobian with respect to
    those params (e.g. a Hammerstein chain's "first.rho", "second.time_constant");
    ``label_of`` names the search and linear coordinates like them for the bound checks."""
    notes: list[str] = []
    direct = (values, free_names, all_bounds, spec, options, depends, workers)
    layout = _layout_for(cls, model, problem, recs, warmup, direct, chain_free, generic, canon)
    try:
        J = layout.jacobian()
    except ValueError as exc:  # pragma: no cover - defensive
        J = None
        notes.append(f"no Jacobian ({exc})")
    bvalues, bbounds, brefs = _enforced_bounds(
        cls, problem, u_best, use_separable and chain_free is None, label_of
    )
    keep = _free_at_optimum(layout, bvalues, bbounds, brefs, notes)
    group_fn = _single_angle_groups(angle, free_names, notes)
    fitted = _Fitted(layout, model, problem, recs, warmup, u_best, use_separable, sse, n_fit)
    if method == "bootstrap" or method == "bootstrap-recordings":
        se, g_hat, g_se, extra = _bootstrapped(fitted, group_fn, method, count, block, seed)
    else:
        se, g_hat, g_se, extra = _linearised(fitted, group_fn, J, keep, method, free_names)
    notes += undetermined_notes(dict(zip(layout.names, se, strict=True)))
    diag = _diagnostics(J, keep, layout, (bvalues, bbounds, brefs), notes)
    extra["estimate_names"] = list(layout.names)
    return {
        "standard_errors": layout.to_dict(se),
        "diagnostics": diag,
        "groups": _groups(g_hat, g_se, free_names, angle),
        "se_method": extra,
        "estimate": layout.vector(model),
    }


def _layout_for(cls, model, problem, recs, warmup, direct, chain_free, generic, canon) -> Layout:
    """The identified quantities: the model's params (``generic``, chains and the play
    operators) or the search problem's coordinates (a DirectProblem, built if needed from
    ``direct``: values, free names, bounds, spec, options, angle laws, workers)."""
    values, free_names, all_bounds, spec, options, depends, workers = direct
    if generic is not None:
        names, scales = generic
        return _generic_layout(model, recs, warmup, names, scales, canon=canon)
    if chain_free is not None or cls in (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii):
        names, scales = _entries_names(cls, model, chain_free)
        return _generic_layout(model, recs, warmup, names, scales)
    se_problem = problem
    if not isinstance(problem, DirectProblem):
        se_problem = DirectProblem(
            cls,
            recs,
            warmup,
            {**values, **model.params},
            free_names,
            all_bounds,
            spec.log_names,
            options,
            None,
            workers,
        )
    return _direct_layout(se_problem, model, depends, free_names)


def _enforced_bounds(cls, problem, u_best, linear: bool, label_of):
    """The bounds actually enforced: the searched coordinates and (``linear``) the solved
    linear ones: (values, bounds, reference magnitudes), named by ``label_of``."""
    space = problem.space
    best = space.natural(u_best) if space.lower.size else np.zeros(0)
    lo_nat, hi_nat = space.natural(space.lower), space.natural(space.upper)
    bvalues = {n: float(v) for n, v in zip(space.names, best, strict=True)}
    bbounds = {n: (float(a), float(b)) for n, a, b in zip(space.names, lo_nat, hi_nat, strict=True)}
    brefs: dict[str, float] = {}
    if linear and hasattr(problem, "linear"):
        theta, _ = problem.linear(u_best if not space.lower.size else best)
        lo, hi = problem.lin_lo, problem.lin_hi
        if cls is PrandtlIshlinskii:
            lin_names = [f"sum(weights[:{j + 1}])" for j in range(theta.size)]
        elif cls is GeneralizedPrandtlIshlinskii:
            lin_names = [f"weights[{j}]" for j in range(theta.size - 1)] + ["offset"]
        else:
            lin_names = _LINEAR_NAMES.get(cls.__name__, [f"linear[{j}]" for j in range(theta.size)])
        ref = float(np.max(np.abs(theta))) if theta.size else 0.0
        for n, v, a, b in zip(lin_names, theta, lo, hi, strict=False):
            bvalues[n] = float(v)
            bbounds[n] = (float(a), float(b))
            brefs[n] = ref
    if label_of is not None:
        bvalues = {label_of(n): v for n, v in bvalues.items()}
        bbounds = {label_of(n): v for n, v in bbounds.items()}
        brefs = {label_of(n): v for n, v in brefs.items()}
    return bvalues, bbounds, brefs


def _free_at_optimum(layout, bvalues, bbounds, brefs, notes: list[str]) -> list[int]:
    """Indices of the estimates not held at an active one-sided constraint (e.g. a weight at
    0): those are not free at the optimum and are left out of the linearised covariance and
    the conditioning."""
    active = set()
    for n, (a, b) in bbounds.items():
        if np.isfinite(a) == np.isfinite(b):
            continue
        if bound_side(bvalues[n], a, b, ref=brefs.get(n, 0.0)) is not None:
            label = n.split(" ")[0]
            if label in layout.names:
                active.add(label)
    if active:
        notes.append(
            f"{', '.join(sorted(active))} at an active constraint: left out of the linearised "
            "covariance and the conditioning (standard error NaN there; "
            'standard_errors="bootstrap" gives one)'
        )
    return [i for i, n in enumerate(layout.names) if n not in active]


def _single_angle_groups(angle: SingleAngle | None, free_names, notes: list[str]):
    """The groups' function of a CurveAngleModel at one angle (None otherwise), with the
    note on held friction."""
    if angle is None:
        return None
    if angle.friction_held:
        notes.append(
            f"!single curve angle ({angle.angle:.4g} rad): friction cannot be separated "
            f"from the stiffness (EA) there; friction held at {angle.friction:g} and the "
            "identifiable groups reported in fit.groups (backlash_half_width, load_offset"
            + (", gain" if _gain_free(free_names) else "")
            + "); the stiffness and load values are only meaningful with that friction"
        )
    return lambda m: curve_angle_groups(m, angle.shape)


@dataclass
class _Fitted:
    """What the standard errors are computed from: the estimate and its problem."""

    layout: Layout
    model: Any
    problem: Any
    recs: list
    warmup: int
    u_best: np.ndarray
    use_separable: bool
    sse: float
    n_fit: int


def _linearised(f: _Fitted, group_fn, J, keep, method: str, free_names):
    """Standard errors from the Jacobian (``method`` "linearised"), or NaN ("none")."""
    extra: dict[str, Any] = {"method": method}
    g_hat = group_fn(f.model) if group_fn else {}
    se = np.full(len(f.layout.names), np.nan)
    if method == "none":
        return se, g_hat, {k: float("nan") for k in g_hat}, extra
    g_se: dict[str, float] = {}
    if J is not None:
        J_keep = J[:, keep]
        se[keep] = linearised_se(J_keep, f.sse, f.n_fit)
        if np.all(np.isfinite(J_keep)):
            cov = np.full((se.size, se.size), np.nan)
            cov[np.ix_(keep, keep)] = covariance(J_keep, f.sse, f.n_fit)
            extra["covariance"] = cov  # for mapping the errors to other parameters
        if group_fn:
            g_se = _delta_group_se(f.layout, f.model, group_fn, J, f.sse, f.n_fit, free_names)
    return se, g_hat, g_se, extra


def _bootstrapped(f: _Fitted, group_fn, method: str, count: int, block, seed):
    """Standard errors as the spread of re-fits on resampled residual blocks ("bootstrap")
    or resampled recordings ("bootstrap-recordings")."""
    extra: dict[str, Any] = {"method": method}
    g_hat = group_fn(f.model) if group_fn else {}
    space, problem, recs = f.problem.space, f.problem, f.recs

    def refit(p2):
        try:
            u = _local_refit(p2, space, f.u_best, f.use_separable)
            m = p2.model(space.natural(u))
        except (ValueError, np.linalg.LinAlgError):
            return None
        vec = f.layout.vector(m)
        if group_fn:
            vec = np.r_[vec, list(group_fn(m).values())]
        return vec

    if method == "bootstrap":
        y_hat, resid, segments = _residuals(f.model, recs, f.warmup)
        b = int(block) if block else block_length(resid)
        extra["block"] = b

        def draw(rng):
            y_star = y_hat + moving_block_resample(resid, segments, b, rng)
            return refit(with_fitted_output(problem, y_star))
    else:
        if len(recs) < 2:
            raise ValueError(
                'standard_errors="bootstrap-recordings" needs several recordings '
                f'(got {len(recs)}); use "bootstrap" (residual blocks)'
            )

        def draw(rng):
            idx = rng.integers(0, len(recs), size=len(recs))
            return refit(over_recordings(problem, [recs[i] for i in idx], f.warmup))

    boot = bootstrap(draw, count, seed)
    k = len(f.layout.names)
    g_se = {n: float(s) for n, s in zip(g_hat, boot["se"][k:], strict=True)}
    extra.update(
        resamples=int(count),
        failed=int(boot["failed"]),
        seed=seed,
        names=[*f.layout.names, *g_hat],
        samples=boot["samples"],
    )
    return boot["se"][:k], g_hat, g_se, extra


def _diagnostics(J, keep, layout, bound_check, notes) -> Diagnostics:
    """Identifiability diagnostics from the Jacobian's free columns and the bound check
    ((values, bounds, reference magnitudes) of the enforced coordinates)."""
    values, bounds, refs = bound_check
    return Diagnostics.from_jacobian(
        J[:, keep] if J is not None else None,
        [layout.names[i] for i in keep],
        values=values,
        bounds=bounds,
        refs=refs,
        source=layout.source,
        notes=notes,
    )


def _groups(g_hat: dict, g_se: dict, free_names, angle) -> dict:
    groups = {}
    for name, v in g_hat.items():
        identified = name != "gain" or _gain_free(free_names)
        groups[name] = {
            "value": v,
            "se": g_se.get(name) if identified else None,
            "unit": _GROUP_UNITS[name],
            "curve_angle": angle.angle,
            "identified": identified,
        }
    return groups


REFIT_NFEV = 30  # least-squares iterations of a bootstrap re-fit (it starts at the estimate)


def _local_refit(problem, space, u0, use_separable) -> np.ndarray:
    """Least squares on a resample's simulation error from the estimate ``u0`` (a bounded
    trust-region run like the fit's own refinement, with a smaller budget: it starts at the
    optimum of the original data, a few iterations away from the resample's)."""
    from scipy.optimize import least_squares

    span = space.upper - space.lower
    u0 = np.clip(u0, space.lower + 1e-9 * span, space.upper - 1e-9 * span)
    if use_separable:

        def fun(u):
            return problem.residual(space.natural(u))
    else:

        def fun(u):
            return problem.residuals(space.natural(u)[None, :])[0]

    res = least_squares(
        fun,
        u0,
        jac="2-point",
        bounds=(space.lower, space.upper),
        method="trf",
        x_scale="jac",
        max_nfev=REFIT_NFEV,
        ftol=1e-10,
        xtol=1e-10,
    )
    return res.x


def _gain_free(free_names) -> bool:
    return bool(set(free_names) & (_GAIN_NAMES - {"stiffness"}))


def _delta_group_se(layout, model, group_fn, J, sse, n_fit, free_names) -> dict[str, float]:
    """Linearised standard errors of the groups: G cov G' with G = d group / d estimate."""
    k = J.shape[1]
    cov = covariance(J, sse, n_fit)
    g0 = group_fn(model)
    entries = [Entry(n, n) for n in free_names]
    v0 = vector_of(model, entries)
    G = np.zeros((len(g0), k))
    for i in range(k):
        h = 1e-6 * max(abs(v0[i]), 1e-9)
        up = v0.copy()
        up[i] += h
        down = v0.copy()
        down[i] -= h
        try:
            gu = group_fn(with_vector(model, entries, up))
            gd = group_fn(with_vector(model, entries, down))
        except ValueError:
            continue
        G[:, i] = [(gu[n] - gd[n]) / (2 * h) for n in g0]
    var = np.einsum("ik,kl,il->i", G, cov, G)
    return {n: float(np.sqrt(max(v, 0.0))) for n, v in zip(g0, var, strict=True)}


def _residuals(model, recs, warmup):
    """Fitted predictions, residuals and per-recording fitted lengths."""
    y_hat = np.concatenate([simulate_model(model, r.t, r.x, r.angle_input)[warmup:] for r in recs])
    y = np.concatenate([r.y[warmup:] for r in recs])
    return y_hat, y - y_hat, [r.n - warmup for r in recs]


__all__ = [
    "BOOTSTRAP_DEFAULT",
    "Layout",
    "REFIT_NFEV",
    "SE_METHODS",
    "SingleAngle",
    "assess",
    "check_method",
    "curve_angle_groups",
    "setup_single_angle",
    "single_angle",
]
