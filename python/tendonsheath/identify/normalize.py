"""Any sign, any offset, any units: identification on centred, scaled data.

The hysteresis models' own parameters have a positive gain and (Backlash, PrandtlIshlinskii)
no output offset, and their default bounds assume an input centred near zero. ``identify``
therefore fits them on normalised data

    x_n = (x - x_c) / x_s,    y_n = (y - y_c) / g

with x_c, x_s the input's mid-range and half-range, g = +-(half the output's range) with the
sign of the affine least-squares slope of y on x, and y_c the affine map at x_c (the loop's
centre line). The model identified on (x_n, y_n) is mapped back to raw units:

- into the model class's own parameters where that is exact (Backlash and BoucWenBacklash:
  slopes, dead-band offsets and rho; GeneralizedPrandtlIshlinskii: envelopes and weights;
  a Chain's polynomial takes the output map), which needs a positive gain and, for the
  dead bands, offsets that stay >= 0;
- otherwise into :class:`~tendonsheath.models.Scaled`, the normalised model inside an affine
  input and output map (a negative gain, or a PrandtlIshlinskii with offsets).

Either way ``fit.model.simulate(t, x_raw)`` predicts the raw output and saves to JSON, and
the standard errors are those of the returned model's parameters (:func:`map_uncertainty`:
the delta method through the map back, or each bootstrap re-fit mapped). The
mapped model is kept when it fits the training data as well as the Scaled one (rmse within
``PLAIN_TOLERANCE``), so a compensator gets the plain class whenever one serves. BoucWen is
not normalised (its output has no offset and its state no input scale to map exactly).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ..models import (
    Backlash,
    BoucWenBacklash,
    Chain,
    GeneralizedPrandtlIshlinskii,
    HysteresisModel,
    LinearBlock,
    PlantModel,
    Polynomial,
    PrandtlIshlinskii,
    Scaled,
)
from . import gauge
from .data import Recording
from .diagnostics import entries_from_labels, se_dict, vector_of, with_vector
from .dynamic import is_dynamic_chain
from .fit import Fit, metrics, simulate_model

#: model classes identified on normalised data by default
NORMALIZED = (
    Backlash,
    BoucWenBacklash,
    PrandtlIshlinskii,
    GeneralizedPrandtlIshlinskii,
    PlantModel,
)
_CHAIN_FIRST = (Backlash, BoucWenBacklash)
#: the model in its own class is preferred to Scaled when its training rmse is at most this
#: much (relative) worse: a PrandtlIshlinskii's plays start from x = 0, so the input offset
#: moves its initial state and the mapping is exact only up to the first reversal
PLAIN_TOLERANCE = 0.01


@dataclasses.dataclass(frozen=True)
class IOMap:
    x_c: float
    x_s: float
    y_c: float
    g: float  # signed output scale

    @classmethod
    def of(cls, recs: list[Recording]) -> IOMap:
        x_all = np.concatenate([r.x for r in recs])
        x = np.concatenate([r.x[r.skip :] for r in recs])  # the samples counted
        y = np.concatenate([r.y[r.skip :] for r in recs])
        lo, hi = float(x_all.min()), float(x_all.max())
        x_c, x_s = 0.5 * (lo + hi), 0.5 * (hi - lo)
        if not x_s > 0:
            x_s = max(abs(x_c), 1.0)
        xc = x - x.mean()
        slope = float(np.dot(xc, y - y.mean()) / max(float(np.dot(xc, xc)), 1e-300))
        y_c = float(y.mean() + slope * (x_c - x.mean()))
        y_s = 0.5 * float(np.ptp(y))
        if not y_s > 0:
            y_s = max(abs(y_c), 1.0)
        return cls(x_c, x_s, y_c, y_s if slope >= 0 else -y_s)

    def recordings(self, recs: list[Recording]) -> list[Recording]:
        return [
            Recording(
                r.t,
                (r.x - self.x_c) / self.x_s,
                (r.y - self.y_c) / self.g,
                r.curve_angle,
                r.skip,
                r.route,
            )
            for r in recs
        ]

    def scaled(self, model: HysteresisModel) -> Scaled:
        return Scaled(model, self.x_c, self.x_s, self.y_c, self.g)


def applies(model_class, *, depends, bounds, fixed, initial) -> bool:
    """Whether identify normalises this problem (user bounds and values are in raw units)."""
    if depends or bounds or fixed:
        return False
    if isinstance(model_class, Chain):
        return is_dynamic_chain(model_class) or (
            type(model_class.first) in _CHAIN_FIRST and isinstance(model_class.second, Polynomial)
        )
    if model_class in (PrandtlIshlinskii, GeneralizedPrandtlIshlinskii):
        return True  # ``initial`` gives the threshold pattern only (scale-free)
    return model_class in NORMALIZED and initial is None


def _first_to_raw(first: HysteresisModel, m: IOMap, gain: float, offset: float):
    """Backlash / BoucWenBacklash fitted on x_n, its output times ``gain`` plus ``offset``,
    in raw units: slopes c g / x_s, dead bands x_c + x_s B -+ offset / c', rho / x_s."""
    p = first.params
    c_r = p["c_r"] * gain / m.x_s
    c_l = p["c_l"] * gain / m.x_s
    new = {
        "c_r": c_r,
        "c_l": c_l,
        "B_r": m.x_c + m.x_s * p["B_r"] - offset / c_r,
        "B_l": m.x_s * p["B_l"] - m.x_c + offset / c_l,
    }
    if "rho" in p:
        new["rho"] = p["rho"] / m.x_s
    return first.with_params(**new)


