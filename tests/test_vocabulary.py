"""One vocabulary (docs/vocabulary.md): the public constructors speak the Python names (the
old names were removed; files saved with them still load), wrong types are TypeErrors naming
the argument, and models are hashable values."""

from __future__ import annotations

import ast
import inspect
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.compensate import (
    AdaptiveController,
    ContinuumFeedforward,
    CurveAngleFeedforward,
    InverseFeedforward,
)
from tendonsheath.compensate.adaptive_controller import _GAINS

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "tendonsheath"
ROUTE = ts.Route.uniform(1.0, np.pi)
# the C++ fields named otherwise before issue 26 (now the Python names): no message says them
CPP_ONLY = ("v_eps", "total_angle", "sheath_length", "reflected_inertia", "compliance")
CURVE_MODEL_CPP_ONLY = ("load", "spring")  # CurveAngleParams' old fields (CurveAngleModel's names)
SHEATH = {"friction": 0.1, "stiffness": 2e4, "length": 1.0, "pretension": 10.0}


def _models() -> dict[str, tuple]:
    """Every model class that builds from its defaults alone."""
    out = {}
    for name in ts.models.__all__:
        cls = getattr(ts.models, name)
        if isinstance(cls, type) and issubclass(cls, ts.models.HysteresisModel) and cls.param_names:
            try:
                cls()
            except (TypeError, ValueError):  # needs more (Chain, Scaled, Polynomial, ...)
                continue
            out[name] = (cls, {})
    return out


# every public constructor and what it needs besides the argument under test
CONSTRUCTORS = {
    "PullPullPlant": (ts.PullPullPlant, {"route": ROUTE}),
    "SingleTendonPlant": (ts.SingleTendonPlant, {"route": ROUTE}),
    "ContinuumPlant": (ts.ContinuumPlant, {}),
    "Motor.position": (ts.Motor.position, {}),
    "Motor.torque": (ts.Motor.torque, {}),
    "Sensor": (ts.Sensor, {}),
    "Route.uniform": (ts.Route.uniform, {"length": 1.0, "curve_angle": 1.0}),
    "InverseFeedforward": (InverseFeedforward, {"model": ts.models.Backlash()}),
    "CurveAngleFeedforward": (CurveAngleFeedforward, dict(SHEATH)),
    "ContinuumFeedforward": (ContinuumFeedforward, {}),
    "AdaptiveController": (AdaptiveController, {"feedforward_model": ts.models.Backlash()}),
    "AdaptiveController.from_model": (
        AdaptiveController.from_model,
        {"model": ts.models.Backlash(), "inertia": 1e-3},
    ),
    "ConstantTorque": (ts.loads.ConstantTorque, {"tau": 0.1}),
    "TorsionalSpring": (ts.loads.TorsionalSpring, {"k": 0.1}),
    "SpringDamper": (ts.loads.SpringDamper, {"k": 0.1, "c": 0.01}),
    "ConstantForce": (ts.loads.ConstantForce, {"F": 1.0}),
    "LinearSpring": (ts.loads.LinearSpring, {"k": 10.0}),
    "SpringPreload": (ts.loads.SpringPreload, {"k": 10.0, "F0": 1.0}),
    **_models(),
    "Polynomial": (ts.models.Polynomial, {"degree": 3}),
    "Scaled": (ts.models.Scaled, {"inner": ts.models.Backlash()}),
    "AngleDependent": (
        ts.models.AngleDependent,
        {
            "base": "Backlash",
            "coefficients": {"c_r": [1.0], "c_l": [1.0], "B_r": [0.0, 0.2], "B_l": [0.1]},
            "laws": {"B_r": "tanh"},
            "angle_friction": 0.2,
        },
    ),
}  # Chain takes two models and no number


def _is_number(value) -> bool:
    return isinstance(value, int | float) and not isinstance(value, bool)


