"""One validation for every entry point (issue 27, step 17 item 1).

A value gets the same rule, and the same one-line message, whether it comes from the Python API,
a saved JSON file (``to_dict`` with the field replaced, then ``from_dict``) or a scenario TOML
(``tendonsheath bench FILE.toml``). The table is built by walking the public constructors'
numeric fields (the plants' and motors' signatures, every model's ``param_names`` and
``option_names``, every saved compensator's numeric settings), not written by hand; each field
gets nan, +-inf, a negative number and zero through each entry point that reaches it.

Two invariants hold for every field: nan is refused by a ValueError naming the field (nowhere is
nan a setting), and every entry point agrees with the Python constructor: it refuses the same
values with the Python message (a file's or a scenario's prefix added), and takes the others.
The silent cases of the issue each have their own test below.

The walk reaches every class ``ts.compensate.load`` reads (EncoderLoop, TipLoop,
LearnedFeedforward, LoadCompensated and CoupledFeedforward among them), the composite models
(Scaled's map, Loaded's terms, AngleDependent's angle_friction, a Chain's parts, a Coupled
coupling), and every keyword of the motors and the sensor with its own bound. The C++ loader's
rows are in test_entry_point_validation_cpp.py.
"""

from __future__ import annotations

import inspect
import math
import warnings

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath.bench import user_scenario
from tendonsheath.compensate.persistence import compensator_from_dict
from tendonsheath.models import HysteresisModel

BAD = (math.nan, math.inf, -math.inf, -1.0, 0.0)
BAD_INT = (0, -1, 1)


