"""Identification as an object (issue 14 item 3): the Identifier estimator's parameters, clones,
fit (the same answer as identify, bit for bit), prediction, unknown settings, and
cross-validation over recordings against a hand-written loop."""

import inspect

import numpy as np
import pytest
from _realdata_helpers import plant_log

import tendonsheath as ts
from tendonsheath.identify import (
    IdentifiabilityWarning,
    Identifier,
    NotFittedError,
    cross_validate,
    metrics,
)
from tendonsheath.identify.estimator import DEFAULTS, IDENTIFIER_NAMES, Options
from tendonsheath.identify.settings import OSCILLATOR_DEFAULTS, OSCILLATOR_NAMES
from tendonsheath.models import (
    Backlash,
    BoucWen,
    BoucWenBacklash,
    Chain,
    CurveAngleModel,
    HystereticOscillator,
    Polynomial,
    PrandtlIshlinskii,
)

FAST = {"maxiter": 12, "popsize": 8, "progress": False}


@pytest.fixture(scope="module")
def log():
    return plant_log(n=300)


@pytest.fixture(scope="module")
def three_logs():
    return [plant_log(n=240, amplitude=a, periods=1.5) for a in (0.5, 0.7, 0.9)]


def test_get_params_set_params_round_trip():
    est = Identifier(BoucWenBacklash, maxiter=7, bounds={"rho": (1.0, 9.0)}, seed=3)
    params = est.get_params()
    assert list(params) == ["model", *IDENTIFIER_NAMES]
    assert params["model"] is BoucWenBacklash and params["maxiter"] == 7 and params["seed"] == 3
    assert params["popsize"] == 15  # an unset setting keeps identify()'s default
    assert Identifier(**params).get_params() == params
    other = Identifier(Backlash)
    assert other.set_params(**params) is other
    assert other.get_params() == params
    assert est.get_params(deep=False) == params


def test_init_takes_every_setting_as_a_keyword_with_identifys_default():
    # an explicit signature (no **settings), the one place the settings and their defaults
    # are written: Options reads it, a HystereticOscillator's own ones grouped in oscillator
    params = list(inspect.signature(Identifier).parameters.values())
    assert [p.name for p in params] == ["model", *IDENTIFIER_NAMES]
    assert set(IDENTIFIER_NAMES) == (set(DEFAULTS) - set(OSCILLATOR_NAMES)) | {"oscillator"}
    assert params[0].default is None and params[-1].default is None
    assert len(IDENTIFIER_NAMES) == 21 and len(DEFAULTS) == 23
    for p in params[1:-1]:
        assert p.kind is p.KEYWORD_ONLY and p.default == DEFAULTS[p.name], p.name
    est = Identifier(Backlash, maxiter=7)
    assert est.maxiter == 7 and est.popsize == 15
    assert est.options() == Options(maxiter=7)
    assert {n: getattr(est.options(), n) for n in OSCILLATOR_NAMES} == OSCILLATOR_DEFAULTS


def test_identify_takes_the_identifiers_settings_by_keyword():
    # identify's signature: the data, then **settings, read as Identifier's (its defaults) and
    # a HystereticOscillator's own ones flat; a misspelt one is a TypeError naming it and the
    # closest known one
    params = list(inspect.signature(ts.identify).parameters.values())
    assert [p.name for p in params] == [
        "model_class", "t", "x", "y", "recordings", "curve_angle", "load", "settings"
    ]  # fmt: skip
    assert params[-1].kind is params[-1].VAR_KEYWORD
    with pytest.raises(TypeError, match=r"'maxiters' \(did you mean maxiter\?\)"):
        ts.identify(Backlash, [0.0, 1.0], [0.0, 1.0], [0.0, 1.0], maxiters=5)
    options = Options(strategy="search", maxiter=3)
    assert options.replace(maxiter=4) == Options(strategy="search", maxiter=4)
    assert options.maxiter == 3 and options.popsize == 15  # unchanged; the default read


