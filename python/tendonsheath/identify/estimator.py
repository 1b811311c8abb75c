"""Identification as an object, in the scikit-learn mould: :class:`Identifier` stores the model
and the settings (keyword arguments of ``__init__``, kept as attributes of the same names),
``fit(recordings)`` returns the estimator with the fitted model in ``model_`` and the
:class:`Fit` in ``fit_``, and ``get_params``/``set_params``/``clone`` let a comparison or a
cross-validation make one unfitted copy per fold."""

from __future__ import annotations

import copy
import inspect
from collections.abc import Sequence
from typing import Any

import numpy as np

from .._util.typing import ArrayLike, RecordingLike, Recordings
from ..models import HysteresisModel
from .core import fit_recordings, identify_with
from .data import make_recordings
from .fit import Fit, metrics, simulate_model
from .settings import (
    OSCILLATOR_DEFAULTS,
    check_names,
    oscillator_settings,
)


class NotFittedError(ValueError, AttributeError):
    """An :class:`Identifier` used for prediction before ``fit``."""


class Identifier:
    """An identification's model and settings; ``fit(recordings)`` runs it.

    ``Identifier(model, maxiter=30, ...)`` takes the settings as keyword arguments (listed
    below) and stores them, unchanged and unchecked, as attributes of the same names
    (scikit-learn's convention), which ``get_params``, ``set_params`` and ``clone`` read and
    copy, so that a comparison or a cross-validation can make one unfitted copy per fold.
    ``fit(recordings)`` identifies the model and returns the estimator, with the fitted model
    in ``model_`` and the :class:`Fit` in ``fit_``: ``Identifier(model, ...).fit(recs).model_``.
    ``identify(model, t, x, y, **settings)`` is ``Identifier(model, **settings).fit_data(t, x,
    y)``, which returns the Fit. An unknown setting raises TypeError naming it; the values are
    checked by ``fit``. The settings are those of :func:`~tendonsheath.identify.identify`,
    whose docstring describes the search in full; this signature is the one place they and
    their defaults are written (:func:`~tendonsheath.identify.identify` and :class:`Options`
    read it). The settings that only a
    HystereticOscillator's identification reads (``input_interpolation``, ``periodic``,
    ``strategy``) are grouped in the ``oscillator`` dict: ``identify(HystereticOscillator, t, x,
    y, strategy="search")`` is ``Identifier(HystereticOscillator, oscillator={"strategy":
    "search"}).fit_data(t, x, y)``.

    Every Fit carries ``diagnostics`` (parameters near their bounds, correlations, condition
    number) and an :class:`~tendonsheath.identify.IdentifiabilityWarning` names the parameters
    involved. CurveAngleModel recordings at a single curve angle hold the friction
    (``initial``'s, 0.1 by default, unless ``fixed``) and report the identifiable groups in
    ``fit.groups``.

    Parameters
    ----------
    model : type, str or Chain
        The model class (e.g. ``BoucWenBacklash``) or its name, or a
        :class:`~tendonsheath.models.Chain` instance, e.g. ``Chain(BoucWenBacklash(),
        Polynomial(3))``. None (the default, for scikit-learn's protocol) cannot be fitted.
    warmup : int, default 0
        Samples at the start of every recording left out of the cost.
    bounds : dict of str to (float, float), optional
        Search bounds by parameter (default from the data's scale; some are searched on a log
        scale).
    fixed : dict of str to float, optional
        Parameters held at given values. Some are held by default because input/output data
        cannot identify them (BoucWen: A; HystereticOscillator: beta; CurveAngleModel:
        pretension, length, radii and load_stiffness).
    free : iterable of str, optional
        Parameters held by default that are to be identified.
    initial : HysteresisModel, optional
        Values of held parameters and numerical options (PrandtlIshlinskii: the threshold
        pattern, whose scale is identified; GeneralizedPrandtlIshlinskii: the plays, default
        10; PlantModel: its element count; CurveAngleModel: the friction held when the
        recordings cover a single curve angle, 0.1 by default).
    depends_on_angle : dict of str to str, optional
        Parameter -> "constant", "linear" or "tanh" law of the curve angle (one constant angle
        per recording); the result is an :class:`~tendonsheath.models.AngleDependent` model.
    seed : int or None, default 0
        Seed of the search (and of the bootstrap): seeded and reproducible.
    maxiter : int, default 100
        Generations of differential evolution.
    popsize : int, default 15
        Population per parameter.
    tol : float, default 0.01
        Relative tolerance of the search.
    workers : int, optional
        Threads of the batched simulations (default all cores).
    polish : bool, default True
        Refine the search's best candidate by least squares
        (``scipy.optimize.least_squares``).
    separable : bool, default True
        Solve linear-in-parameter parts by least squares (BoucWenBacklash: c_r, c_l, c_r B_r,
        c_l B_l; BoucWen: a, (1-a) k; PrandtlIshlinskii: the weights).
    progress : bool, default True
        Show a progress bar (on a terminal, for a search lasting over a second).
    search_samples : int or None, default 200000
        Samples the global search runs on at most (None: no limit). Above it the search runs
        on 8 evenly spaced windows per recording, each from the model's rest state with a fifth
        of it warm-up; a rate-independent model's search runs on records thinned to about
        2 000 samples (every m-th sample, m <= 20, and every turning point). The refinement
        and everything after use every sample.
    time_budget : float, optional
        Seconds of wall clock for the search and the refinement: the search stops after the
        generation in which it runs out and the least squares at its next evaluation, keeping
        the best point so far (``fit.stopped_on_budget`` records it). Standard errors and
        diagnostics come after, outside the budget.
    normalize : bool, default True
        Fit on centred, scaled data and map back (Backlash, BoucWenBacklash,
        PrandtlIshlinskii, GeneralizedPrandtlIshlinskii, PlantModel and Chains of a
        (Bouc-Wen) backlash and a polynomial): into the class's own parameters where exact,
        otherwise a :class:`~tendonsheath.models.Scaled` model. Not applied with ``bounds``,
        ``fixed`` or ``depends_on_angle``.
    standard_errors : {"linearised", "bootstrap", "bootstrap-recordings", "none"}
        How the standard errors are obtained (default "linearised": from the Jacobian at the
        optimum; "bootstrap": moving-block resamples of the residuals; "bootstrap-recordings":
        resampled recordings).
    bootstrap : int, optional
        Bootstrap resamples (default 200).
    bootstrap_block : int, optional
        Block length of the residual bootstrap (default from the autocorrelation).
    oscillator : dict, optional
        A HystereticOscillator's own settings, by key (each optional): ``"strategy"``
        ({"auto", "search"}, default "auto": best linear approximation, equation error, then
        simulation-error least squares; "search": the plain differential evolution),
        ``"input_interpolation"`` ({"hold", "linear", "bandlimited"}: the input
        reconstruction between samples; default detected from the input when no ``initial``
        is given, else ``initial``'s; another model class raises) and ``"periodic"`` (bool:
        whether the records are whole periods, for the band-limited reconstruction; default
        detected).

    Attributes
    ----------
    fit_ : Fit
        After ``fit``: the identification's result (errors, standard errors, diagnostics).
    model_ : HysteresisModel
        After ``fit``: the fitted model (``fit_.model``).

    See Also
    --------
    tendonsheath.identify.identify : The same identification as one call.
    tendonsheath.identify.cross_validate : Scores an Identifier over held-out recordings.
    """

    def __init__(
        self,
        model: type[HysteresisModel] | HysteresisModel | str | None = None,
        *,
        warmup: int = 0,
        bounds: dict | None = None,
        fixed: dict | None = None,
        free: Any = None,
        initial: Any = None,
        depends_on_angle: dict | None = None,
        seed: int | None = 0,
        maxiter: int = 100,
        popsize: int = 15,
        tol: float = 0.01,
        workers: int | None = None,
        polish: bool = True,
        separable: bool = True,
        progress: bool = True,
        search_samples: int | None = 200_000,
        time_budget: Any = None,
        normalize: bool = True,
        standard_errors: str = "linearised",
        bootstrap: int | None = None,
        bootstrap_block: int | None = None,
        oscillator: dict[str, Any] | None = None,
    ) -> None:
        # every setting stored as given, under its own name (scikit-learn's convention); this
        # signature is the one place the settings and their defaults are written (Options and
        # identify() read it); a HystereticOscillator's own settings are grouped in
        # ``oscillator``
        self.model = model
        self.warmup = warmup
        self.bounds = bounds
        self.fixed = fixed
        self.free = free
        self.initial = initial
        self.depends_on_angle = depends_on_angle
        self.seed = seed
        self.maxiter = maxiter
        self.popsize = popsize
        self.tol = tol
        self.workers = workers
        self.polish = polish
        self.separable = separable
        self.progress = progress
        self.search_samples = search_samples
        self.time_budget = time_budget
        self.normalize = normalize
        self.standard_errors = standard_errors
        self.bootstrap = bootstrap
        self.bootstrap_block = bootstrap_block
        self.oscillator = oscillator

    # -- parameters ------------------------------------------------------------------------

    def get_params(self, deep: bool = True) -> dict[str, Any]:
        """The model and every setting, as ``Identifier(**params)`` takes them.

        Parameters
        ----------
        deep : bool, default True
            Accepted for scikit-learn's protocol; the settings hold no nested estimators, so
            it changes nothing.

        Returns
        -------
        dict of str to object
            ``model`` and every setting by name (the values themselves, not copies).
        """
        return {"model": self.model, **{n: getattr(self, n) for n in IDENTIFIER_NAMES}}

    def set_params(self, **params: Any) -> Identifier:
        """Change settings (or ``model``) in place.

        The values are not checked here but by ``fit``; a fit made before keeps its ``fit_``
        and ``model_`` until the next ``fit``.

        Parameters
        ----------
        **params
            New values by name: ``model`` or any setting of :class:`Identifier` (``warmup``,
            ``bounds``, ``fixed``, ``free``, ``initial``, ``depends_on_angle``, ``seed``,
            ``maxiter``, ``popsize``, ``tol``, ``workers``, ``polish``, ``separable``,
            ``progress``, ``search_samples``, ``time_budget``, ``normalize``,
            ``standard_errors``, ``bootstrap``, ``bootstrap_block``, ``oscillator``).

        Returns
        -------
        Identifier
            This estimator, changed.

        Raises
        ------
        TypeError
            An unknown name (the message names it and the closest known ones); nothing is
            changed then.
        """
        check_names([n for n in params if n != "model"], type(self).__name__, IDENTIFIER_NAMES)
        for name, value in params.items():
            setattr(self, name, value)
        return self

    def clone(self) -> Identifier:
        """An unfitted copy with equal settings.

        Dicts, lists, sets and tuples among the settings are deep-copied, so editing one's
        ``bounds`` or ``fixed`` leaves the other's as it was; the model and other values are
        shared.

        Returns
        -------
        Identifier
            A new estimator of the same class with the same model and settings, without
            ``fit_`` or ``model_``.
        """
        params = {k: _copied(v) for k, v in self.get_params().items()}
        return type(self)(**params)

    def options(self) -> Options:
        """The settings as one record, as the identification takes them.

        Returns
        -------
        Options
            A frozen :class:`Options` of the current settings,
            ``oscillator``'s among them (their values unchecked: ``fit`` checks them).

        Raises
        ------
        TypeError
            ``oscillator`` is not a dict, or has a key that is no oscillator setting.
        """
        general = {n: getattr(self, n) for n in IDENTIFIER_NAMES if n != "oscillator"}
        return Options(**general, **oscillator_settings(self.oscillator, type(self).__name__))

    def __repr__(self) -> str:
        changed = [
            f"{n}={getattr(self, n)!r}" for n in IDENTIFIER_NAMES if _differs(getattr(self, n), n)
        ]
        name = getattr(self.model, "__name__", None) or repr(self.model)
        return f"{type(self).__name__}({', '.join([name, *changed])})"

    # -- fitting and prediction ------------------------------------------------------------

    def fit(self, recordings: Recordings, *, curve_angle: ArrayLike | None = None) -> Identifier:
        """Identify the model from recordings; the recordings share the parameters.

        Parameters
        ----------
        recordings : Log, Recording, tuple or sequence of them
            One recording or a list of them: :class:`~tendonsheath.io.Log` objects (with an
            output column), Recordings, or (t, x, y) or (t, x, y, curve_angle) tuples. ``t``
            may be None for a rate-independent model.
        curve_angle : float or array_like of float, optional
            The curve angle (rad) of the recordings that carry none, for models that take one.

        Returns
        -------
        Identifier
            This estimator, fitted: the model in ``model_``, the :class:`Fit` in ``fit_``.

        Raises
        ------
        ValueError
            Bad data or settings (the message names them), or a setting the model does not
            support.
        """
        self.fit_data(recordings=_as_list(recordings), curve_angle=curve_angle)
        return self

    def fit_data(
        self,
        t: ArrayLike | None = None,
        x: ArrayLike | None = None,
        y: ArrayLike | None = None,
        *,
        recordings: Sequence[RecordingLike] | None = None,
        curve_angle: ArrayLike | None = None,
    ) -> Fit:
        """``fit`` with :func:`~tendonsheath.identify.identify`'s two data forms.

        Give ``t, x, y`` (one recording) or ``recordings=``, not both.

        Parameters
        ----------
        t : array_like of float, shape (n,), optional
            Sample times (s); None for a rate-independent model.
        x : array_like of float, shape (n,), optional
            Input samples (or give ``recordings``).
        y : array_like of float, shape (n,), optional
            Output samples.
        recordings : sequence of tuple, optional
            (t, x, y) or (t, x, y, curve_angle) per recording (or Logs, Recordings), instead
            of t, x, y.
        curve_angle : float or array_like of float, optional
            The curve angle (rad) of t, x, y (or of the recordings that carry none), for
            models that take one.

        Returns
        -------
        Fit
            The identified model, its errors, standard errors and diagnostics (also kept in
            ``fit_``; the model in ``model_``).

        Raises
        ------
        ValueError
            Bad data or settings (the message names them), or a setting the model does not
            support.
        """
        self.fit_ = fit_recordings(
            self.model, self.options(), t, x, y, recordings=recordings, curve_angle=curve_angle
        )
        self.model_ = self.fit_.model
        return self.fit_

    def predict(self, recordings: Recordings) -> list[np.ndarray]:
        """The fitted model's output over each recording's input, run from its rest state.

        Parameters
        ----------
        recordings : Log, Recording, tuple or sequence of them
            One recording or a list of them: Logs, Recordings, or (t, x), (t, x, y) or
            (t, x, y, curve_angle) tuples (the output is not used).

        Returns
        -------
        list of numpy.ndarray of float
            One array per recording, of its input's length.

        Raises
        ------
        NotFittedError
            Called before ``fit``.
        ValueError
            A recording of none of the forms above.
        """
        model = self._fitted()
        return [simulate_model(model, t, x, angle) for t, x, angle in _inputs(recordings)]

    def score(self, recordings: Recordings) -> float:
        """How well the fitted model predicts recordings: the fit percentage (higher is better).

        The fit percentage of :func:`~tendonsheath.identify.metrics`,
        100 (1 - ||y - y_hat|| / ||y - mean(y)||), pooled over every recording; the model runs
        from its rest state over each, and the first ``warmup`` samples of each (and a
        Recording's ``skip``) are not counted.

        Parameters
        ----------
        recordings : Log, Recording, tuple or sequence of them
            One recording or a list of them, with outputs: Logs, Recordings, or (t, x, y) or
            (t, x, y, curve_angle) tuples.

        Returns
        -------
        float
            The fit percentage: 100 for a perfect prediction, 0 for predicting the mean,
            NaN for a constant output.

        Raises
        ------
        NotFittedError
            Called before ``fit``.
        ValueError
            Bad data (the message names it).
        """
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
            route = getattr(r, "route", None)  # a Recording's sensed route, when it has one
            angle = getattr(r, "curve_angle", None) if route is None else route
            out.append((getattr(r, "t", None), np.asarray(r.x), angle))
        elif isinstance(r, tuple | list) and 2 <= len(r) <= 4:
            angle = r[3] if len(r) == 4 else None
            out.append((r[0], np.asarray(r[1], dtype=float), angle))
        else:
            raise ValueError(f"recording {i}: a Log, a Recording or (t, x[, y[, curve_angle]])")
    return out