def _outcome(build):
    """(error type, message) of build(), or None when it builds (warnings silenced: a unit
    warning is not a refusal)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            build()
    except (ValueError, TypeError) as exc:
        return type(exc), str(exc)
    return None


def _body(message: str) -> str:
    """A message without its "Where: " prefix (the class, a file or a scenario's table)."""
    return message.split(": ", 1)[1] if ": " in message else message


def _agrees(python, other) -> bool:
    """Another entry point gives the Python outcome: both take the value, or both refuse it
    with a ValueError whose message ends with the Python message's body."""
    if python is None or other is None:
        return python is other
    both = python[0] is ValueError and issubclass(other[0], ValueError)
    return both and other[1].endswith(_body(python[1]))


def _is_number(value) -> bool:
    return isinstance(value, float | int) and not isinstance(value, bool)


# -- the walk -------------------------------------------------------------------------------------
ROUTE = ts.Route.uniform(1.0, math.pi)
PLANTS = (ts.PullPullPlant, ts.SingleTendonPlant, ts.ContinuumPlant)
# keywords that are numbers but given as None by default (an effect left off)
EFFECTS = {
    "max_increment",
    "distal_inertia",
    "distal_damping",
    "sheath_viscosity",
    "relaxation_fraction",
    "relaxation_time",
    "friction2",
    "stiffness2",
}


def _numeric_keywords(fn) -> list[str]:
    """The keywords of fn whose default is a number, or None for a numeric effect."""
    params = inspect.signature(fn).parameters.values()
    return [
        p.name for p in params if _is_number(p.default) or (p.default is None and p.name in EFFECTS)
    ]


def _plant_rows():
    return [
        (cls, name, bad)
        for cls in PLANTS
        for name in _numeric_keywords(cls.__init__)
        for bad in (BAD_INT if name == "elements" else BAD)
    ]


def _sample_model(cls):
    try:
        return cls()
    except (TypeError, ValueError):  # a composite (Chain, Scaled, ...): built from its parts
        return None


def _model_rows():
    rows = []
    for name in ts.models.__all__:
        cls = getattr(ts.models, name)
        if not (isinstance(cls, type) and issubclass(cls, HysteresisModel)):
            continue
        if cls is HysteresisModel or cls.__name__.endswith("Inverse"):
            continue  # the base class; an inverse is built from its model
        model = _sample_model(cls)
        if model is None:
            continue
        saved = model.to_dict()
        for section in ("params", "options"):
            for field, value in saved.get(section, {}).items():
                if _is_number(value):
                    bads = BAD_INT if isinstance(value, int) else BAD
                    rows += [(cls, section, field, bad) for bad in bads]
    return rows


def _compensators():
    """One of each saved compensator with numeric settings, and its constructor's keywords:
    every class ts.compensate.load reads (test_the_walk_covers_every_saved_compensator)."""
    model = ts.models.BoucWenBacklash()
    sheath = {"friction": 0.1, "stiffness": 2e4, "length": 1.0, "pretension": 10.0}
    inverse = ts.compensate.InverseFeedforward(ts.models.Backlash(B_r=0.05, B_l=0.04))
    loaded = ts.models.Loaded(ts.models.Backlash(), gain=0.1, slack=0.01, slack_load=0.2)
    coupled = ts.models.Coupled([ts.models.Backlash(), ts.models.Backlash()], [[0, 0.1], [0.1, 0]])
    return [
        (ts.compensate.CurveAngleFeedforward, sheath),
        (ts.compensate.ContinuumFeedforward, {}),
        (ts.compensate.InverseFeedforward, {"model": model}),
        (ts.compensate.AdaptiveController, {}),
        (ts.compensate.EncoderLoop, {"feedforward": inverse, "max_correction": 0.5}),
        (ts.compensate.TipLoop, {"feedforward": inverse, "max_correction": 0.5}),
        (
            ts.compensate.LearnedFeedforward,
            {"feedforward": inverse, "table": [0.0, 0.1], "table_dt": 0.01},
        ),
        (ts.compensate.LoadCompensated, {"model": loaded, "filter_hz": 30.0}),
        (ts.compensate.CoupledFeedforward, {"model": coupled, "filter_hz": 30.0}),
        # a feedforward whose constructor is its table (compensate/from_table.py) needs nothing
        *(
            (cls, {})
            for cls in (getattr(ts.compensate, n) for n in ts.compensate.__all__)
            if getattr(getattr(cls, "__init__", None), "from_table", False)
        ),
    ]


def _takes(cls, field: str) -> bool:
    """Whether cls's constructor takes field: a keyword of its own, or of the inverse its
    **settings go to (LoadCompensated, CoupledFeedforward)."""
    params = inspect.signature(cls.__init__).parameters
    forwards = any(p.kind is inspect.Parameter.VAR_KEYWORD for p in params.values())
    inverse = inspect.signature(ts.compensate.InverseFeedforward.__init__).parameters
    return field in params or (forwards and field in inverse)


def _compensator_rows():
    rows = []
    for cls, kwargs in _compensators():
        saved = cls(**kwargs).to_dict()
        for field, value in saved.items():
            if field in ("format", "version", "compensator") or not _is_number(value):
                continue
            if _takes(cls, field):
                rows += [(cls, kwargs, field, bad) for bad in BAD]
    return rows


# -- the composite models: built around other models, their own numbers in a section of the file
COEFFICIENTS = {"c_r": 1.0, "c_l": 1.0, "B_r": [0.05, 0.01], "B_l": 0.05}
COMPOSITES = {
    "Scaled": (lambda **kw: ts.models.Scaled(ts.models.Backlash(), **kw), "map"),
    "Loaded": (lambda **kw: ts.models.Loaded(ts.models.Backlash(), **kw), "terms"),
    "AngleDependent": (
        lambda **kw: ts.models.AngleDependent(
            "Backlash", COEFFICIENTS, laws={"B_r": "tanh"}, **{"angle_friction": 0.2, **kw}
        ),
        "params",
    ),
}
# composites whose numbers are not keywords: their parts' (Chain) or a matrix (Coupled), each
# with its own test below
OTHER_COMPOSITES = {"Chain", "Coupled"}


def _composite_rows():
    rows = []
    for name, (build, section) in COMPOSITES.items():
        for field, value in build().to_dict()[section].items():
            if _is_number(value):
                rows += [(name, field, bad) for bad in BAD]
    return rows


PLANT_ROWS = _plant_rows()
MODEL_ROWS = _model_rows()
COMPENSATOR_ROWS = _compensator_rows()
COMPOSITE_ROWS = _composite_rows()


def test_the_walk_covers_every_public_numeric_field():
    """The table is not empty where it should not be: every plant's physical keyword, every
    model with a default, the compensators; and every numeric TOML key of [plant] is a plant
    keyword (so the scenario path of each is walked)."""
    walked = {(cls.__name__, name) for cls, name, _ in PLANT_ROWS}
    for name in ("friction", "stiffness", "pretension", "proximal_radius", "elements"):
        assert ("PullPullPlant", name) in walked
    assert ("ContinuumPlant", "backbone_length") in walked
    assert len({(cls, field) for cls, _, field, _ in MODEL_ROWS}) >= 40
    assert {cls for cls, *_ in COMPENSATOR_ROWS} == {c for c, _ in _compensators()}
    toml_numbers = [k for k, kind in user_scenario._KEYS["plant"].items() if kind in (int, float)]
    plant_keywords = {name for _, name, _ in PLANT_ROWS}
    assert set(toml_numbers) <= plant_keywords


def test_the_walk_covers_every_saved_compensator_and_composite_model():
    """Every class ts.compensate.load reads is walked, and every model class that cannot be
    built without parts (a composite) has rows here."""
    from tendonsheath.compensate.persistence import _KINDS

    assert {cls.__name__ for cls, _ in _compensators()} == set(_KINDS)
    walked = {(cls.__name__, field) for cls, _, field, _ in COMPENSATOR_ROWS}
    for name in ("EncoderLoop", "TipLoop"):
        assert {(name, k) for k in ("kp", "ki", "kd", "max_correction")} <= walked
    assert {("LoadCompensated", "switch"), ("CoupledFeedforward", "filter_hz")} <= walked
    assert ("LearnedFeedforward", "table_dt") in walked
    needs_parts = {
        name
        for name in ts.models.__all__
        if isinstance(getattr(ts.models, name), type)
        and issubclass(getattr(ts.models, name), HysteresisModel)
        and not name.endswith("Inverse")
        and getattr(ts.models, name) not in (HysteresisModel, ts.models.LinearBlock)  # bases
        and _sample_model(getattr(ts.models, name)) is None
    }
    # Polynomial needs a degree, not parts (its numbers are a list); Coupled is no
    # HysteresisModel (J joints), walked all the same
    assert needs_parts - {"Polynomial"} == set(COMPOSITES) | {"Chain"}
    assert {name for name, *_ in COMPOSITE_ROWS} == set(COMPOSITES)


def _plant_kwargs(cls, name, bad):
    kwargs = {"route": ROUTE, "elements": 10, name: bad}
    return kwargs


@pytest.mark.parametrize("cls, name, bad", PLANT_ROWS, ids=str)
def test_plant_fields_python_and_toml(cls, name, bad):
    python = _outcome(lambda: cls(**_plant_kwargs(cls, name, bad)))
    if isinstance(bad, float) and math.isnan(bad):
        assert python is not None and python[0] is ValueError and name in python[1]
    if python is not None:
        assert "\n" not in python[1] and name in python[1]
    toml_type = {ts.PullPullPlant: "pull_pull", ts.ContinuumPlant: "continuum"}.get(cls)
    if toml_type is None or name not in user_scenario._KEYS["plant"]:
        return
    literal = {math.inf: "inf", -math.inf: "-inf"}.get(bad, "nan" if bad != bad else repr(bad))
    text = (
        f'[plant]\ntype = "{toml_type}"\nrealistic = false\nelements = 10\n{name} = {literal}\n'
        if name != "elements"
        else f'[plant]\ntype = "{toml_type}"\nrealistic = false\nelements = {bad}\n'
    )
    toml = _outcome(lambda: user_scenario.parse(text, "s.toml"))
    if isinstance(bad, float) and not math.isfinite(bad):  # TOML's own guard, naming the key
        assert toml is not None and f"'{name}' must be a finite number" in toml[1]
    else:
        assert _agrees(python, toml), (python, toml)


@pytest.mark.parametrize("cls, section, field, bad", MODEL_ROWS, ids=str)
def test_model_fields_python_and_json(cls, section, field, bad):
    python = _outcome(lambda: cls(**{field: bad}))
    if isinstance(bad, float) and math.isnan(bad):
        assert python is not None and python[0] is ValueError and field in python[1]
    saved = cls().to_dict()
    saved[section][field] = bad
    json_file = _outcome(lambda: HysteresisModel.from_dict(saved))
    assert _agrees(python, json_file), (python, json_file)


@pytest.mark.parametrize("cls, kwargs, field, bad", COMPENSATOR_ROWS, ids=str)
def test_compensator_fields_python_and_json(cls, kwargs, field, bad):
    python = _outcome(lambda: cls(**{**kwargs, field: bad}))
    if isinstance(bad, float) and math.isnan(bad):
        assert python is not None and python[0] is ValueError and field in python[1]
    saved = cls(**kwargs).to_dict()
    saved[field] = bad
    json_file = _outcome(lambda: compensator_from_dict(saved))
    assert _agrees(python, json_file), (python, json_file)


@pytest.mark.parametrize("name, field, bad", COMPOSITE_ROWS, ids=str)
def test_composite_model_fields_python_and_json(name, field, bad):
    """Scaled's map, Loaded's terms and AngleDependent's angle_friction: the constructor and the
    saved file (the section holding them) agree; nan names the field."""
    build, section = COMPOSITES[name]
    python = _outcome(lambda: build(**{field: bad}))
    if isinstance(bad, float) and not math.isfinite(bad):  # no setting is nan or infinite here
        assert python is not None and python[0] is ValueError and field in python[1], python
    saved = build().to_dict()
    saved[section][field] = bad
    json_file = _outcome(lambda: HysteresisModel.from_dict(saved))
    assert _agrees(python, json_file), (python, json_file)


CHAIN_PARTS = (ts.models.Backlash(B_r=0.05, B_l=0.04), ts.models.FirstOrderLag(time_constant=0.01))


@pytest.mark.parametrize(
    "part, field, bad",
    [
        (i, field, bad)
        for i, model in enumerate(CHAIN_PARTS)
        for field in model.param_names
        for bad in BAD
    ],
    ids=str,
)
def test_a_chain_parts_fields_python_and_json(part, field, bad):
    """A part's number inside a saved Chain gets the part's own rule and message."""
    parts = list(CHAIN_PARTS)
    python = _outcome(
        lambda: ts.models.Chain(
            *[p.with_params(**{field: bad}) if i == part else p for i, p in enumerate(parts)]
        )
    )
    saved = ts.models.Chain(*parts).to_dict()
    saved[("first", "second")[part]]["params"][field] = bad
    json_file = _outcome(lambda: HysteresisModel.from_dict(saved))
    assert _agrees(python, json_file), (python, json_file)
    if isinstance(bad, float) and math.isnan(bad):
        assert python is not None and field in python[1]


@pytest.mark.parametrize("where", ["off_diagonal", "diagonal"])
@pytest.mark.parametrize("bad", BAD)
def test_coupled_coupling_entries_python_and_json(where, bad):
    """A coupling entry: not finite (named by its index), on the diagonal, or making I - C
    singular (-1 off the diagonal of two joints) is refused by the constructor and the file
    alike, with the C++ CoupledFeedforward's message."""
    c = [[0.0, bad], [bad, 0.0]] if where == "off_diagonal" else [[bad, 0.1], [0.1, 0.0]]
    joints = [ts.models.Backlash(), ts.models.Backlash()]
    python = _outcome(lambda: ts.models.Coupled(joints, c))
    saved = ts.models.Coupled(joints, [[0.0, 0.1], [0.1, 0.0]]).to_dict()
    saved["coupling"] = c
    json_file = _outcome(lambda: ts.models.Coupled.from_dict(saved))
    assert _agrees(python, json_file), (python, json_file)
    if not math.isfinite(bad):
        assert "coupling[0][" in python[1] and f"must be finite (got {bad:g})" in python[1]
    elif where == "diagonal" and bad != 0:
        assert python[1].endswith("got coupling[0][0] = -1)")
    elif bad == -1.0:
        assert "I - coupling is singular" in python[1]
    else:
        assert python is None


# each table's defaults in a scenario (user_scenario.parse), so both paths see the same values
MOTOR_TABLES = (
    ("motor", ts.Motor.position, {"bandwidth_hz": 60.0, "damping": 0.8}),
    ("torque_motor", ts.Motor.torque, {"inertia": 0.01, "viscous": 0.2, "max_torque": 5.0}),
    ("sensor", ts.Sensor, {"noise_std": 2e-4, "resolution": 1e-4, "seed": 1}),
)


# each key's own bound, past it: a history beyond the sensor's buffer, a negative seed
INTEGER_BAD = {"seed": (-1, 0), "history": (0, -1, 2**24 + 1)}


def _toml_literal(bad) -> str:
    return {math.inf: "inf", -math.inf: "-inf"}.get(bad, "nan" if bad != bad else repr(bad))


@pytest.mark.parametrize(
    "table, build, base, key, bad",
    [
        (table, build, base, key, bad)
        for table, build, base in MOTOR_TABLES
        for key, kind in user_scenario._KEYS[table].items()
        for bad in (BAD if kind is float else INTEGER_BAD[key])
    ],
    ids=str,
)
def test_motor_and_sensor_tables_give_the_python_message(table, build, base, key, bad):
    """[motor], [torque_motor] and [sensor] of a scenario refuse what the Python constructors
    refuse, with their message, at parse time (before any run); nan and +-inf, which the
    constructors refuse naming the field (or take as "unlimited": max_speed = inf), TOML
    refuses naming the key (omit a limit to leave it off)."""
    python = _outcome(lambda: build(**{**base, key: bad}))
    text = f"[plant]\nrealistic = false\n[{table}]\n{key} = {_toml_literal(bad)}\n"
    toml = _outcome(lambda: user_scenario.parse(text, "s.toml"))
    if isinstance(bad, float) and not math.isfinite(bad):
        assert toml is not None and f"'{key}' must be a finite number" in toml[1], toml
        if python is not None or math.isnan(bad):
            assert python is not None and f"{key} must be" in python[1], python
    elif python is None:
        assert toml is None, toml
    else:
        assert toml is not None and toml[1].endswith(_body(python[1])), (python, toml)


def _motor_and_sensor_rows():
    """Every numeric keyword of the motors and the sensor, with the generic bad values and
    each one's own bound."""
    rows = []
    for build in (ts.Motor.position, ts.Motor.torque, ts.Sensor):
        for name in _numeric_keywords(build):
            bads = INTEGER_BAD.get(name, BAD)
            rows += [(build, name, bad) for bad in bads]
    return rows


@pytest.mark.parametrize("build, name, bad", _motor_and_sensor_rows(), ids=str)
def test_motor_and_sensor_keywords_refuse_nan_and_their_bounds(build, name, bad):
    """nan is refused naming the keyword; a refusal is one line naming it; a keyword the
    scenario reads gives the same outcome there (test above)."""
    python = _outcome(lambda: build(**{name: bad}))
    if isinstance(bad, float) and math.isnan(bad):
        assert python is not None and python[0] is ValueError
    if python is not None:
        assert "\n" not in python[1] and name in python[1], python
    if name in INTEGER_BAD and bad in (-1, 2**24 + 1):
        assert python is not None  # past the bound


@pytest.mark.parametrize(
    "text, python, needle",
    [
        (  # the loop runs at the reference rate: it must sample the servo
            "[motor]\nbandwidth_hz = 600.0\n",
            None,
            r"'rate' 1000 Hz is below twice the servo's bandwidth .*bandwidth_hz = 600 Hz",
        ),
        (  # the realistic preset's PID servo is stable only above damping 0.1
            "[plant]\nrealistic = true\n[motor]\ndamping = 0.05\n",
            lambda: ts.presets.realistic_motor(damping=0.05),
            r"stable only for damping > 0\.1 \(got 0\.05\)",
        ),
        (  # the PID's integral time below 1 / (2 damping w): an unstable loop
            None,
            lambda: ts.Motor.position(bandwidth_hz=10.0, integral_time=1e-4),
            "integral_time",
        ),
    ],
)
def test_motor_bounds_that_depend_on_another_value(text, python, needle):
    """A bound set by another key: refused at parse time (or by the constructor), naming both."""
    if python is not None:
        with pytest.raises(ValueError, match=needle):
            python()
    if text is not None:
        text = text if text.startswith("[plant]") else "[plant]\nrealistic = false\n" + text
        with pytest.raises(user_scenario.ScenarioError, match=needle):
            user_scenario.parse(text, "s.toml")


# -- the silent cases of the issue, each with its class ------------------------------------------
def test_a_pretension_that_would_break_the_tendon_is_refused_everywhere():
    """T0 / EA = 4 ran with output 0 and success; now every plant (and the scenario, through
    the same C++ rule) says T0 / EA must be < 0.05, with the values."""
    for cls in (ts.PullPullPlant, ts.ContinuumPlant):
        with pytest.raises(ValueError, match=r"pretension / EA must be < 0\.05 \(got 20 N / 5 N"):
            cls(ROUTE, stiffness=5, pretension=20, elements=10)
    with pytest.raises(ValueError, match="pretension / EA must be < 0.05"):
        ts.PullPullPlant(ROUTE, stiffness=2e4, stiffness2=100, pretension=10, elements=10)
    with pytest.raises(ValueError, match="load_force / EA must be < 0.05"):
        ts.SingleTendonPlant(ROUTE, stiffness=100, load=ts.loads.ConstantForce(10), elements=10)
    text = "[plant]\nstiffness = 5.0\npretension = 20.0\n"
    with pytest.raises(user_scenario.ScenarioError, match=r"\[plant\]: .*pretension / EA must"):
        user_scenario.parse(text, "s.toml")
    # the spec's ranges (T0 <= 40 N, EA >= 5e3 N: T0 / EA <= 8e-3) all build
    ts.PullPullPlant(ROUTE, stiffness=5e3, pretension=40.0, elements=10)


@pytest.mark.parametrize(
    "build",
    [
        lambda: ts.Route.uniform(1.5, 180),
        lambda: ts.Route.arcs([(0.5, 90), (1.0, 90)]),
        lambda: ts.Route([0.0, 1.0], [0.0, 360.0]),
        lambda: ts.compensate.CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=180),
    ],
)
def test_curve_angles_in_degrees_warn_naming_the_mistake(build):
    with pytest.warns(ts.UnitWarning, match=r"above 12\.57 rad .*did you give degrees\? "):
        build()