def numeric_arguments(make, base: dict) -> list[str]:
    """The arguments of `make` that take a number: numeric defaults, numbers in `base`, and the
    gains of AdaptiveController (keywords outside its signature)."""
    names = [
        p.name
        for p in inspect.signature(make).parameters.values()
        if _is_number(p.default) or _is_number(base.get(p.name))
    ]
    return names + (list(_GAINS[:5]) if make is AdaptiveController else [])


def _wrong_values(make) -> list:
    """A string, a list and None; not None for a model, where None means the parameter's default
    (docs/bad-inputs.md)."""
    is_model = isinstance(make, type) and issubclass(make, ts.models.HysteresisModel)
    return ["high", [1.0]] + ([] if is_model else [None])


TYPE_CASES = [
    pytest.param(name, arg, value, id=f"{name}-{arg}-{type(value).__name__}")
    for name, (make, base) in CONSTRUCTORS.items()
    for arg in numeric_arguments(make, base)
    for value in _wrong_values(make)
]


# models whose parameters are arrays (thresholds, weights), each with an array argument
ARRAY_MODELS = {
    "PrandtlIshlinskii": "thresholds",
    "PrandtlIshlinskiiInverse": "thresholds",
    "GeneralizedPrandtlIshlinskii": "weights",
    "GeneralizedPrandtlIshlinskiiInverse": "weights",
}


def test_every_constructor_has_arguments_under_test():
    """The parametrisations below cover each constructor (a signature change cannot empty it)."""
    covered = {p.values[0] for p in TYPE_CASES}
    assert covered == set(CONSTRUCTORS) - set(ARRAY_MODELS)
    assert set(ARRAY_MODELS) <= set(CONSTRUCTORS)
    assert len(TYPE_CASES) > 120


@pytest.mark.parametrize(("name", "arg"), ARRAY_MODELS.items())
def test_an_array_parameter_of_the_wrong_type_is_a_type_error(name, arg):
    make, base = CONSTRUCTORS[name]
    for value in ("high", ["a", "b"], {"x": 1.0}):
        with pytest.raises(TypeError, match=rf"\b{arg}\b"):
            make(**{**base, arg: value})


@pytest.mark.parametrize(("name", "arg", "value"), TYPE_CASES)
def test_a_wrong_type_is_a_type_error_naming_the_argument_and_the_type(name, arg, value):
    make, base = CONSTRUCTORS[name]
    with pytest.raises(TypeError) as info:
        make(**{**base, arg: value})
    message = str(info.value)
    assert re.search(rf"\b{arg}\b", message) and "\n" not in message, message
    if value is not None:  # None can also mean "missing", said so
        assert type(value).__name__ in message, message


# arguments that take an object or an array, each given a string
OBJECT_CASES = [
    ("Route", "s", lambda v: ts.Route(v, [0.0, 1.0])),
    ("Route", "theta", lambda v: ts.Route([0.0, 1.0], v)),
    ("Route.arcs", "pieces", lambda v: ts.Route.arcs(v)),
    ("Route.from_points", "xyz", lambda v: ts.Route.from_points(v)),
    ("Route.from_curvature", "kappa", lambda v: ts.Route.from_curvature([0.0, 1.0], v)),
    ("CommandLimits", "min", lambda v: ts.compensate.CommandLimits(min=v)),
    ("CommandLimits", "max_rate", lambda v: ts.compensate.CommandLimits(max_rate=v)),
    ("InverseFeedforward", "limits", lambda v: InverseFeedforward(ts.models.Backlash(), limits=v)),
    ("InverseFeedforward", "model", lambda v: InverseFeedforward(v)),
    ("AdaptiveController", "feedforward_model", lambda v: AdaptiveController(v)),
    ("Chain", "models", lambda v: ts.models.Chain(v, ts.models.Backlash())),
    ("Scaled", "inner", lambda v: ts.models.Scaled(v)),
    ("PullPullPlant", "route", lambda v: ts.PullPullPlant(v)),
    ("PullPullPlant", "route2", lambda v: ts.PullPullPlant(ROUTE, route2=v)),
    ("PullPullPlant", "load", lambda v: ts.PullPullPlant(ROUTE, load=v)),
    ("PullPullPlant", "motor", lambda v: ts.PullPullPlant(ROUTE, motor=v)),
    ("SingleTendonPlant", "sensor", lambda v: ts.SingleTendonPlant(ROUTE, sensor=v)),
    ("ContinuumFeedforward", "mode", lambda v: ContinuumFeedforward(mode=3.0)),
]


