"""One parameter table per C++ params struct (include/tendonsheath/param_table.hpp, issue 26):
every table is walked here against what is derived from it or must agree with it: the bound
struct (its properties and keyword constructor), the Python class that takes those parameters
(a keyword of that name with the same default, a numpydoc entry), its saved JSON, and the
generated page docs/parameters.md. The struct -> Python mapping and the fields no Python
argument sets are test_core_field_names' (PYTHON_OF, INTERNAL)."""

from __future__ import annotations

import importlib.util
import inspect
import math
import re
import sys
from pathlib import Path
from typing import Any

import numpydoc.docscrape as nd
import pytest
from test_core_field_names import INTERNAL, PYTHON_OF, _arguments

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.compensate import (
    AdaptiveController,
    ContinuumFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    LearnedFeedforward,
    TipLoop,
)

m = ts.models
ROOT = Path(__file__).resolve().parents[1]
STRUCTS = sorted(PYTHON_OF)

# struct -> {property bound by hand beside the table's rows: why}
HAND_BOUND = {
    "TipLoopParams": {
        "schedule_angles": "read-only list of schedule_size points, set by set_schedule",
        "schedule_gains": "read-only list of schedule_size points, set by set_schedule",
    },
}

# (struct, field) -> why a Python default differs from the table's (in form, or for one kind)
DEFAULT_DIFFERS = {
    ("HystereticOscillatorParams", "input_interpolation"): "Python names the code: 'linear' is 1",
}

# struct -> why no JSON holds its fields
NOT_SAVED = {
    "SingleTendonParams": "a plant is not saved to JSON (a scenario file builds it)",
    "PullPullParams": "a plant is not saved to JSON (a scenario file builds it)",
    "ContinuumParams": "a plant is not saved to JSON (a scenario file builds it)",
    "MotorParams": "a motor is not saved to JSON (a scenario file builds it)",
    "SensorParams": "a sensor is not saved to JSON (a scenario file builds it)",
}


def _curve_ff() -> CurveAngleFeedforward:
    return CurveAngleFeedforward(friction=0.1, stiffness=2e4, length=1.0, pretension=10.0)


def _default_of(kind: str) -> Any:
    return lambda: [getattr(m, kind)()]


# struct -> the saved objects whose to_dict() together hold its fields: a model of the core's
# list (model_list.hpp) with its defaults, unless given below; then the others
SAVED = {
    **{k["params"].__name__: _default_of(k["kind"]) for k in core.model_kinds()},
    "PolynomialParams": lambda: [m.Polynomial(coefficients=[0.0, 1.0])],
    "LagInverseParams": lambda: [
        InverseFeedforward(m.FirstOrderLag()),
        InverseFeedforward(m.SecondOrderLag()),
    ],
    "BacklashInverseParams": lambda: [InverseFeedforward(m.Backlash())],
    "CurveAngleFeedforwardParams": lambda: [_curve_ff()],
    "ContinuumFeedforwardParams": lambda: [ContinuumFeedforward()],
    "AdaptiveControllerParams": lambda: [AdaptiveController()],
    "EncoderLoopParams": lambda: [EncoderLoop(InverseFeedforward(m.Backlash()))],
    "TipLoopParams": lambda: [TipLoop(_curve_ff())],
    "LearnedFeedforwardParams": lambda: [
        LearnedFeedforward(InverseFeedforward(m.Backlash()), table=[0.0, 0.1], table_dt=1e-3)
    ],
}


# the compensators of the core's list bound from their tables: saved as built from defaults
def _built_from_defaults(kind: str):
    return lambda: [getattr(ts.compensate, kind)()]


SAVED.update(
    {
        kind + "Params": _built_from_defaults(kind)
        for kind in core.compensator_kinds()
        if kind + "Params" not in SAVED and kind + "Params" in PYTHON_OF
    }
)


def _rows(struct: str) -> list[dict[str, Any]]:
    return getattr(core, struct).fields()


