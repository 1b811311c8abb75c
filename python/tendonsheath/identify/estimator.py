"""Identification as an object, in the scikit-learn mould: :class:`Identifier` stores the model
and the settings, ``fit(recordings)`` returns the fitted model (the :class:`Fit` kept in
``fit_``), ``get_params``/``set_params``/``clone`` let a comparison or a cross-validation make
one unfitted copy per fold."""

from __future__ import annotations

import copy
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._typing import ArrayLike, RecordingLike, Recordings
from ..models import HysteresisModel
from .data import make_recordings
from .fit import Fit, metrics, simulate_model
from .settings import (
    DEFAULTS,
    OPTION_NAMES,
    Options,
    Search,
    check_names,
    with_settings_signature,
)


class NotFittedError(ValueError, AttributeError):
    """An :class:`Identifier` used for prediction before ``fit``."""


class Identifier:
    """An identification's model and settings; ``fit(recordings)`` runs it.

    ``Identifier(model, **settings)``: ``model`` is a model class (or its name), or a
    :class:`~tendonsheath.models.Chain` instance, e.g. ``Chain(BoucWenBacklash(),
    Polynomial(3))``. ``identify(model, t, x, y, **settings)`` is
    ``Identifier(model, **settings).fit([(t, x, y)])`` with the :class:`Fit` returned. An
    unknown setting raises TypeError naming it; the values are checked by ``fit``.

    Settings (defaults in :class:`~tendonsheath.identify.settings.Options`):

    - ``warmup`` (0): the first samples of every recording are not counted in the cost.
    - Global search by SciPy's differential evolution: ``popsize`` (15), ``maxiter`` (100),
      ``tol`` (0.01), ``seed`` (0: seeded and reproducible); each generation is evaluated in
      one batched C++ call over ``workers`` threads (None: all cores). ``polish`` (True):
      ``scipy.optimize.least_squares`` refines the best candidate. ``progress`` (True): a bar
      on a terminal.
    - ``bounds`` ({name: (low, high)}): otherwise derived from the data's scale, some searched
      on a log scale. ``fixed`` ({name: value}) holds parameters; some are held by default
      because input/output data cannot identify them (BoucWen: A; HystereticOscillator: beta;
      CurveAngleModel: pretension, length, radii and spring); ``free`` releases those.
      ``initial`` supplies held values and numerical options (PrandtlIshlinskii: the
      threshold pattern, whose scale is identified; GeneralizedPrandtlIshlinskii: the plays,
      default 10; PlantModel: its element count).
    - ``search_samples`` (200 000; None: no limit): above it the global search runs on 8 evenly
      spaced windows per recording counting that many samples (each from the model's rest
      state, a fifth of it warm-up); a rate-independent model's search runs on records
      thinned to about 2 000 samples (every m-th sample, m <= 20, and every turning point).
      The refinement and everything after use every sample.
    - ``separable`` (True): linear-in-parameter parts are solved by least squares instead of
      searched (BoucWenBacklash: c_r, c_l, c_r B_r, c_l B_l; BoucWen: a, (1-a) k;
      PrandtlIshlinskii: the weights).
    - ``depends_on_angle`` ({name: "constant" | "linear" | "tanh"}): parameters as functions of
      the curve angle (one constant angle per recording); the result is an
      :class:`~tendonsheath.models.AngleDependent` model.
    - ``strategy`` ("auto"): HystereticOscillator by best linear approximation, equation error,
      then simulation-error least squares; "search" runs the plain differential evolution.
      ``input_interpolation`` ("hold", "linear", "bandlimited"; default: ``initial``'s) and
      ``periodic`` (None: detected) set its input reconstruction.
    - ``time_budget`` (seconds of wall clock): the search stops after the generation in which
      it runs out and the least squares at its next evaluation; ``fit.stopped_on_budget``
      records it. Standard errors and diagnostics come after, outside the budget.
    - ``normalize`` (True): Backlash, BoucWenBacklash, PrandtlIshlinskii,
      GeneralizedPrandtlIshlinskii, PlantModel and Chains of a (Bouc-Wen) backlash and a
      polynomial are fitted on centred, scaled data and mapped back (into the class's own
      parameters where exact, otherwise a :class:`~tendonsheath.models.Scaled` model); not
      with ``bounds``, ``fixed`` or ``depends_on_angle``.
    - ``standard_errors`` ("linearised"; "bootstrap": ``bootstrap`` (200) moving-block
      resamples of the residuals, blocks of ``bootstrap_block`` samples (default from the
      residual's autocorrelation); "bootstrap-recordings": resampled recordings; "none"). Every
      Fit carries ``diagnostics`` (parameters near bounds, correlations, condition number) and
      an :class:`~tendonsheath.identify.IdentifiabilityWarning` names the parameters involved.
      CurveAngleModel recordings at a single curve angle hold the friction (``initial``'s, 0.1
      by default, unless ``fixed``) and report the identifiable groups in ``fit.groups``.

    Attributes after ``fit``: ``fit_`` (the :class:`Fit`) and ``model_`` (the fitted model).
    """

    warmup: int  # one of the settings (OPTION_NAMES), set by __init__ and set_params

    @with_settings_signature
    def __init__(
        self, model: type[HysteresisModel] | HysteresisModel | str | None = None, **settings: Any
    ):
        check_names(settings, type(self).__name__)
        self.model = model
        for name in OPTION_NAMES:
            setattr(self, name, settings.get(name, DEFAULTS[name]))

    # -- parameters ------------------------------------------------------------------------

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        """The model and every setting, {name: value} (``deep``: accepted for scikit-learn's
        protocol; the settings hold no nested estimators)."""
        return {"model": self.model, **{n: getattr(self, n) for n in OPTION_NAMES}}

    def set_params(self, **params: Any) -> Identifier:
        """Change settings (or ``model``); returns self. Unknown names raise TypeError."""
        check_names([n for n in params if n != "model"], type(self).__name__)
        for name, value in params.items():
            setattr(self, name, value)
        return self

    def clone(self) -> Identifier:
        """An unfitted copy with equal settings (containers copied, so editing one's
        ``bounds`` or ``fixed`` leaves the other's as it was)."""
        params = {k: _copied(v) for k, v in self.get_params().items()}
        return type(self)(**params)

    def options(self) -> Options:
        """The settings as an :class:`~tendonsheath.identify.settings.Options` record."""
        return Options(**{n: getattr(self, n) for n in OPTION_NAMES})

    def __repr__(self) -> str:
        changed = [
            f"{n}={getattr(self, n)!r}" for n in OPTION_NAMES if _differs(getattr(self, n), n)
        ]
        name = getattr(self.model, "__name__", None) or repr(self.model)
        return f"{type(self).__name__}({', '.join([name, *changed])})"

    # -- fitting and prediction ------------------------------------------------------------

    def fit(
        self, recordings: Recordings, *, curve_angle: ArrayLike | None = None
    ) -> HysteresisModel:
        """Identify the model from ``recordings`` (Logs, Recordings or (t, x, y[, curve_angle])
        tuples; ``curve_angle`` applies to those without one); returns the fitted model."""
        self.fit_data(recordings=_as_list(recordings), curve_angle=curve_angle)
        return self.model_

    def fit_data(
        self,
        t: ArrayLike | None = None,
        x: ArrayLike | None = None,
        y: ArrayLike | None = None,
        *,
        recordings: Sequence[RecordingLike] | None = None,
        curve_angle: ArrayLike | None = None,
    ) -> Fit:
        """``fit`` with identify()'s two data forms (t, x, y or recordings=); returns the Fit."""
        from .core import run

        options = self.options()
        search = Search.of(options)  # checked before the data, as identify() always did
        recs = make_recordings(t, x, y, recordings=recordings, curve_angle=curve_angle)
        self.fit_ = run(self.model, recs, options, search)
        self.model_ = self.fit_.model
        return self.fit_

    def predict(self, recordings: Recordings) -> list[np.ndarray]:
        """The fitted model's output over each recording's input (Logs, Recordings or
        (t, x[, y[, curve_angle]]) tuples), run from its rest state: one array per recording."""
        model = self._fitted()
        return [simulate_model(model, t, x, angle) for t, x, angle in _inputs(recordings)]

    def score(self, recordings: Recordings) -> float:
        """Fit percentage, 100 (1 - nrmse), of the prediction over ``recordings`` (higher is
        better; the first ``warmup`` samples and each recording's skip are not counted)."""
        self._fitted()
        recs = make_recordings(recordings=_as_list(recordings))
        preds = self.predict(recs)
        start = [int(self.warmup) + r.skip for r in recs]
        y = np.concatenate([r.y[k:] for r, k in zip(recs, start, strict=True)])
        yh = np.concatenate([p[k:] for p, k in zip(preds, start, strict=True)])
        return float(metrics(y, yh)["fit_percent"])

    def _fitted(self):
        if not hasattr(self, "model_"):
            raise NotFittedError(f"this {type(self).__name__} is not fitted: call fit() first")
        return self.model_