def to_raw(model: HysteresisModel, m: IOMap) -> HysteresisModel | None:
    """The normalised model in raw units within its own class, or None if not possible."""
    try:
        if isinstance(model, Chain) and isinstance(model.first, LinearBlock):  # Wiener
            static = to_raw(model.second, m)  # L[x_n] = (L[x] - x_c) / x_s (unit gain)
            return None if static is None else Chain(model.first, static)
        if isinstance(model, Chain) and isinstance(model.second, LinearBlock):  # Hammerstein
            static = to_raw(model.first, m)  # L commutes with the affine output map
            return None if static is None else Chain(static, model.second)
        if isinstance(model, Chain):
            # the first model keeps its held slope (c_r = 1): its raw output is x_s times the
            # normalised one, so the polynomial's a_k become g a_k / x_s^k (+ y_c on a_0)
            first = _first_to_raw(model.first, m, m.x_s, 0.0)
            poly = model.second
            assert isinstance(poly, Polynomial)  # a normalised chain: a play model + polynomial
            odd = bool(poly.options["odd"])
            powers = np.arange(1, poly.degree + 1, 2) if odd else np.arange(poly.degree + 1)
            a = m.g * np.asarray(poly.params["coefficients"], dtype=float) / m.x_s**powers
            if odd and m.y_c != 0.0:
                return None
            if not odd:
                a[0] += m.y_c
            return Chain(first, Polynomial(coefficients=a, odd=odd))
        if m.g <= 0:
            return None
        if isinstance(model, Backlash | BoucWenBacklash):
            return _first_to_raw(model, m, m.g, m.y_c)
        if isinstance(model, PrandtlIshlinskii):
            p = model.params
            return PrandtlIshlinskii(
                m.x_s * np.asarray(p["thresholds"]), m.g / m.x_s * np.asarray(p["weights"])
            )
        if isinstance(model, GeneralizedPrandtlIshlinskii):
            p = model.params
            w = m.g * np.asarray(p["weights"], dtype=float)
            shift = m.y_c / float(w.sum())

            new = {"weights": w.tolist()}
            for side in ("rising", "falling"):
                new[f"{side}_b"] = p[f"{side}_b"] / m.x_s
                new[f"{side}_c"] = m.x_c + m.x_s * p[f"{side}_c"]
                new[f"{side}_d"] = p[f"{side}_d"] + shift
            span = model.options.get("envelope_range")
            if span is not None:  # the tanh's input range, in raw input units
                new["envelope_range"] = [m.x_c + m.x_s * v for v in span]
            return model.with_params(**new)
    except ValueError:  # e.g. a dead band that would be < 0 in raw units
        return None
    return None