def test_plausible_curve_angles_do_not_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", ts.UnitWarning)
        ts.Route.uniform(1.2, 4 * math.pi)  # two full coils: the spec's largest
        ts.Route.arcs([(0.5, -math.pi), (0.5, math.pi)])
        ts.compensate.CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=2 * math.pi)


@pytest.mark.parametrize("angle", [-1.0, math.nan, math.inf])
def test_a_bad_curve_angle_is_refused_not_ignored(angle):
    """set_curve_angle(-1) and (nan) did nothing and said OK. The Python call (outside real
    time) raises; the C++ engine keeps the last angle and reports input_clamped."""
    ff = ts.compensate.CurveAngleFeedforward(0.1, 2e4, 1.0, 10.0, curve_angle=1.0)
    before = ff.step(0.3, 0.0)
    with pytest.raises(ValueError, match="curve_angle must be finite and >= 0"):
        ff.set_curve_angle(angle)
    with pytest.raises(ValueError, match="curve_angle must be finite and >= 0"):
        ff.step(0.3, 0.0, curve_angle=angle)
    inverse = ts.compensate.InverseFeedforward(ts.models.Backlash())
    with pytest.raises(ValueError, match="curve_angle must be finite and >= 0"):
        inverse.set_curve_angle(angle)
    core = ts._core.CurveAngleFeedforward  # the real-time methods: no exception
    assert core.set_curve_angle(ff, angle) is False
    assert ff.angle_rejected()
    assert ts.Status.INPUT_CLAMPED in ff.status()
    assert ff.shape.curve_angle == 1.0  # unchanged
    ff.reset()
    assert ff.step(0.3, 0.0) == before
    assert core.set_curve_angle(ff, 2.0) and ff.status() == ts.Status.OK