def _as_list(recordings):
    """One recording (a Log, a Recording or a tuple) as a list of one; lists as they are."""
    if recordings is None or isinstance(recordings, list):
        return recordings
    if (
        isinstance(recordings, tuple)
        and len(recordings) in (3, 4)
        and not hasattr(recordings[0], "x")
    ):
        return [recordings]
    if hasattr(recordings, "x") and hasattr(recordings, "y"):
        return [recordings]
    return list(recordings)


def _inputs(recordings):
    """(t, x, curve_angle) of each recording; tuples may omit the output."""
    if hasattr(recordings, "x") or (
        isinstance(recordings, tuple)
        and recordings
        and not hasattr(recordings[0], "x")
        and not isinstance(recordings[0], tuple)
    ):
        recordings = [recordings]
    out = []
    for i, r in enumerate(recordings):
        if hasattr(r, "x"):
            out.append((getattr(r, "t", None), np.asarray(r.x), getattr(r, "curve_angle", None)))
        elif isinstance(r, tuple | list) and 2 <= len(r) <= 4:
            angle = r[3] if len(r) == 4 else None
            out.append((r[0], np.asarray(r[1], dtype=float), angle))
        else:
            raise ValueError(f"recording {i}: a Log, a Recording or (t, x[, y[, curve_angle]])")
    return out


def _copied(value):
    if isinstance(value, dict | list | set | tuple):
        return copy.deepcopy(value)
    return value


def _differs(value, name: str) -> bool:
    default = DEFAULTS[name]
    try:
        return bool(value != default)
    except (TypeError, ValueError):
        return True