def _raw_vector(model_n, m: IOMap, entries_n, entries_raw):
    """vec -> the raw model's identified quantities, for the normalised ones ``vec``."""

    def fn(vec):
        raw = to_raw(with_vector(model_n, entries_n, vec), m)
        if raw is None:
            raise ValueError("outside the mappable range")
        if gauge.applies(raw) and any(e.also for e in entries_raw):
            raw = gauge.canonical(raw)  # the raw offset moves the dead bands apart again
        return vector_of(raw, entries_raw)

    return fn


def _map_jacobian(fn, v0: np.ndarray) -> np.ndarray:
    """Central differences of the map ``fn`` at ``v0`` (one-sided where it is not defined)."""
    f0 = fn(v0)
    typ = float(np.max(np.abs(v0))) if v0.size else 1.0
    D = np.zeros((f0.size, v0.size))
    for i in range(v0.size):
        h = 1e-6 * max(abs(v0[i]), 1e-3 * typ, 1e-12)
        cols = []
        for sign in (1.0, -1.0):
            v = v0.copy()
            v[i] += sign * h
            try:
                cols.append((sign, fn(v)))
            except ValueError:
                pass
        if len(cols) == 2:
            D[:, i] = (cols[0][1] - cols[1][1]) / (2 * h)
        elif cols:
            D[:, i] = cols[0][0] * (cols[0][1] - f0) / h
    return D


def map_uncertainty(fit_n: Fit, raw, m: IOMap) -> tuple[dict, dict]:
    """Standard errors (and the uncertainty record) of the mapped-back model ``raw``.

    Scaled: the normalised model is inside it, its errors are the inner ones. Otherwise the
    map from the normalised estimates to the raw parameters (nonlinear: e.g. the GPI's
    output offset spread over its d's by the weights' sum) carries them: the linearised
    covariance by the delta method (D C D' with D the map's Jacobian), bootstrap re-fits
    one by one through the map itself. The map's own constants (centres, scales and, when
    re-solved, the output offset and gain) are taken as exact."""
    u = dict(fit_n.uncertainty)
    if isinstance(raw, Scaled):
        inner_se = {f"inner.{k}": v for k, v in fit_n.standard_errors.items()}
        if "names" in u:
            u["names"] = [f"inner.{k}" for k in u["names"]]
        u["estimate_names"] = [f"inner.{k}" for k in u.get("estimate_names", [])]
        return inner_se, u
    labels = u.get("estimate_names", [])
    entries = entries_from_labels(labels)
    fn = _raw_vector(fit_n.model, m, entries, entries)
    v0 = vector_of(fit_n.model, entries)
    se_n = vector_of(_NanParams(fit_n.standard_errors), entries)
    if u.get("method") == "linearised" and "covariance" in u:
        cov_n = np.where(np.isfinite(u["covariance"]), u["covariance"], 0.0)
        D = _map_jacobian(fn, v0)
        cov = D @ cov_n @ D.T
        se = np.sqrt(np.clip(np.diag(cov), 0.0, None))
        u["covariance"] = cov
    elif str(u.get("method", "")).startswith("bootstrap"):
        rows = []
        for row in u["samples"][:, : len(labels)]:
            try:
                rows.append(fn(row))
            except ValueError:
                u["failed"] = u.get("failed", 0) + 1
        if len(rows) >= 2:
            S = np.vstack(rows)
            se = S.std(axis=0, ddof=1)
            u["samples"] = S
        else:
            se = np.full(len(labels), np.nan)
    else:
        se = np.full(len(labels), np.nan)
    se[~np.isfinite(se_n)] = np.nan  # at an active constraint (or not computed) there too
    return se_dict(raw, entries, se), u


class _NanParams:
    """Standard errors read like a model's params (for :func:`vector_of`); NaN where absent."""

    def __init__(self, se: dict):
        self.params = {k: (v if v is not None else np.nan) for k, v in se.items()}