@pytest.mark.parametrize("version", [True, 1.0, "1"])
def test_a_file_version_must_be_the_integer(version):
    """JSON "version": true loaded (True == 1 in Python); 1.0 and "1" neither."""
    model = ts.models.Backlash().to_dict()
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash()).to_dict()
    for saved, load in ((model, HysteresisModel.from_dict), (ff, compensator_from_dict)):
        with pytest.raises(ValueError, match="version"):
            load({**saved, "version": version})


SCENARIO = "[plant]\nrealistic = false\nelements = 10\n[reference]\nduration = 10.0\n"


@pytest.mark.parametrize(
    "extra, needle",
    [
        ("[[route.changes]]\nt = 12.0\ntotal_angle = 1.0\n", "outside the run"),
        ("[[route.changes]]\nt = -1.0\ntotal_angle = 1.0\n", "outside the run"),
        ("[calibration]\nangles = [-1.0, 2.0]\n", "curve_angle must be >= 0"),
        ("[calibration]\nangles = []\n", "must list at least one curve angle"),
        (
            "[calibration]\nshape_noise = -1.0\n",
            r"'shape_noise' \(ShapeSensing noise_std\) out of range",
        ),
        ("[calibration]\nduration = 0.0\n", "'duration' must be >= 3 s"),
        ("[reference]\nsines = [[1.0, -0.5, 0.0]]\n", "frequency >= 0"),
        ("[reference]\nsines = [[nan, 0.5, 0.0]]\n", "must be finite"),
        ("[sensor]\nhistory = 4294967296\n", r"'history' must be below 2\*\*31"),
        (
            '[load]\ntype = "constant_torque"\ntorque = 0.1\nstiffness = 2.0\n',
            r"a constant_torque load takes \['torque'\], not \['stiffness'\]",
        ),
    ],
)
def test_scenarios_that_cannot_run_as_written_are_refused(extra, needle):
    text = SCENARIO.replace("[reference]\nduration = 10.0\n", "") + extra
    if "[reference]" not in extra:
        text += "[reference]\nduration = 10.0\n"
    else:
        text = text.replace("[reference]\n", "[reference]\nduration = 10.0\n")
    with pytest.raises(user_scenario.ScenarioError, match=needle):
        user_scenario.parse(text, "s.toml")