def _properties(cls: type) -> set[str]:
    return {n for n, d in vars(cls).items() if isinstance(d, property) and not n.startswith("_")}


def _same(python_default: Any, table_default: Any) -> bool:
    """A Python default equal to the table's: numbers, sequences, an enum by its name, a nested
    struct (an Envelope) by its (a, b, c, d)."""
    if isinstance(table_default, list):
        return list(python_default) == table_default
    if hasattr(type(table_default), "__members__"):
        return str(python_default) == table_default.name
    if isinstance(table_default, core.Envelope):
        t = table_default
        return tuple(python_default) == (t.a, t.b, t.c, t.d)
    return python_default == table_default or (
        isinstance(table_default, float)
        and math.isnan(table_default)
        and math.isnan(python_default)
    )


def _doc_names(target) -> dict[str, str]:
    """A numpydoc Parameters section as {name: description} (``a, b : float`` gives both)."""
    doc = nd.ClassDoc(target) if isinstance(target, type) else nd.FunctionDoc(target)
    out = {}
    for p in doc["Parameters"]:
        for name in p.name.split(","):
            out[name.strip()] = " ".join(p.desc)
    return out


def _documented(name: str, targets) -> bool:
    """An entry for name, or a ``**kwargs`` entry whose description lists it."""
    for t in targets:
        entries = _doc_names(t)
        if name in entries:
            return True
        for key, desc in entries.items():
            if key.startswith("**") and re.search(rf"(?<!\w){re.escape(name)}(?!\w)", desc):
                return True
    return False


def _keys(obj: Any) -> set[str]:
    """Every key of every dict nested in a to_dict() result."""
    if isinstance(obj, dict):
        return set(obj).union(*(_keys(v) for v in obj.values()))
    if isinstance(obj, list | tuple):
        return set().union(*(_keys(v) for v in obj)) if obj else set()
    return set()


# -- the checks, as functions of the rows (the self-check feeds them a broken row) ----------


def binding_problems(struct: str, rows: list[dict[str, Any]]) -> list[str]:
    """The bound struct's properties are exactly the rows' names (and the hand-bound ones)."""
    names = [r["name"] for r in rows]
    bound = _properties(getattr(core, struct))
    expected = set(names) | set(HAND_BOUND.get(struct, {}))
    problems = [f"{struct}: bound but not in its table: {sorted(bound - expected)}"] * bool(
        bound - expected
    )
    problems += [f"{struct}: in its table but not bound: {sorted(expected - bound)}"] * bool(
        expected - bound
    )
    if len(set(names)) != len(names):
        problems.append(f"{struct}: a row twice")
    return problems


def python_problems(struct: str, rows: list[dict[str, Any]]) -> list[str]:
    """Each row's field is a keyword of a Python callable that takes the struct, with the
    table's default (where it has one: None keeps the C++ default), and has a docstring entry."""
    targets = PYTHON_OF[struct]
    problems = []
    for row in rows:
        name = row["name"]
        if name in INTERNAL.get(struct, {}):
            continue
        takers = [t for t in targets if name in _arguments(t)]
        if not takers:
            problems.append(f"{struct}.{name}: no Python keyword")
            continue
        defaults = [  # a callable built from its table (TABLE in its def) has no copy to compare
            p.default  # (test_param_single_copy: its defaults are the table's)
            for t in takers
            if getattr(t, "_table_struct", None) is not getattr(core, struct)
            and (p := inspect.signature(t).parameters.get(name)) is not None
            and p.default not in (None, inspect.Parameter.empty)
        ]
        if (struct, name) not in DEFAULT_DIFFERS and any(
            not _same(d, row["default"]) for d in defaults
        ):
            problems.append(f"{struct}.{name}: Python default {defaults} != {row['default']}")
        if not _documented(name, takers):
            problems.append(f"{struct}.{name}: no docstring entry")
    return problems


