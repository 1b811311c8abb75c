"""Classes of silent answers (Step 22), each walked over every entry point of its class found
programmatically, so that a new entry point is walked without a new test:

1. wrong-kind objects: every compensator in ``ts.compensate`` whose constructor takes a
   feedforward, a model or a forward model first, and every ``from_calibration``, given a
   forward model, a model class, a Fit-like dict or a plant's sensor: a one-line TypeError
   naming the constructor (a new such constructor with a required argument the walk does
   not know fails here until it is given a value);
2. missing measurements: every model in ``ts.models`` whose ``control_inputs`` name more
   than the input (a load, a curve angle), simulated or stepped without it: a one-line
   ValueError, never an answer for 0; the compensators that take one likewise;
3. identifiability: inputs whose data cannot determine an estimate (a constant load, two
   joints driven by one signal, the output equal to the input, the encoder equal to the
   command) refused by name at every ``identify*`` entry they reach, and standard errors of
   undetermined directions inf, never 0.
"""

from __future__ import annotations

import inspect

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.identify import identify_servo
from tendonsheath.identify.diagnostics import linearised_se
from tendonsheath.identify.newey_west import newey_west

# -- 1. wrong-kind objects --------------------------------------------------------------------

#: the first parameters that take an object of a kind (a compensator or a model)
_KIND_PARAMS = ("feedforward", "model", "feedforward_model")
#: values for the other required arguments of those constructors
_GOOD = {"t": np.arange(10) * 0.01, "reference": np.zeros(10), "table": np.zeros(3),
         "table_dt": 0.01}  # fmt: skip


def _kind_constructors():
    out = []
    for name in ts.compensate.__all__:
        cls = getattr(ts.compensate, name)
        if not inspect.isclass(cls):
            continue
        params = list(inspect.signature(cls.__init__).parameters.values())[1:]
        if params and params[0].name in _KIND_PARAMS:
            out.append(pytest.param(cls, params, id=name))
    return out


def _wrong_kinds():
    return {
        "a forward model": ts.models.Backlash(),
        "a model class": ts.models.Backlash,
        "a dict": {"c_r": 1.0},
        "a sensor": ts.Sensor(),
    }


def test_the_walk_finds_the_constructors_that_take_a_kind():
    """The walk is not empty: the constructors known today are among those it finds (a
    renamed first parameter would drop one silently otherwise)."""
    found = {p.id for p in _kind_constructors()}
    assert {"EncoderLoop", "TipLoop", "InverseFeedforward", "LoadCompensated",
            "LearnedFeedforward", "IterativeLearning", "AdaptiveController",
            "CoupledFeedforward"} <= found  # fmt: skip


@pytest.mark.parametrize(("cls", "params"), _kind_constructors())
@pytest.mark.parametrize("kind", list(_wrong_kinds()))
def test_a_constructor_given_the_wrong_kind_says_what_it_wants(cls, params, kind):
    wrong = _wrong_kinds()[kind]
    if params[0].name != "feedforward" and kind == "a forward model":
        wrong = ts.compensate.InverseFeedforward(ts.models.Backlash())  # a compensator
        if cls is ts.compensate.InverseFeedforward:
            wrong = ts.models.Loaded(ts.models.Backlash())  # needs its load: LoadCompensated
    rest = {}
    for p in params[1:]:
        if p.default is p.empty and p.kind is p.POSITIONAL_OR_KEYWORD:
            assert p.name in _GOOD, f"{cls.__name__}: give the walk a value for {p.name}"
            rest[p.name] = _GOOD[p.name]
    with pytest.raises(TypeError) as err:
        cls(wrong, **rest)
    message = str(err.value)
    assert "\n" not in message and message.startswith(cls.__name__), message


def test_the_forward_model_as_a_feedforward_names_its_inverse():
    with pytest.raises(TypeError, match=r"not the forward model Backlash.*InverseFeedforward"):
        ts.compensate.EncoderLoop(ts.models.Backlash())
    with pytest.raises(TypeError, match=r"LoadCompensated\(model\)"):
        ts.compensate.InverseFeedforward(ts.models.Loaded(ts.models.Backlash()))