def test_an_empty_scenario_is_refused_and_a_titled_one_runs_the_defaults():
    for text in ("", "# only a comment\n"):
        with pytest.raises(user_scenario.ScenarioError, match="empty"):
            user_scenario.parse(text, "s.toml")
    assert user_scenario.parse('title = "defaults"\n', "s.toml").title == "defaults"


def test_scenario_angles_in_degrees_warn_and_extrapolation_is_noted():
    sines = SCENARIO.replace("[reference]\n", "[reference]\nsines = [[45.0, 0.5, 0.0]]\n")
    with pytest.warns(ts.UnitWarning, match=r"sines\[0\] amplitude 45 rad .*45 deg = 0\.7854"):
        user_scenario.parse(sines, "s.toml")
    with pytest.warns(ts.UnitWarning, match=r"Route.uniform: curve_angle 180 rad .*degrees"):
        user_scenario.parse(SCENARIO + "[route]\ntotal_angle = 180.0\n", "s.toml")
    far = SCENARIO + "[calibration]\nangles = [10.0]\n"
    with pytest.warns(UserWarning, match=r"lie outside the calibration angles .*extrapolate"):
        user_scenario.parse(far, "s.toml")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        user_scenario.parse(SCENARIO + "[calibration]\nangles = [1.0, 5.0]\n", "s.toml")