#: the settings of an Identifier besides ``model``, in its signature's order (``oscillator``
#: last): its signature is the one place they are written
IDENTIFIER_NAMES: tuple[str, ...] = tuple(inspect.signature(Identifier).parameters)[1:]
#: every setting of one identification with its default: the Identifier's (its signature's),
#: a HystereticOscillator's own ones flat in place of ``oscillator``
DEFAULTS: dict[str, Any] = {
    **{
        name: p.default
        for name, p in inspect.signature(Identifier).parameters.items()
        if name in IDENTIFIER_NAMES and name != "oscillator"
    },
    **OSCILLATOR_DEFAULTS,
}
OPTION_NAMES: tuple[str, ...] = tuple(DEFAULTS)


class Options:
    """Every setting of one identification, by name (``options.maxiter``), as the
    identification paths take them: the Identifier's settings with its signature's defaults,
    a HystereticOscillator's own ones (``input_interpolation``, ``periodic``, ``strategy``)
    flat. Immutable: :meth:`replace` makes a changed copy.

    Parameters
    ----------
    **settings
        Settings by name (:data:`OPTION_NAMES`); the others take their defaults.

    Raises
    ------
    TypeError
        An unknown setting (named, with the closest known ones).
    """

    __slots__ = ("_values",)
    _values: dict[str, Any]

    def __init__(self, **settings: Any) -> None:
        check_names(settings, "identify", OPTION_NAMES)
        object.__setattr__(self, "_values", {**DEFAULTS, **settings})

    def __getattr__(self, name: str) -> Any:
        if not name.startswith("_") and name in self._values:
            return self._values[name]
        raise AttributeError(f"Options has no setting {name!r}")

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError(f"Options are frozen: use replace({name}=...)")

    def __eq__(self, other: object) -> bool:
        return type(other) is type(self) and self._values == other._values

    __hash__ = None  # type: ignore[assignment]  # settings hold dicts

    def __reduce__(self):
        return _options, (self._values,)

    def __repr__(self) -> str:
        return f"Options({', '.join(f'{k}={v!r}' for k, v in self._values.items())})"

    def replace(self, **changes: Any) -> Options:
        """A copy with some settings changed.

        Parameters
        ----------
        **changes
            Settings by name, with their new values.

        Returns
        -------
        Options
            The changed copy; this one is unchanged.
        """
        return Options(**{**self._values, **changes})

    def as_dict(self) -> dict[str, Any]:
        """Every setting by name (a copy of the dict).

        Returns
        -------
        dict
            The settings.
        """
        return dict(self._values)