def json_problems(struct: str, rows: list[dict[str, Any]], saved: list[Any]) -> list[str]:
    """Each row's field is a key of the saved objects' to_dict() (internal fields aside; a
    nested struct's row, an Envelope, may be saved flat as name_a, name_b, ...)."""
    keys = set().union(*(_keys(obj.to_dict()) for obj in saved))
    internal = INTERNAL.get(struct, {})

    def saved_flat(row):
        nested = not isinstance(row["default"], float | int | bool | list)
        return nested and any(k.startswith(row["name"] + "_") for k in keys)

    missing = [
        r["name"]
        for r in rows
        if r["name"] not in internal and r["name"] not in keys and not saved_flat(r)
    ]
    return [f"{struct}: not in the saved JSON: {missing}"] if missing else []


# -- the walk ------------------------------------------------------------------------------


def test_every_params_struct_has_a_table():
    with_table = sorted(
        n for n, c in vars(core).items() if n.endswith("Params") and hasattr(c, "fields")
    )
    assert with_table == STRUCTS
    assert set(NOT_SAVED) | set(SAVED) == set(STRUCTS) and not set(NOT_SAVED) & set(SAVED)


@pytest.mark.parametrize("struct", STRUCTS)
def test_the_binding_is_the_table(struct):
    rows = _rows(struct)
    assert not binding_problems(struct, rows)
    cls = getattr(core, struct)
    default = cls()
    for row in rows:  # each row's default is the struct's own, and a keyword sets it
        assert set(row) == {
            "name",
            "unit",
            "default",
            "lo",
            "lo_closed",
            "hi",
            "hi_closed",
            "check",
            "doc",
            "applies_to",
            "role",
        }
        assert row["doc"], f"{struct}.{row['name']}: no doc"
        assert row["role"] in ("parameter", "option"), (struct, row["name"])
        value = getattr(default, row["name"])
        if isinstance(value, float | int | bool | list):
            assert value == row["default"], (struct, row["name"])
            assert getattr(cls(**{row["name"]: value}), row["name"]) == value
            with pytest.raises(TypeError, match=rf"^{struct}: {row['name']} cannot take .* str$"):
                cls(**{row["name"]: "text"})
    with pytest.raises(TypeError, match=rf"^{struct}: unknown keyword 'no_such_field'$"):
        cls(no_such_field=1.0)


@pytest.mark.parametrize("struct", STRUCTS)
def test_python_takes_and_documents_every_row(struct):
    assert not python_problems(struct, _rows(struct))


@pytest.mark.parametrize("struct", sorted(SAVED))
def test_the_saved_json_holds_every_row(struct):
    assert not json_problems(struct, _rows(struct), SAVED[struct]())


def _route():
    return core.Route.uniform(1.0, 2.5)


# owner -> how to build it from its params (the plants take routes, LearnedCorrection a table)
BUILD = {
    "SingleTendonPlant": lambda p: core.SingleTendonPlant(p, _route()),
    "PullPullPlant": lambda p: core.PullPullPlant(p, _route(), _route()),
    "ContinuumPlant": lambda p: core.ContinuumPlant(p, _route(), _route()),
    "LearnedCorrection": lambda p: core.LearnedCorrection([0.0], p),
}
# struct -> why its owner is not built here
NOT_BUILT = {
    "LagInverseParams": "LagInverse is bound only inside ModelInverse (test_model_inverse)",
    "PlantModelParams": "PlantModel is bound only inside ModelInverse (test_model_inverse)",
}


def _below(row: dict) -> float | int:
    """A value just below an at_least row's bound (an integer for an integer field)."""
    if isinstance(row["default"], int):
        return int(row["lo"]) - 1
    return row["lo"] - 0.5