def _from_calibrations():
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash())
    return [
        pytest.param(
            lambda bad: ts.compensate.TipLoop.from_calibration(ts.models.Backlash(), bad),
            id="TipLoop",
        ),  # fmt: skip
        pytest.param(
            lambda bad: ts.compensate.AdaptiveController.from_calibration(
                ts.models.Backlash(), bad, inertia=1e-4
            ),
            id="AdaptiveController",
        ),  # fmt: skip
        pytest.param(
            lambda bad: ts.compensate.EncoderLoop.from_calibration(ff, bad), id="EncoderLoop"
        ),  # fmt: skip
        pytest.param(lambda bad: ts.compensate.tune_encoder_loop(bad), id="tune_encoder_loop"),
    ]


@pytest.mark.parametrize("call", _from_calibrations())
@pytest.mark.parametrize("bad", [{"resonance_hz": 40.0}, [1.0, 2.0], "dynamics"])
def test_a_design_from_the_wrong_kind_of_calibration_is_one_line(call, bad):
    """TipLoop.from_calibration(model, dict) was an AttributeError from deep in the tuner."""
    with pytest.raises(TypeError, match=r"must be a (LoopDynamics|ServoFit)") as err:
        call(bad)
    assert "\n" not in str(err.value)


def test_a_python_step_that_takes_a_measurement_it_does_not_declare_is_named():
    """bench.run with step(y_d, y, dt) and no step_inputs failed inside the C++ loop."""

    class PI:
        def reset(self):
            pass

        def step(self, y_d, y, dt):
            return y_d

    plant = ts.PullPullPlant(ts.Route.uniform(1.0, 1.5), elements=10)
    t = np.arange(0, 0.05, 1e-3)
    with pytest.raises(TypeError, match=r"PI\.step\(y_d, y, dt\) takes a measurement.*step_inputs"):
        ts.bench.run(plant, PI(), t, 0.1 * t)
    PI.step_inputs = ("y_d", "y")
    assert np.all(np.isfinite(ts.bench.run(plant, PI(), t, 0.1 * t).command))


# -- 2. missing measurements ------------------------------------------------------------------


def _measured_models():
    out = []
    for name in ts.models.__all__:
        cls = getattr(ts.models, name)
        if not (inspect.isclass(cls) and issubclass(cls, ts.models.HysteresisModel)):
            continue
        if cls is ts.models.HysteresisModel:  # the abstract base
            continue
        model = None
        for args in ((), (ts.models.Backlash(),)):  # a wrapper: around a Backlash
            try:
                model = cls(*args)
                break
            except (TypeError, ValueError):
                continue
        if model is None:
            continue
        inputs = tuple(getattr(model, "control_inputs", ("x",)))
        if len(inputs) > 1:
            out.append(pytest.param(model, inputs[1], id=name))
    return out


def test_the_walk_finds_the_models_that_need_a_measurement():
    assert {"Loaded", "CurveAngleModel"} <= {p.id for p in _measured_models()}


@pytest.mark.parametrize(("model", "measured"), _measured_models())
def test_a_model_without_its_measurement_refuses_instead_of_assuming_zero(model, measured):
    """Loaded.simulate without a load computed for load 0; CurveAngleModel.step for angle 0."""
    t, x = np.arange(5) * 1e-3, np.linspace(0.0, 0.5, 5)
    with pytest.raises(ValueError, match=measured.replace("_", ".")) as err:
        model.simulate(t, x)
    assert "\n" not in str(err.value)
    model.reset()
    with pytest.raises(ValueError, match=measured.replace("_", ".")):
        model.step(0.1, 1e-3)
    model.reset()
    given = model.step(0.1, 1e-3, **{measured: 0.5})  # given once, it is kept
    assert np.isfinite(given)


def test_compensators_that_take_a_measurement_need_it():
    loaded = ts.models.Loaded(ts.models.Backlash(), gain=0.1, slack=0.01)
    with pytest.raises(TypeError, match="load"):
        ts.compensate.LoadCompensated(loaded).step(0.1, 1e-3)  # type: ignore[call-arg]
    ff = ts.compensate.InverseFeedforward(ts.models.CurveAngleModel())
    with pytest.raises(ValueError, match="follows the route"):
        ff.step(0.1, 1e-3)
    assert np.isfinite(ff.step(0.1, 1e-3, curve_angle=1.0))
    assert np.isfinite(ff.step(0.2, 1e-3))  # the angle is kept