def _options(values: dict[str, Any]) -> Options:
    return Options(**values)


def identify(
    model_class: type[HysteresisModel] | HysteresisModel | str,
    t: ArrayLike | None = None,
    x: ArrayLike | None = None,
    y: ArrayLike | None = None,
    *,
    recordings: Sequence | None = None,
    curve_angle: ArrayLike | None = None,
    load: Any = None,
    **settings: Any,
) -> Fit:
    """Identify a model from input/output recordings by simulation-error minimisation.

    Data: ``identify(cls, t, x, y)`` (``curve_angle=`` a number or per-sample array for models
    that use it) or ``identify(cls, recordings=[(t, x, y), (t, x, y, curve_angle), ...])``; the
    recordings share the parameters. ``t`` may be None for rate-independent models. A
    recording's curve angle may also be a :class:`~tendonsheath.Route` (e.g. the sensed
    shape, held over that recording): CurveAngleModel and ``depends_on_angle`` models then use
    its distribution of curvature (the shape integrals g, G, recomputed for every candidate
    friction), not its curve angle alone.

    The cost is the sum of squared simulation errors (the model runs free from its initial
    state; the first ``warmup`` samples of every recording are not counted). A global search
    by SciPy's differential evolution (``popsize``, ``maxiter``, ``tol``, ``seed``: seeded and
    reproducible) evaluates each generation in one batched C++ call spread over ``workers``
    threads (default: all cores), then ``scipy.optimize.least_squares`` refines the best
    candidate (``polish=False`` skips it). Bounds are derived from the data's scale unless
    given in ``bounds`` ({name: (low, high)}); some are searched on a log scale.

    Long records: the global search only has to find the basin, so when the recordings hold
    more than ``search_samples`` samples (default 200 000; None: no limit) it runs on 8 evenly
    spaced windows per recording counting that many samples (each window starts from the
    model's rest state, with a warm-up of a fifth of its length); the refinement and
    everything after it use every sample. A rate-independent model's search runs on the
    records thinned to about 2 000 samples (every m-th sample, m <= 20, and every turning
    point of the input; see :func:`~tendonsheath.identify.data.thin_for_search`).
    The cost per evaluation is linear in the samples and
    memory grows linearly with them (no candidate's output is kept during the search).

    Linear-in-parameter parts are solved by least squares instead of searched (``separable``):
    BoucWenBacklash (c_r, c_l, c_r B_r, c_l B_l given rho, sigma, n), BoucWen (a, (1-a) k
    given the state z) and PrandtlIshlinskii (the weights, given the threshold scale).

    ``fixed`` holds parameters at given values; some are held by default because they are
    not identifiable from input/output data (BoucWen: A; HystereticOscillator: beta;
    CurveAngleModel: pretension, length, radii and load_stiffness); ``free`` releases those.
    ``initial`` supplies the values of held parameters and the numerical options (for
    PrandtlIshlinskii: the threshold pattern, whose scale is identified).

    ``depends_on_angle`` ({name: "constant" | "linear" | "tanh"}) makes parameters functions
    of the curve angle (one constant angle per recording); the result is then an
    :class:`~tendonsheath.models.AngleDependent` model that predicts at any angle.

    ``model_class`` may also be a :class:`~tendonsheath.models.Chain` instance, e.g.
    ``Chain(BoucWenBacklash(), Polynomial(3))``: the first model's nonlinear parameters are
    searched (its output scale held, the polynomial carries it) and the polynomial
    coefficients are solved by least squares for every candidate (see
    :func:`~tendonsheath.identify.chain.identify_chain`).

    HystereticOscillator (``strategy="auto"``): best linear approximation, then an
    equation-error stage, then simulation-error least squares (see
    :mod:`tendonsheath.identify.oscillator`); ``strategy="search"`` runs the plain
    differential evolution instead. ``input_interpolation`` ("hold", "linear",
    "bandlimited"; default: detected from the input when no ``initial`` is given, see
    :mod:`tendonsheath.identify.interpolation`, else ``initial``'s) is the input
    reconstruction between samples,
    recorded in the fitted model's options and the Fit's method; ``periodic`` says whether
    the records are whole periods (None: detected) for the band-limited reconstruction;
    ``time_budget`` (seconds of wall clock, every model and chain): the global search stops
    after the generation in which it runs out and the least-squares stage at its next
    evaluation, keeping the best point so far; ``fit.stopped_on_budget`` records it and
    ``fit.message`` says so. Standard errors and diagnostics are computed after it, outside
    the budget.

    PlantModel (the grey-box pull-pull plant): friction angle, backlash and viscous time are
    searched by a short differential evolution (at most 25 generations of 6 per parameter:
    each candidate is a plant simulation) and refined by least squares; the output gain and
    offset are solved by least squares for every candidate (see
    :mod:`tendonsheath.identify.plant_model`). ``bounds``, ``fixed`` and ``depends_on_angle``
    are not supported for it; ``initial`` sets its element count.

    GeneralizedPrandtlIshlinskii: the envelopes and the threshold scale are searched, the
    weights (>= 0) and an output offset are solved by bounded least squares; ``initial``
    gives the number of plays and the threshold pattern (default 10 evenly spaced plays).

    Any sign, offset and units (``normalize``, default on): Backlash, BoucWenBacklash,
    PrandtlIshlinskii, GeneralizedPrandtlIshlinskii and Chains of a (Bouc-Wen)
    backlash and a polynomial are fitted on centred, scaled data with a positive gain and
    mapped back (see :mod:`tendonsheath.identify.normalize`): into the class's own parameters
    where exact, otherwise as a :class:`~tendonsheath.models.Scaled` model (e.g. a negative
    gain). Not applied with ``bounds``, ``fixed`` or ``depends_on_angle`` (raw units).

    A measured load (``load=``: per-sample array of t, x, y, or one array per recording;
    recordings that are :class:`~tendonsheath.io.Log` objects bring their own ``Log.load``)
    is taken by a :class:`~tendonsheath.models.Loaded` model, e.g.
    ``identify(Loaded(BoucWenBacklash), recordings=logs)``, staged: the tendon's stretch by a
    linear regression, the base alone on the data without it, the load's play terms with the
    base held, then everything jointly; a (generalized) Prandtl-Ishlinskii base's weights are
    kept >= 0 (see :mod:`tendonsheath.identify.loaded`; ``fixed`` may hold load terms; the
    other settings go to the base's identification).

    Uncertainty and identifiability (:mod:`tendonsheath.identify.diagnostics`): every Fit
    carries ``standard_errors`` (``standard_errors="linearised"``: from the Jacobian at the
    optimum; ``"bootstrap"``: the spread of ``bootstrap`` (default 200) moving-block
    bootstrap resamples of the residuals, each re-fitted by least squares from the estimate,
    seeded by ``seed``, blocks of ``bootstrap_block`` samples (default from the residual's
    autocorrelation); ``"bootstrap-recordings"``: resamples of the recordings, drawn with
    replacement (for many recordings); ``"none"``) and ``diagnostics`` (parameters near
    their bounds, correlations, condition number); an :class:`IdentifiabilityWarning` names
    the parameters involved. CurveAngleModel recordings that cover a single curve angle
    cannot separate friction from EA: the friction is then held (at ``initial``'s value, 0.1
    by default, unless given in ``fixed``), with a warning, and the identifiable groups
    (dead-zone half-width, load offset, gain at that angle) are reported in ``fit.groups``.

    Parameters
    ----------
    model_class : type or Chain
        The model class (e.g. ``BoucWenBacklash``), or a Chain instance.
    t : array_like of float, shape (n,), optional
        Sample times (s); None for a rate-independent model.
    x : array_like of float, shape (n,), optional
        Input samples (or give ``recordings``).
    y : array_like of float, shape (n,), optional
        Output samples.
    recordings : sequence of tuple, optional
        (t, x, y) or (t, x, y, curve_angle) per recording, instead of t, x, y.
    curve_angle : float, array_like of float, or Route, optional
        The curve angle (rad) of t, x, y, or its route, for models that take one.
    load : array_like of float, or sequence of them, optional
        The measured load of t, x, y (or one per recording), for a Loaded model.
    **settings
        The settings of :class:`~tendonsheath.identify.Identifier` (each described there,
        with its default), a HystereticOscillator's own (the keys of Identifier's
        ``oscillator``) as keywords of their own.

    Returns
    -------
    Fit
        The identified model, its errors, standard errors and diagnostics.

    Raises
    ------
    TypeError
        An unknown setting (named, with the closest known ones).
    ValueError
        Bad data or arguments (the message names them), or an option the model does not
        support.
    """
    options = Options(**settings)  # the settings, by Identifier's names and defaults
    return identify_with(
        model_class, options, t, x, y, recordings=recordings, curve_angle=curve_angle, load=load
    )


def _copied(value):
    if isinstance(value, dict | list | set | tuple):
        return copy.deepcopy(value)
    return value


def _differs(value, name: str) -> bool:
    default = DEFAULTS.get(name)
    try:
        return bool(value != default)
    except (TypeError, ValueError):
        return True


__all__ = ["Identifier", "NotFittedError", "Options", "identify"]