# The walk below builds each owner from defaults plus one field out of its range; a row that
# applies to some parameters only (a Motor's kind: applies_to) with those (APPLIES), and with the
# others it must pass.
BAD = {  # check -> (a value out of range, the message's tail)
    "positive": lambda r: (0.0, "must be > 0 (got 0)"),
    "non_negative": lambda r: (-1.0, "must be >= 0 (got -1)"),
    "at_least": lambda r: (_below(r), f"must be >= {r['lo']:g} (got {_below(r):g})"),
    "in_range": lambda r: (
        r["hi"] + 1.0,
        f"must be in [{r['lo']:g}, {r['hi']:g}] (got {r['hi'] + 1:g})",
    ),
    "finite": lambda r: (math.inf, "must be finite (got inf)"),
    "positive_or_inf": lambda r: (0.0, "must be > 0 (got 0)"),
}
# (struct, applies_to) -> the other fields that make a row apply (a torque motor needs inertia)
APPLIES = {
    ("MotorParams", "position"): {"kind": core.MotorKind.Position},
    ("MotorParams", "torque"): {"kind": core.MotorKind.Torque, "inertia": 1e-3},
}


@pytest.mark.parametrize("struct", sorted(set(STRUCTS) - set(NOT_BUILT)))
def test_every_checked_row_is_the_constructors_first_message(struct):
    """Each row with a checked bound: the owner built from defaults and that one field out of
    range fails first with validate.hpp's message naming it, whether the constructor checks it
    from the table or by hand (so a table cannot claim a bound its constructor does not hold)."""
    cls = getattr(core, struct)
    build = BUILD.get(cls.owner, getattr(core, cls.owner))
    for row in cls.fields():
        if row["check"] not in BAD:
            continue
        value, tail = BAD[row["check"]](row)
        name = row["name"]
        setup = APPLIES[(struct, row["applies_to"])] if row["applies_to"] else {}
        with pytest.raises(ValueError, match=f"^{re.escape(f'{cls.owner}: {name} {tail}')}"):
            build(cls(**{**setup, row["name"]: value}))
        if row["applies_to"]:  # the bound holds only where the row applies
            others = [
                s for (st, w), s in APPLIES.items() if st == struct and w != row["applies_to"]
            ]
            for other in others:
                build(cls(**{**other, row["name"]: value}))


def test_checked_from_table_is_what_the_header_does():
    """checked_from_table (the docs page's claim) is true exactly for the structs whose table's
    header calls validate_fields()."""
    # the function that checks a struct, where it is not its owner's constructor
    checker = {
        "ContinuumParams": r"continuum_to_pull_pull\(const ContinuumParams& c\)",
        "PlantModelParams": r"static PullPullPlant make\(const Params& p\)",
    }
    for header in (ROOT / "include" / "tendonsheath").rglob("*.hpp"):
        text = header.read_text(encoding="utf-8")
        for struct in re.findall(r"^struct ParamTable<(\w+)>", text, flags=re.M):
            owner = getattr(core, struct).owner
            head = checker.get(struct, rf"{owner}\([^)]*const Params& p[^)]*\)")
            calls = re.search(rf"{head}[^{{]*\{{[^}}]*validate_fields\([pc],", text)
            assert getattr(core, struct).checked_from_table == bool(calls), struct


def test_a_checked_bound_is_the_constructors_message():
    """A row checked from the table fails with validate.hpp's message, in the owner's name."""
    for struct, field, bad, message in (
        ("BacklashParams", "c_r", 0.0, "Backlash: c_r must be > 0 (got 0)"),
        (
            "BoucWenBacklashParams",
            "sigma",
            0.25,
            "BoucWenBacklash: sigma must be >= 0.5 (got 0.25)",
        ),
        ("CurveAngleParams", "play", -1.0, "CurveAngleModel: play must be >= 0 (got -1)"),
        ("SensorParams", "delay", -1.0, "Sensor: delay must be >= 0 (got -1)"),
        (
            "EncoderLoopParams",
            "derivative_cutoff_hz",
            0.0,
            "EncoderLoop: derivative_cutoff_hz must be > 0 (got 0)",
        ),
    ):
        cls = getattr(core, struct)
        owner = getattr(core, cls.owner)
        with pytest.raises(ValueError, match=f"^{re.escape(message)}$"):
            owner(cls(**{field: bad}))