def test_oscillator_settings_are_grouped_and_the_old_keywords_are_refused(log):
    t, x, y = log
    fit = ts.identify(HystereticOscillator, t, x, y, strategy="search", periodic=False, **FAST)
    group = {"strategy": "search", "periodic": False}
    est = Identifier(HystereticOscillator, oscillator=group, **FAST)
    assert est.fit([(t, x, y)]).model_.to_dict() == fit.model.to_dict()  # identical floats
    # the old keywords of their own were removed (0.x): a TypeError naming the keyword
    with pytest.raises(TypeError, match="'strategy'"):
        Identifier(HystereticOscillator, strategy="search", oscillator={"periodic": False})
    with pytest.raises(TypeError, match="'input_interpolation'"):
        est.set_params(input_interpolation="hold")
    assert est.oscillator == group  # unchanged by the refused call
    with pytest.raises(TypeError, match=r"oscillator: unknown setting\(s\) 'strategie'"):
        Identifier(HystereticOscillator, oscillator={"strategie": "search"}).fit([(t, x, y)])
    with pytest.raises(TypeError, match="oscillator must be a dict"):
        Identifier(HystereticOscillator, oscillator="search").options()


def test_fit_returns_the_estimator_not_the_model(log):
    t, x, y = log
    est = Identifier(Backlash, **FAST)
    with pytest.raises(AttributeError, match="to_dict"):
        est.to_dict  # noqa: B018 (unfitted: no fallback)
    assert est.fit([(t, x, y)]) is est
    assert est.model_ is est.fit_.model
    # before, fit() returned the model: its attributes are the model_'s only (0.x removal)
    with pytest.raises(AttributeError, match="to_dict"):
        est.to_dict  # noqa: B018
    with pytest.raises(AttributeError, match="no_such_attribute"):
        est.no_such_attribute  # noqa: B018


def test_clone_is_unfitted_equal_and_independent(log):
    t, x, y = log
    est = Identifier(Backlash, fixed={"c_l": 0.9}, bounds={"c_r": (0.1, 3.0)}, **FAST)
    est.fit([(t, x, y)])
    twin = est.clone()
    assert twin.get_params() == est.get_params()
    assert not hasattr(twin, "fit_") and not hasattr(twin, "model_")
    with pytest.raises(NotFittedError, match="not fitted"):
        twin.predict([(t, x)])
    twin.bounds["c_r"] = (0.5, 1.0)  # containers are copied: the original keeps its own
    twin.fixed["c_l"] = 0.5
    twin.set_params(maxiter=3)
    assert est.bounds == {"c_r": (0.1, 3.0)} and est.fixed == {"c_l": 0.9}
    assert est.maxiter == FAST["maxiter"]


@pytest.mark.parametrize(
    "model, extra",
    [
        (Backlash, {}),
        (BoucWenBacklash, {}),
        (BoucWenBacklash, {"normalize": False}),
        (PrandtlIshlinskii, {}),
        (BoucWen, {}),
        (Chain(BoucWenBacklash(), Polynomial(3)), {}),
        (Backlash, {"standard_errors": "bootstrap", "bootstrap": 5}),
    ],
)
def test_fit_gives_identify_bit_for_bit(log, model, extra):
    t, x, y = log
    fit = ts.identify(model, t, x, y, **FAST, **extra)
    est = Identifier(model, **FAST, **extra)
    assert est.fit([(t, x, y)]) is est
    fitted = est.model_
    assert fitted is est.fit_.model
    assert fitted.to_dict() == fit.model.to_dict()  # identical floats, not approximately
    assert est.fit_.rmse == fit.rmse
    assert est.fit_.standard_errors.keys() == fit.standard_errors.keys()
    for name, se in fit.standard_errors.items():
        np.testing.assert_array_equal(est.fit_.standard_errors[name], se)


def test_fit_with_angle_laws_gives_identify_bit_for_bit(three_logs):
    recs = [(t, x, y, angle) for (t, x, y), angle in zip(three_logs, (0.5, 1.5, 2.5), strict=True)]
    laws = {"c_r": "linear"}
    fit = ts.identify(Backlash, recordings=recs, depends_on_angle=laws, **FAST)
    model = Identifier(Backlash, depends_on_angle=laws, **FAST).fit(recs).model_
    assert model.to_dict() == fit.model.to_dict()


def test_predict_and_score_match_the_fit(log):
    t, x, y = log
    est = Identifier(BoucWenBacklash, **FAST)
    est.fit((t, x, y))  # one recording as a tuple
    (pred,) = est.predict([(t, x)])
    np.testing.assert_array_equal(pred, est.fit_.predictions[0])
    np.testing.assert_array_equal(est.predict((t, x, y))[0], pred)
    assert est.score([(t, x, y)]) == pytest.approx(metrics(y, pred)["fit_percent"], abs=1e-12)
    assert est.score([(t, x, y)]) == pytest.approx(est.fit_.fit_percent, abs=1e-9)