def identify_normalized(fit_normalised, model_class, recs: list[Recording]) -> Fit:
    """``fit_normalised(model_class, recordings)`` (identify with ``normalize=False``) on
    normalised recordings, the model mapped back (see the module)."""
    m = IOMap.of(recs)
    odd_chain = isinstance(model_class, Chain) and isinstance(model_class.second, Polynomial)
    odd_chain = odd_chain and bool(model_class.second.options["odd"])
    if odd_chain:  # an odd polynomial holds no offset: scale and sign only
        m = dataclasses.replace(m, x_c=0.0, y_c=0.0)
    fit_n = fit_normalised(model_class, m.recordings(recs))
    scaled = m.scaled(fit_n.model)
    y = np.concatenate([r.y for r in recs])
    warm = fit_n.warmup
    y_fit = np.concatenate([r.y[warm + r.skip :] for r in recs])  # the samples counted

    def score(model):
        preds = [simulate_model(model, r.t, r.x, r.angle_input) for r in recs]
        yh = np.concatenate([p[warm + r.skip :] for r, p in zip(recs, preds, strict=True)])
        return float(np.sqrt(np.mean((y_fit - yh) ** 2))), (preds)

    model: HysteresisModel = scaled
    rmse, preds = score(scaled)
    # The inner model may lack an output offset (PrandtlIshlinskii, Backlash): re-solve the
    # output map's offset and gain by least squares on its prediction; kept if it helps.
    u = np.concatenate([p[warm + r.skip :] for r, p in zip(recs, fit_n.predictions, strict=True)])
    A = np.column_stack([np.ones_like(u), u])
    b0, b1 = np.linalg.lstsq(A, y_fit, rcond=None)[0]
    if not odd_chain and np.isfinite(b0) and np.isfinite(b1) and b1 != 0:
        alt = Scaled(fit_n.model, m.x_c, m.x_s, float(b0), float(b1))
        a_rmse, a_preds = score(alt)
        if a_rmse < rmse * (1 - 1e-9):
            scaled, model, rmse, preds = alt, alt, a_rmse, a_preds
            m = dataclasses.replace(m, y_c=float(b0), g=float(b1))
    raw = to_raw(fit_n.model, m)
    gauged = any(" = " in n for n in fit_n.uncertainty.get("estimate_names", []))
    if isinstance(raw, Chain) and gauged:  # gauged: a chain's play-model parameters
        raw = gauge.canonical(raw)
    if raw is not None:
        r_rmse, r_preds = score(raw)
        if np.isfinite(r_rmse) and r_rmse <= rmse * (1 + PLAIN_TOLERANCE) + 1e-12 * np.ptp(y):
            model, rmse, preds = raw, r_rmse, r_preds
    overall = metrics(
        y_fit, np.concatenate([p[warm + r.skip :] for r, p in zip(recs, preds, strict=True)])
    )
    how = (
        f"normalised: x -> (x - {m.x_c:.6g}) / {m.x_s:.6g}, y -> (y - {m.y_c:.6g}) / {m.g:.6g}; "
        + ("mapped back into the model's parameters" if model is not scaled else "as Scaled")
    )
    prefix = (lambda k: f"inner.{k}") if model is scaled else (lambda k: k)
    errors, uncertainty = map_uncertainty(fit_n, model, m)
    groups = fit_n.groups
    if gauged:  # in raw units (a Scaled model keeps them inside, in its own units)
        groups = gauge.groups(model, errors) if isinstance(model, Chain) else {}
    return dataclasses.replace(
        fit_n,
        model=model,
        rmse=overall["rmse"],
        nrmse=overall["nrmse"],
        fit_percent=overall["fit_percent"],
        standard_errors=errors,
        uncertainty=uncertainty,
        groups=groups,
        identified=[prefix(k) for k in fit_n.identified],
        fixed={prefix(k): v for k, v in fit_n.fixed.items()},
        per_recording=[
            metrics(r.y[warm + r.skip :], p[warm + r.skip :])
            for r, p in zip(recs, preds, strict=True)
        ],
        method=f"{fit_n.method}; {how}",
        bounds={prefix(k): v for k, v in fit_n.bounds.items()},
        recordings=recs,
        predictions=preds,
    )


__all__ = [
    "IOMap",
    "NORMALIZED",
    "PLAIN_TOLERANCE",
    "applies",
    "identify_normalized",
    "map_uncertainty",
    "to_raw",
]