@pytest.mark.parametrize(
    ("who", "arg", "make"), OBJECT_CASES, ids=[c[0] + "-" + c[1] for c in OBJECT_CASES]
)
def test_an_object_or_array_of_the_wrong_type_is_a_type_error(who, arg, make):
    with pytest.raises(TypeError) as info:
        make("high")
    message = str(info.value)
    assert "\n" not in message and ("high" in message or "str" in message), message
    if arg != "models":  # Chain names its two parts together
        assert re.search(rf"\b{arg}\b", message), message


def test_the_issue_examples():
    with pytest.raises(ValueError, match=r"^InverseFeedforward: smoothing must be > 0 \(got 0\)$"):
        InverseFeedforward(ts.models.Backlash(), smoothing=0)
    with pytest.raises(
        ValueError, match=r"^CurveAngleFeedforward: curve_angle must be >= 0 \(got -1\)$"
    ):
        CurveAngleFeedforward(**SHEATH, curve_angle=-1)
    with pytest.raises(
        TypeError, match=r"^PullPullPlant: friction must be a number \(got str 'high'\)$"
    ):
        ts.PullPullPlant(ROUTE, friction="high")


# out-of-range values the C++ core refuses, and the Python argument each message must name
RANGE_CASES = [
    (lambda v: InverseFeedforward(ts.models.Backlash(), smoothing=-v), "smoothing"),
    (lambda v: InverseFeedforward(ts.models.BoucWenBacklash(), smoothing=-v), "smoothing"),
    (
        lambda v: InverseFeedforward(
            ts.models.Scaled(ts.models.Backlash(), output_gain=-2.0), smoothing=-v
        ),
        "smoothing",
    ),  # fmt: skip
    (lambda v: AdaptiveController(ts.models.Backlash(), smoothing=-v), "smoothing"),
    (lambda v: CurveAngleFeedforward(**SHEATH, curve_angle=-v), "curve_angle"),
    (lambda v: CurveAngleFeedforward(**SHEATH, curve_angle=600 + v), "curve_angle"),
    (lambda v: CurveAngleFeedforward(**SHEATH, smoothing=-v), "smoothing"),
    (lambda v: CurveAngleFeedforward(**{**SHEATH, "stiffness": -v}), "stiffness"),
    (lambda v: CurveAngleFeedforward(**{**SHEATH, "length": -v}), "length"),
    (lambda v: ContinuumFeedforward(curve_angle=-v), "curve_angle"),
    (lambda v: ContinuumFeedforward(curve_angle=600 + v), "curve_angle"),
    (lambda v: ContinuumFeedforward(length=-v), "length"),
    (lambda v: ContinuumFeedforward(smoothing=-v), "smoothing"),
    (lambda v: ts.Route.uniform(1.0, -v), "curve_angle"),
    (lambda v: ts.Motor.position(coulomb_friction=v), "inertia"),
    (lambda v: ts.PullPullPlant(ROUTE, friction=-v), "friction"),
    (lambda v: ts.Sensor(noise_std=-v), "noise_std"),
    (lambda v: ts.models.CurveAngleModel(load_stiffness=-v), "load_stiffness"),
]