def test_the_message_is_one_line_and_names_the_field():
    """Spot check of the table's message on a value each path refuses."""
    msgs = [
        _outcome(lambda: ts.PullPullPlant(ROUTE, friction=-1.0))[1],
        _outcome(lambda: user_scenario.parse("[plant]\nfriction = -1.0\n", "s.toml"))[1],
    ]
    assert all("\n" not in m and "friction must be >= 0 (got -1)" in m for m in msgs)
    assert np.isfinite(ROUTE.curve_angle)


@pytest.mark.parametrize(
    "kind, key, build",
    [
        ("constant_torque", "torque", lambda v: ts.loads.ConstantTorque(v)),
        ("torsional_spring", "stiffness", lambda v: ts.loads.TorsionalSpring(v)),
        ("torsional_spring", "preload", lambda v: ts.loads.TorsionalSpring(0.0, v)),
        ("spring_damper", "stiffness", lambda v: ts.loads.SpringDamper(v, 0.0)),
        ("spring_damper", "damping", lambda v: ts.loads.SpringDamper(0.0, v)),
    ],
)
@pytest.mark.parametrize("bad", [-1.0, 0.0])
def test_load_table_gives_the_load_class_message_with_its_key(kind, key, build, bad):
    """[load] refuses what the load class refuses, at parse time, in the table's words."""
    python = _outcome(lambda: build(bad))
    text = f'[plant]\nrealistic = false\n[load]\ntype = "{kind}"\n{key} = {bad!r}\n'
    toml = _outcome(lambda: user_scenario.parse(text, "s.toml"))
    if python is None:
        assert toml is None, toml
        return
    assert toml is not None and toml[1].startswith("s.toml [load]: ") and f"'{key}'" in toml[1]
    assert toml[1].endswith(_body(python[1]).split(" must ", 1)[1])


