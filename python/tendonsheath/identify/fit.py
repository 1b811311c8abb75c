"""The result of an identification: fitted model, errors, standard errors, the optimiser's story."""

from __future__ import annotations

from dataclasses import dataclass, field
from dataclasses import fields as dataclass_fields
from pathlib import Path
from typing import Any, cast

import numpy as np

from .._util.typing import ArrayLike
from ..models import HysteresisModel
from ..models.loaded import Loaded
from ..plant.route import Route
from .data import Recording
from .diagnostics import Diagnostics
from .report import draw_report

#: what every standard error here is: the spread of the estimates were the data made by the
#: model class, not a measure of how far a real drive lies from it
GIVEN_CLASS = "given the model class: not how far the drive lies from it"


def metrics(y: ArrayLike, y_hat: ArrayLike) -> dict[str, float]:
    """rmse; nrmse = rmse / (max(y) - min(y)); fit % = 100 (1 - ||y - y_hat|| / ||y - mean(y)||).

    Parameters
    ----------
    y : array_like of float
        Measured outputs.
    y_hat : array_like of float
        Predicted outputs, of y's length.

    Returns
    -------
    dict of str to float
        rmse, nrmse, fit_percent (NaN for a constant y) and max_abs.
    """
    y = np.asarray(y, dtype=float)
    y_hat = np.asarray(y_hat, dtype=float)
    e = y - y_hat
    rmse = float(np.sqrt(np.mean(e**2)))
    span = float(np.ptp(y))
    spread = float(np.linalg.norm(y - y.mean()))
    return {
        "rmse": rmse,
        "nrmse": rmse / span if span > 0 else float("nan"),
        "fit_percent": 100.0 * (1.0 - float(np.linalg.norm(e)) / spread)
        if spread > 0
        else float("nan"),
        "max_abs": float(np.max(np.abs(e))),
    }


@dataclass(frozen=True)
class FitQuality:
    """How predictions match the recordings after each one's warm-up."""

    overall: dict[str, float]  # metrics() over all fitted samples
    per_recording: list[dict[str, float]]
    sse: float  # sum of squared errors over all fitted samples
    n: int  # fitted samples


def fit_quality(recs, predictions, warmup: int) -> FitQuality:
    """Metrics of ``predictions`` (one per recording) against the recordings' outputs, from
    sample ``warmup`` of each on: over all of them, per recording, the SSE and the count."""
    y_fit = np.concatenate([r.y[warmup:] for r in recs])
    y_hat = np.concatenate([p[warmup:] for p in predictions])
    return FitQuality(
        overall=metrics(y_fit, y_hat),
        per_recording=[
            metrics(r.y[warmup:], p[warmup:]) for r, p in zip(recs, predictions, strict=True)
        ],
        sse=float(np.sum((y_fit - y_hat) ** 2)),
        n=int(y_fit.size),
    )


def simulate_model(model: HysteresisModel, t, x, curve_angle=None, load=None) -> np.ndarray:
    """Simulate any model; the curve angle is passed to the models that take one, the
    measured load to a Loaded model (which needs it)."""
    if isinstance(model, Loaded):
        if load is None:
            raise ValueError("a Loaded model needs the recording's measured load")
        return cast(np.ndarray, model.simulate(t, x, load=load))
    # status not asked: the outputs alone
    if getattr(model, "uses_curve_angle", False):
        # a model that uses_curve_angle takes it (its _simulate's further input)
        y = model.simulate(t, x, curve_angle=curve_angle)
        return cast(np.ndarray, y)
    return cast(np.ndarray, model.simulate(t, x))