@pytest.mark.parametrize(("make", "arg"), RANGE_CASES)
def test_a_value_out_of_range_names_the_python_argument_not_the_cpp_field(make, arg, rng):
    who = None
    for v in rng.uniform(0.01, 50.0, 5):
        with pytest.raises(ValueError) as info:
            make(float(v))
        message = str(info.value)
        assert re.search(rf"\b{re.escape(arg)}\b", message), message
        for cpp in CPP_ONLY + CURVE_MODEL_CPP_ONLY:
            assert not re.search(rf"\b{cpp}\b", message), message
        head = message.split(": ", 1)[0]
        assert who in (None, head) and "\n" not in message  # one prefix: the Python class
        who = head
    assert who.split(".")[0] in dir(ts) + dir(ts.compensate) + dir(ts.models) + ["Motor"]


# -- the old names are gone (0.x: removed, CHANGELOG); saved files with them still load ----

OLD_NAMES = [
    (lambda: ts.Route.uniform(1.0, total_angle=1.0), "total_angle"),
    (lambda: ContinuumFeedforward(friction=0.1, total_angle=1.0), "total_angle"),
    (lambda: ContinuumFeedforward(friction=0.1, sheath_length=1.0), "sheath_length"),
    (
        lambda: ContinuumFeedforward.from_model(
            ts.models.CurveAngleModel(load_stiffness=300.0), 2e-3, 0.03, 1.0, total_angle=1.0
        ),
        "total_angle",
    ),
    (lambda: CurveAngleFeedforward(0.1, compliance=1e-4, pretension=10.0), "compliance"),
    (lambda: CurveAngleFeedforward(**SHEATH).set_curve_angle(total_angle=1.0), "total_angle"),
    (lambda: ts.models.BoucWen(a=0.3), "a"),
    (lambda: ts.models.BoucWen().with_params(a=0.3), "a"),
    (lambda: ts.models.CurveAngleModel(load=1.0), "load"),
    (lambda: ts.models.CurveAngleModel(spring=1.0), "spring"),
    (lambda: ts.models.CurveAngleModel().with_params(load=1.0), "load"),
    (lambda: ts.physics.capstan_ratio(0.1, total_angle=1.0), "total_angle"),
]


@pytest.mark.parametrize(("make", "old"), OLD_NAMES, ids=[o for _, o in OLD_NAMES])
def test_an_old_name_is_a_type_error_naming_it(make, old):
    # Python's own words, or a table-built model's (which lists the names it takes)
    with pytest.raises(
        TypeError,
        match=rf"unexpected keyword argument '{old}'|unknown parameter\(s\) \['{old}'\]",
    ):
        make()


def test_a_route_has_no_old_total_angle():
    assert not hasattr(ROUTE, "total_angle") and ROUTE.curve_angle == pytest.approx(np.pi)


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (lambda: CurveAngleFeedforward(0.1, 2e4), "missing 2 .* 'length' and 'pretension'"),
        (lambda: CurveAngleFeedforward(0.1, 5e-5, 10.0), "missing 1 .* 'pretension'"),
        (lambda: ts.Route.uniform(1.0, angle=1.0), "unexpected keyword argument 'angle'"),
        (lambda: ContinuumFeedforward(spring=1.0), "unexpected keyword argument 'spring'"),
        (lambda: ts.models.BoucWen(b=1.0), r"unknown parameter\(s\) \['b'\]"),
        (lambda: ts.models.CurveAngleModel(springs=1.0), r"unknown parameter\(s\) \['springs'\]"),
    ],
)
def test_missing_or_unknown_keywords_are_type_errors(make, message):
    with pytest.raises(TypeError, match=message):
        make()