@pytest.mark.parametrize("key", ["length", "total_angle"])
@pytest.mark.parametrize("bad", [-1.0, 0.0])
def test_route_table_gives_the_route_message(key, bad):
    """[route] length and total_angle refuse what Route.uniform refuses, with its message."""
    args = {
        "length": 1.2,
        "curve_angle": math.pi,
        {"total_angle": "curve_angle"}.get(key, key): bad,
    }
    python = _outcome(lambda: ts.Route.uniform(**args))
    toml = _outcome(lambda: user_scenario.parse(f"[route]\n{key} = {bad!r}\n", "s.toml"))
    assert _agrees(python, toml), (python, toml)


def test_a_load_on_the_continuum_plant_is_refused_not_ignored():
    text = '[plant]\ntype = "continuum"\n[load]\ntype = "constant_torque"\ntorque = 0.1\n'
    with pytest.raises(user_scenario.ScenarioError, match="continuum plant takes no distal load"):
        user_scenario.parse(text, "s.toml")
    user_scenario.parse(text.split("[load]")[0], "s.toml")  # the same plant without it runs


def test_the_plant_element_count_beyond_a_c_int_is_one_line():
    with pytest.raises(user_scenario.ScenarioError, match=r"\[plant\]: 'elements' must be below"):
        user_scenario.parse("[plant]\nelements = 4294967296\n", "s.toml")