# -- 3. identifiability -----------------------------------------------------------------------


def _loaded_logs(loads):
    truth = ts.models.Loaded(ts.models.Backlash(), gain=-1.5, slack=0.02, friction=0.01)
    t = np.linspace(0, 5, 400)
    logs = []
    for k, level in enumerate(loads):
        x = (1 + 0.2 * k) * np.sin(2 * np.pi * 0.4 * t)
        load = np.full_like(t, level)
        logs.append(ts.io.Log(t, x, np.asarray(truth.simulate(t, x, load=load)), load=load))
    return logs


def test_a_constant_load_is_refused_naming_the_load_terms():
    """A gain of -0.16 (true -1.5) with an error of 4.5e-5 before."""
    logs = _loaded_logs([0.7, 0.7])
    with pytest.raises(ValueError, match=r"load is constant \(0\.7\).*gain, slack"):
        ts.identify(ts.models.Loaded(ts.models.Backlash), recordings=logs, progress=False)
    with pytest.raises(ValueError, match="load is constant"):
        ts.Identifier(ts.models.Loaded(ts.models.Backlash), progress=False).fit(logs)


def test_two_joints_on_one_signal_are_refused_naming_the_couplings():
    """Couplings of 0.79 and 0.25 for 0 and 0.25 with errors of 0.0016 before."""
    t = np.linspace(0, 5, 500)
    s = np.sin(2 * np.pi * 0.5 * t)
    x = np.column_stack([s, 2.0 * s + 0.1])  # the same signal, scaled and offset
    with pytest.raises(ValueError, match=r"same signal.*C\[0,1\], C\[1,0\]"):
        ts.identify_coupled(ts.models.Backlash, t, x, x + 0.01)


@pytest.mark.parametrize(
    "call",
    [
        pytest.param(lambda t, x: ts.identify(ts.models.Backlash, t, x, x.copy()), id="identify"),
        pytest.param(
            lambda t, x: ts.Identifier(ts.models.Backlash).fit([(t, x, x.copy())]),
            id="Identifier.fit",
        ),  # fmt: skip
        pytest.param(lambda t, x: ts.compare_models([(t, x, x.copy())]), id="compare_models"),
        pytest.param(
            lambda t, x: ts.identify(
                ts.models.Loaded(ts.models.Backlash), t, x, x.copy(), load=np.linspace(0, 1, x.size)
            ),
            id="identify(Loaded)",
        ),  # fmt: skip
        pytest.param(lambda t, x: identify_servo(t, x, x.copy()), id="identify_servo"),  # fmt: skip
    ],
)
def test_an_output_equal_to_the_input_is_refused(call):
    """The same column read as input and output fitted the identity."""
    t = np.arange(400) * 1e-3
    x = np.sin(2 * np.pi * 3 * t) + 0.1 * np.sin(2 * np.pi * 40 * t)
    with pytest.raises(ValueError, match=r"sample for sample") as err:
        call(t, x)
    assert "\n" not in str(err.value)


def test_read_log_refuses_one_column_for_two_roles(tmp_path):
    path = ts.io.write_csv(tmp_path / "a.csv", {"t": np.arange(5.0), "x": np.arange(5.0) ** 2})
    with pytest.raises(ValueError, match="'x' is named as both the input and the output"):
        ts.io.read_log(path, time="t", input="x", output="x")
    with pytest.raises(ValueError, match="both the time and the input"):
        ts.io.read_log(path, time="t", input="t", output="x")


def test_undetermined_standard_errors_are_inf_never_zero():
    """A zero column and an exactly collinear pair (a constant regressor beside an offset):
    inf; a determined parameter beside them keeps its finite error."""
    rng = np.random.default_rng(0)
    n = 200
    good = rng.normal(size=n)
    J = np.column_stack([good, np.ones(n), 0.7 * np.ones(n), np.zeros(n)])
    se = linearised_se(J, 1.0, n)
    assert np.isfinite(se[0]) and se[0] > 0
    assert np.all(np.isposinf(se[1:]))
    r = rng.normal(size=n)
    nw, _, _ = newey_west(J[:, :3], r, 2, lags=2)
    assert np.all(np.isposinf(nw))