def test_files_saved_with_the_old_names_still_load_without_a_warning(recwarn):
    new = ContinuumFeedforward(length=0.8, curve_angle=2.0)
    data = new.to_dict()
    assert "curve_angle" in data and "total_angle" not in data
    data["sheath_length"], data["total_angle"] = data.pop("length"), data.pop("curve_angle")
    assert ts.compensate.load(data).params == new.params
    curve = CurveAngleFeedforward(0.1, 1e4, 1.0, 10.0)
    old = curve.to_dict()
    del old["stiffness"], old["length"]
    old["compliance"] = 1e-4
    np.testing.assert_allclose(
        ts.compensate.load(old).command(np.arange(50) * 0.01, np.sin(np.arange(50) * 0.1)),
        curve.command(np.arange(50) * 0.01, np.sin(np.arange(50) * 0.1)),
        rtol=1e-12,
    )
    assert not [w for w in recwarn if issubclass(w.category, DeprecationWarning)]


def test_model_files_saved_with_the_old_load_names_still_load_without_a_warning(recwarn, rng):
    for _ in range(5):
        new = ts.models.CurveAngleModel(
            friction=rng.uniform(0.05, 0.3),
            load_force=rng.uniform(-5.0, 5.0),
            load_stiffness=10 ** rng.uniform(1.0, 4.0),
        )
        data = new.to_dict()
        assert {"load_force", "load_stiffness"} <= set(data["params"])
        assert not {"load", "spring"} & set(data["params"])
        params = data["params"]
        params["load"], params["spring"] = params.pop("load_force"), params.pop("load_stiffness")
        old = ts.models.load_model(json.dumps(data))
        assert old == new and old.params == new.params
    assert not [w for w in recwarn if issubclass(w.category, DeprecationWarning)]


def test_a_model_file_with_a_load_under_both_names_is_a_bad_file():
    data = ts.models.CurveAngleModel(load_force=1.0).to_dict()
    data["params"]["load"] = 2.0
    with pytest.raises(ValueError, match="CurveAngleModel file: give load_force or its old name"):
        ts.models.load_model(data)


# -- identify's fixed, free and bounds take the parameters' names only --------------------


def _curve_recordings():
    truth = ts.models.CurveAngleModel(friction=0.15, stiffness=2e3, load_force=1.5)
    t = np.linspace(0.0, 4.0, 401)
    x = 0.3 * np.sin(2 * np.pi * 0.5 * t)
    return [(t, x, truth.simulate(t, x, curve_angle=a), a) for a in (1.0, 3.0)]


@pytest.mark.parametrize(
    ("old", "name"),
    [
        ({"fixed": {"spring": 50.0}}, "spring"),
        ({"free": ["spring"]}, "spring"),
        ({"bounds": {"load": (-4.0, 4.0)}}, "load"),
    ],
)
def test_identify_refuses_the_old_load_names_naming_them(old, name):
    with pytest.raises(
        ValueError, match=rf"unknown parameter\(s\) \['{name}'\] of CurveAngleModel"
    ):
        ts.identify(
            ts.models.CurveAngleModel, recordings=_curve_recordings(), progress=False, **old
        )


# -- no deprecated name inside the package ------------------------------------------------------

OLD_KEYWORDS = {"total_angle", "sheath_length", "compliance"}
# old keywords of one class only (a plant's load= is a load object, not an old name)
OLD_KEYWORDS_OF = {"CurveAngleModel": {"load", "spring"}}