def test_the_walk_can_fail():
    """Self-check: a deliberately broken row is caught by each check."""
    rows = _rows("BacklashParams")
    renamed = [dict(rows[0], name="c_right")] + rows[1:]
    assert binding_problems("BacklashParams", renamed) == [
        "BacklashParams: bound but not in its table: ['c_r']",
        "BacklashParams: in its table but not bound: ['c_right']",
    ]
    assert python_problems("BacklashParams", renamed) == [
        "BacklashParams.c_right: no Python keyword"
    ]
    wrong_default = [dict(rows[0], default=2.0)] + rows[1:]
    assert python_problems("BacklashParams", wrong_default) == [
        "BacklashParams.c_r: Python default [1.0] != 2.0"
    ]
    assert json_problems("BacklashParams", renamed, [m.Backlash()]) == [
        "BacklashParams: not in the saved JSON: ['c_right']"
    ]
    assert not _documented("c_right", (m.Backlash,))


def test_the_parameters_page_is_current(capsys):
    spec = importlib.util.spec_from_file_location(
        "parameters_page", ROOT / "tools" / "parameters_page.py"
    )
    page = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = page
    try:
        spec.loader.exec_module(page)
        code = page.main(["--check"])
        names = [n for _, group in page.structs_by_group() for n in group]
    finally:
        sys.modules.pop(spec.name, None)
    assert code == 0, (
        "docs/parameters.md is stale: run `python tools/parameters_page.py`\n"
        + capsys.readouterr().out
    )
    assert sorted(names) == STRUCTS  # every table on the page, each once


# public classes with numeric settings that are on neither kind of table, and why
NOT_ON_THE_PAGE = {
    "Comparison": "a result of compare_models (parsimony is how it was ranked)",
    "CoupledFit": "a result of identify_coupled",
    "Diagnostics": "a result of identify",
    "ServoFit": "a result of identify_servo",
    "Status": "per-sample flags (an IntFlag), not settings",
    "Identifier": "identify's options, documented with ts.identify (docs/api)",
}


def _page_module():
    spec = importlib.util.spec_from_file_location(
        "parameters_page", ROOT / "tools" / "parameters_page.py"
    )
    page = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(page)
    return page


def _configurable_classes() -> set[str]:
    """The public classes whose constructor takes a number with a default, or a model's
    coupling (Coupled) or a model to invert (the composite compensators)."""
    found = set()
    for mod in (ts, ts.models, ts.compensate, ts.bench, ts.io, ts.identify):
        for name in mod.__all__:
            cls = getattr(mod, name, None)
            if not inspect.isclass(cls) or issubclass(cls, BaseException):
                continue
            try:
                params = inspect.signature(cls).parameters.values()
            except (TypeError, ValueError):
                continue
            numbers = [
                p
                for p in params
                if isinstance(p.default, int | float) and not isinstance(p.default, bool)
            ]
            if numbers or name in ("Coupled", "LoadCompensated", "CoupledFeedforward"):
                found.add(name)
    return found


def test_every_configurable_class_is_on_the_parameters_page():
    """A class with settings is a C++ table's (PYTHON_OF), on the page's Python-only tables,
    or named above with why not: a new class fails here until it is one of them."""
    page = _page_module()
    on_page = {name for _, name, _ in page.PYTHON_CLASSES}
    tables = {getattr(t, "__name__", "") for targets in PYTHON_OF.values() for t in targets}
    missing = _configurable_classes() - on_page - tables - set(NOT_ON_THE_PAGE)
    assert not missing, f"configurable classes on no table of docs/parameters.md: {missing}"
    text = (ROOT / "docs" / "parameters.md").read_text(encoding="utf-8")
    for name in ("Loaded", "Coupled", "ShapeSensing", "IterativeLearning"):
        assert f"### {name}\n" in text
    assert {"Loaded", "ShapeSensing", "IterativeLearning"} <= _configurable_classes()