def test_unknown_settings_are_rejected_by_name(log):
    t, x, y = log
    with pytest.raises(TypeError, match=r"unexpected keyword argument 'maxiters'"):
        Identifier(Backlash, maxiters=5)
    with pytest.raises(TypeError, match="'smoothing'"):
        Identifier(Backlash).set_params(smoothing=1.0)
    with pytest.raises(TypeError, match="'popsise'"):
        ts.identify(Backlash, t, x, y, popsise=5)
    with pytest.raises(ValueError, match="maxiter must be an integer >= 0"):
        Identifier(Backlash, maxiter=-1).fit([(t, x, y)])
    with pytest.raises(ValueError, match="standard_errors must be one of"):
        Identifier(Backlash, standard_errors="jackknife").fit([(t, x, y)])
    # the normalised path passes every setting down: no longer silently dropped there
    with pytest.raises(ValueError, match="Backlash has no input_interpolation option"):
        ts.identify(Backlash, t, x, y, input_interpolation="hold", **FAST)


def test_warnings_name_the_callers_line():
    """The steps are several calls deep: an IdentifiabilityWarning still points at the
    user's line (here, this file), from identify() and from Identifier.fit alike."""
    truth = CurveAngleModel(friction=0.2, stiffness=2e4, load_force=1.5)
    t = np.arange(0.0, 4.0, 5e-3)
    x = 0.6 * np.sin(2 * np.pi * 0.4 * t) + 0.2 * np.sin(2 * np.pi * 0.9 * t)
    y = truth.simulate(t, x, curve_angle=3.0)
    for run in (
        lambda: ts.identify(CurveAngleModel, t, x, y, curve_angle=3.0, **FAST),
        lambda: Identifier(CurveAngleModel, **FAST).fit([(t, x, y, 3.0)]),
    ):
        with pytest.warns(IdentifiabilityWarning, match="friction cannot be separated") as rec:
            run()
        assert {w.filename for w in rec} == {__file__}


def test_cross_validate_agrees_with_a_hand_written_loop(three_logs):
    est = Identifier(BoucWenBacklash, **FAST)
    cv = cross_validate(est, three_logs)
    assert cv.held_out_indices == [[0], [1], [2]]
    assert cv.description.startswith("cross-validation: leave one recording out (3 folds)")
    ys, yh = [], []
    for i, (t, x, y) in enumerate(three_logs):
        train = [r for j, r in enumerate(three_logs) if j != i]
        model = ts.identify(BoucWenBacklash, recordings=train, **FAST).model
        ys.append(y)
        yh.append(model.simulate(t, x))
        assert cv.estimators[i].model_.to_dict() == model.to_dict()
        np.testing.assert_array_equal(cv.predictions[i], yh[-1])
    want = metrics(np.concatenate(ys), np.concatenate(yh))
    assert cv.held_out == want
    assert not hasattr(est, "fit_")  # the estimator given is cloned, never fitted itself


def test_cross_validate_groups_recordings_round_robin(three_logs):
    cv = cross_validate(Identifier(Backlash, **FAST), three_logs, folds=2)
    assert cv.held_out_indices == [[0, 2], [1]]
    assert "group of recordings" in cv.description and len(cv.estimators) == 2
    with pytest.raises(ValueError, match="at least 2"):
        cross_validate(Identifier(Backlash, **FAST), three_logs[:1])
    with pytest.raises(ValueError, match="folds: at least 2"):
        cross_validate(Identifier(Backlash, **FAST), three_logs, folds=1)


def test_cross_validate_rejects_a_fold_count_that_is_not_an_integer_of_at_least_2(three_logs):
    # folds=0 used to fall back silently to the default split ("folds or 5")
    est = Identifier(Backlash, **FAST)
    for bad in (0, -3):
        with pytest.raises(ValueError, match="folds: at least 2"):
            cross_validate(est, three_logs, folds=bad)
    for bad in (2.5, "2", True):
        with pytest.raises(TypeError, match="folds must be an integer"):
            cross_validate(est, three_logs, folds=bad)