def _old_names_in(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            old = OLD_KEYWORDS | OLD_KEYWORDS_OF.get(ast.unparse(node.func).split(".")[-1], set())
            found += [f"{k.arg}=" for k in node.keywords if k.arg in old]
        if (
            isinstance(node, ast.Attribute)
            and node.attr == "total_angle"
            and isinstance(node.ctx, ast.Load)
        ):  # a Route's or a ShapeIntegrals' old name (the C++ core says curve_angle too)
            found.append(ast.unparse(node))
    return found


def test_the_package_uses_no_deprecated_name():
    found = {
        str(path.relative_to(ROOT)): hits
        for path in sorted(PACKAGE.rglob("*.py"))
        if (hits := _old_names_in(path))
    }
    assert found == {}


def test_the_scan_finds_an_old_name(tmp_path):
    """The scan above can fail: it sees an old keyword and the old attribute of a Route or of a
    shape (a C++ ShapeIntegrals)."""
    bad = tmp_path / "bad.py"
    bad.write_text(
        "r = Route.uniform(1.0, total_angle=2.0)\nprint(route.total_angle, s.total_angle)\n"
        "m = models.CurveAngleModel(load=1.0)\np = PullPullPlant(route, load=spring)\n"
    )
    assert sorted(_old_names_in(bad)) == [
        "load=",
        "route.total_angle",
        "s.total_angle",
        "total_angle=",
    ]


# -- the table in docs/vocabulary.md ---------------------------------------------------------


def test_the_documented_cpp_renames_are_the_core_fields():
    """Each row of the table of renamed C++ fields: its structs have the new fields, not the old."""
    text = (ROOT / "docs" / "vocabulary.md").read_text(encoding="utf-8")
    section = text.split("## C++ name and Python name", 1)[1]
    rows = re.findall(r"^\| (`\w+Params`.*?) \| (.*?) \| (.*?) \|$", section, re.M)
    assert len(rows) >= 6
    for structs, old, new in rows:
        for struct in re.findall(r"`(\w+)`", structs):
            fields = {k for k, d in vars(getattr(core, struct)).items() if isinstance(d, property)}
            new_names = re.findall(r"`([a-z_]+)`", new)
            assert new_names and set(new_names) <= fields, (struct, new)
            assert not (set(re.findall(r"`(\w+)`", old)) - set(new_names)) & fields, (struct, old)


# -- models are hashable values ----------------------------------------------------------------

MODELS = {name: cls for name, (cls, _) in _models().items()}


def _perturbed(cls, rng):
    """A model with its scalar parameters scaled at random, built twice from the same values."""
    base = cls()
    changes = {
        k: v * rng.uniform(0.8, 1.2)
        for k, v in base.params.items()
        if _is_number(v) and v > 0 and not isinstance(v, int)
    }
    try:
        return base.with_params(**changes), base.with_params(**changes)
    except ValueError:  # a random change left the valid set (e.g. |gamma| <= beta)
        return base, cls()


@pytest.mark.parametrize("name", sorted(MODELS))
def test_equal_models_hash_equal_and_work_as_set_members_and_keys(name, rng):
    cls = MODELS[name]
    for _ in range(5):
        a, b = _perturbed(cls, rng)
        assert a == b and a is not b
        assert hash(a) == hash(b)
        assert len({a, b}) == 1 and {a: "x"}[b] == "x"
        before = hash(a)
        t = np.linspace(0.0, 1.0, 50)
        # a model that takes the curve angle needs one on its first step (then keeps it)
        first = {"curve_angle": 1.0} if getattr(a, "uses_curve_angle", False) else {}
        for k, x in enumerate(np.sin(2 * np.pi * t)):
            # the streaming state moves, the value does not
            a.step(x, 0.0 if k == 0 else t[1], **(first if k == 0 else {}))
        assert hash(a) == before and a == b


def test_models_with_other_parameters_are_different_keys():
    a = ts.models.Backlash(B_r=0.1)
    b = ts.models.Backlash(B_r=0.2)
    assert a != b and len({a, b}) == 2
    assert ts.models.Backlash(B_r=0.0) == ts.models.Backlash(B_r=-0.0)
    assert hash(ts.models.Backlash(B_r=0.0)) == hash(ts.models.Backlash(B_r=-0.0))
    chain = ts.models.Chain(ts.models.Backlash(), ts.models.Polynomial(3))
    assert hash(chain) == hash(ts.models.Chain(ts.models.Backlash(), ts.models.Polynomial(3)))
    scaled = ts.models.Scaled(ts.models.Backlash(), output_gain=-2.0)
    assert {scaled: 1}[ts.models.Scaled(ts.models.Backlash(), output_gain=-2.0)] == 1
    assert math.isfinite(hash(scaled))