@dataclass
class Fit:
    """An identified model and how well it fits.

    ``rmse``, ``nrmse`` (rmse over the output's range) and ``fit_percent`` are over all fitted
    samples (after warm-up) of all recordings; ``per_recording`` has the same for each.
    ``standard_errors`` has one entry per identified parameter (or angle-law coefficient),
    from the Jacobian of the simulation output at the optimum (or, with
    ``standard_errors="bootstrap"``, the spread of bootstrap re-fits: see ``uncertainty``);
    fixed parameters are absent.

    ``diagnostics`` (:class:`~tendonsheath.identify.diagnostics.Diagnostics`): parameters at
    or near their search bounds, the correlation matrix and the condition number of the
    Jacobian, and the warnings they raise (:class:`IdentifiabilityWarning`).
    ``groups``: identified groups where the parameters themselves are not identifiable
    ({name: {"value", "se", "unit", ...}}; the CurveAngleModel at a single curve angle).
    ``uncertainty``: how the standard errors were obtained ({"method": "linearised" |
    "bootstrap" | "bootstrap-recordings" | "none", and for the bootstrap "resamples",
    "block" (residual blocks only), "failed", "seed", "samples" (the re-fitted estimates,
    one row per resample, columns named by "names"), "estimate_names" (the identified
    quantities, as the Jacobian's columns) and, when linearised, "covariance" (their
    covariance matrix, NaN rows for those at an active constraint)}).
    ``stopped_on_budget``: the ``time_budget`` of identify() stopped the search or the
    refinement (the model is the best found by then).

    Parameters
    ----------
    model : HysteresisModel
        The identified model.
    rmse, nrmse, fit_percent : float
        Over all fitted samples.
    standard_errors : dict
        Identified parameter -> standard error (a list for a vector parameter).
    identified : list of str
        The identified parameters.
    fixed : dict
        The parameters held at given values.
    per_recording : list of dict
        :func:`metrics` of each recording.
    evaluations : int
        Simulations the search ran.
    seconds : float
        Wall time of the identification (s).
    generations : int
        Generations of the global search.
    method : str
        The search method.
    message : str
        The optimiser's message.
    warmup : int
        Samples at the start of each recording left out of the fit.
    n_samples : int
        Fitted samples in all.
    bounds : dict of str to (float, float), optional
        The search bounds.
    recordings : list of Recording, optional
        The data fitted.
    predictions : list of numpy.ndarray, optional
        The model's output on each recording.
    diagnostics : Diagnostics, optional
        Identifiability diagnostics.
    groups : dict, optional
        Identified groups.
    uncertainty : dict, optional
        How the standard errors were obtained.
    stopped_on_budget : bool, default False
        The time budget stopped the search.
    input_range : (float, float), optional
        The range (lo, hi) of the training inputs, all recordings, data units (also
        ``model.input_range``; an inverse keeps its commands inside it).
    """

    model: HysteresisModel
    rmse: float
    nrmse: float
    fit_percent: float
    standard_errors: dict[str, Any]
    identified: list[str]
    fixed: dict[str, Any]
    per_recording: list[dict[str, float]]
    evaluations: int
    seconds: float
    generations: int
    method: str
    message: str
    warmup: int
    n_samples: int
    bounds: dict[str, tuple[float, float]] = field(default_factory=dict)
    recordings: list[Recording] = field(default_factory=list, repr=False)
    predictions: list[np.ndarray] = field(default_factory=list, repr=False)
    diagnostics: Diagnostics = field(default_factory=Diagnostics)
    groups: dict[str, dict[str, Any]] = field(default_factory=dict)
    uncertainty: dict[str, Any] = field(
        default_factory=lambda: {"method": "linearised"}, repr=False
    )
    stopped_on_budget: bool = False
    input_range: tuple[float, float] | None = None

    @classmethod
    def from_quality(
        cls,
        model: HysteresisModel,
        quality: FitQuality,
        assessed: dict | None = None,
        **fields: Any,
    ) -> Fit:
        """The Fit of ``model`` from its :func:`fit_quality` and, where given, its
        ``uncertainty.assess()`` result (standard errors, diagnostics, groups, method);
        ``fields`` are the identification path's own (identified, fixed, bounds, counts...).

        Parameters
        ----------
        model : HysteresisModel
            The identified model.
        quality : FitQuality
            Its :func:`fit_quality` on the recordings.
        assessed : dict, optional
            ``uncertainty.assess()``'s result.
        **fields
            The other fields of :class:`Fit`.

        Returns
        -------
        Fit
            The fit.

        Raises
        ------
        TypeError
            A field that Fit does not have, or one missing.
        """
        if assessed is not None:
            fields.update(
                standard_errors=assessed["standard_errors"],
                diagnostics=assessed["diagnostics"],
                groups=assessed["groups"],
                uncertainty=assessed["se_method"],
            )
        return cls(
            model=model,
            rmse=quality.overall["rmse"],
            nrmse=quality.overall["nrmse"],
            fit_percent=quality.overall["fit_percent"],
            per_recording=quality.per_recording,
            n_samples=quality.n,
            **fields,
        )

    def __setattr__(self, name: str, value: Any) -> None:
        """Set a field; a misspelt or unknown name raises instead of adding an attribute
        nothing reads (as the models and compensators do)."""
        if not (name.startswith("_") or name in _field_names()):
            raise AttributeError(
                f"Fit has no attribute {name!r} to set; its attributes are {_field_names()}"
            )
        object.__setattr__(self, name, value)

    def warnings(self) -> list[str]:
        """The identifiability warnings of this fit (empty when there are none).

        Returns
        -------
        list of str
            The warnings' texts.
        """
        return self.diagnostics.warnings()

    def warn(self) -> None:
        """Emit the identifiability warnings (:class:`IdentifiabilityWarning`)."""
        self.diagnostics.warn(stacklevel=4)

    @property
    def params(self) -> dict[str, Any]:
        """The fitted model's parameters."""
        return self.model.params

    def predict(
        self, t: ArrayLike | None, x: ArrayLike, curve_angle: ArrayLike | Route | None = None
    ) -> np.ndarray:
        """The fitted model's output for a new input.

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None for a rate-independent model.
        x : array_like of float, shape (n,)
            Input samples.
        curve_angle : float, array_like of float, or Route, optional
            The curve angle (rad) or the route, for models that take one.

        Returns
        -------
        numpy.ndarray of float, shape (n,)
            The predicted output.
        """
        return simulate_model(self.model, t, x, curve_angle)

    def validate(
        self,
        t: ArrayLike | None,
        x: ArrayLike,
        y: ArrayLike,
        curve_angle: ArrayLike | Route | None = None,
        warmup: int | None = None,
    ) -> dict[str, float]:
        """Metrics of the fitted model on another recording (after the same warm-up).

        Parameters
        ----------
        t : array_like of float, shape (n,), or None
            Sample times (s); None for a rate-independent model.
        x : array_like of float, shape (n,)
            Input samples.
        y : array_like of float, shape (n,)
            Measured outputs.
        curve_angle : float, array_like of float, or Route, optional
            The curve angle (rad) or the route, for models that take one.
        warmup : int, optional
            Samples left out at the start (default the fit's).

        Returns
        -------
        dict of str to float
            :func:`metrics` of the prediction.
        """
        w = self.warmup if warmup is None else int(warmup)
        y_hat = self.predict(t, x, curve_angle)
        return metrics(np.asarray(y, dtype=float)[w:], y_hat[w:])

    def table(self) -> list[tuple[str, str, str]]:
        """Rows (parameter, value, standard error) with fixed parameters marked.

        Returns
        -------
        list of (str, str, str)
            Name, value and standard error ("fixed" for a fixed parameter), as text.
        """
        rows = []
        params = self.model.params
        if "coefficients" in params:  # AngleDependent
            for name, coefs in params["coefficients"].items():
                law = params["laws"][name]
                se = self.standard_errors.get(name)
                for i, c in enumerate(coefs):
                    label = name if law == "constant" else f"{name}[{i}] ({law})"
                    rows.append((label, _fmt(c), _fmt(se[i]) if se is not None else "fixed"))
            if params.get("angle_friction") is not None:
                rows.append(
                    (
                        "angle_friction",
                        _fmt(params["angle_friction"]),
                        _fmt(self.standard_errors.get("angle_friction")),
                    )
                )
            return rows
        for name, value in params.items():
            se = self.standard_errors.get(name)
            if isinstance(value, list):
                for i, v in enumerate(value):
                    rows.append(
                        (f"{name}[{i}]", _fmt(v), _fmt(se[i]) if se is not None else "fixed")
                    )
            else:
                rows.append((name, _fmt(value), _fmt(se) if se is not None else "fixed"))
        return rows

    def se_description(self) -> str:
        """How the standard errors were obtained, in words.

        Returns
        -------
        str
            E.g. "linearised" or "bootstrap, 200 resamples of 50-sample blocks, seed 0".
        """
        u = self.uncertainty
        method = u.get("method", "linearised")
        if method == "bootstrap":
            text = f"bootstrap, {u['resamples']} resamples of {u['block']}-sample blocks"
        elif method == "bootstrap-recordings":
            text = f"bootstrap over recordings, {u['resamples']} resamples"
        else:
            return method
        failed = f", {u['failed']} re-fits failed" if u.get("failed") else ""
        return f"{text}, seed {u.get('seed')}{failed}"

    def summary(self) -> str:
        """The fit in words: figures, parameters with standard errors, groups, identifiability.

        Returns
        -------
        str
            Several lines of text (also ``str(fit)``).
        """
        lines = [
            f"{type(self.model).__name__} identified from {len(self.recordings)} recording(s), "
            f"{self.n_samples} fitted samples",
            f"rmse {self.rmse:.4g}  nrmse {100 * self.nrmse:.3f} %  fit {self.fit_percent:.2f} %",
            f"{self.method}: {self.evaluations} evaluations, {self.generations} generations, "
            f"{self.seconds:.2f} s",
        ]
        if self.stopped_on_budget:
            lines.append("stopped by the time budget: the best model found by then")
        width = max(len(r[0]) for r in self.table())
        lines.append(f"parameters (+- standard error, {self.se_description()}; {GIVEN_CLASS}):")
        for name, value, se in self.table():
            lines.append(f"  {name:<{width}}  {value:>12}  +- {se}")
        if self.groups:
            lines.append("identified groups:")
            for name, g in self.groups.items():
                se = "held" if not g.get("identified", True) else _fmt(g.get("se"))
                lines.append(f"  {name}  {_fmt(g['value'])}  +- {se}  ({g.get('unit', '')})")
        lines.append("identifiability:")
        lines += [f"  {line}" for line in self.diagnostics.lines()]
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.summary()

    def to_dict(self) -> dict[str, Any]:
        """Figures of the fit (JSON-friendly), with the model itself.

        Returns
        -------
        dict
            The fields of the fit, the model as :meth:`HysteresisModel.to_dict`.
        """
        return {
            "model": self.model.to_dict(),
            "rmse": self.rmse,
            "nrmse": self.nrmse,
            "fit_percent": self.fit_percent,
            "standard_errors": self.standard_errors,
            "identified": self.identified,
            "fixed": self.fixed,
            "per_recording": self.per_recording,
            "evaluations": self.evaluations,
            "generations": self.generations,
            "seconds": self.seconds,
            "method": self.method,
            "message": self.message,
            "stopped_on_budget": self.stopped_on_budget,
            "input_range": None if self.input_range is None else list(self.input_range),
            "warmup": self.warmup,
            "n_samples": self.n_samples,
            "bounds": {k: [float(a), float(b)] for k, (a, b) in self.bounds.items()},
            "diagnostics": self.diagnostics.to_dict(),
            "groups": self.groups,
            "uncertainty": {
                k: v for k, v in self.uncertainty.items() if k not in ("samples", "covariance")
            },
        }

    def report(self, path: str | Path) -> Path:
        """Draw measured vs predicted over time, the input-output loop and the residual;
        emits the fit's identifiability warnings (:class:`IdentifiabilityWarning`).

        Parameters
        ----------
        path : str or Path
            The figure file.

        Returns
        -------
        Path
            The file written.
        """
        self.warn()
        return draw_report(self, Path(path))


def _fmt(v) -> str:
    if v is None:
        return "fixed"
    try:
        v = float(v)
    except (TypeError, ValueError):
        return str(v)
    return f"{v:.6g}"


def _field_names() -> list[str]:
    """The fields of :class:`Fit`, in order (what may be set on one)."""
    return [f.name for f in dataclass_fields(Fit)]


__all__ = ["Fit", "FitQuality", "GIVEN_CLASS", "fit_quality", "metrics", "simulate_model"]
