"""A parameter is written once, in its C++ parameter table (issue 37, item 2).

The Python model classes take their names (``param_names``, ``option_names``, the saved file's
keys), signatures, defaults and the numpydoc entries of their parameters from ``fields()``
(``tendonsheath/models/_param_table.py``); the plants, the motor and the sensor, whose
constructors interleave the rows with Python-only arguments, take the rows' defaults and
entries from it (``TABLE`` in the ``def``, ``tendonsheath/_util/param_table.py``). This test
reads the source of every module of ``tendonsheath/models`` and of those plant modules and
fails where one writes again what a table already says:

- a default: an argument or a dict key named as a row with a literal value;
- the names: ``param_names``/``option_names`` assigned a literal naming a row, or a literal
  list of two or more rows' names;
- a forward by hand: a call keyword ``name=name`` for a row;
- a docstring entry: a class's docstring Parameters section documenting a row (outside
  models/, a function's too: Motor.position is built from the table).

A Python default that differs from the table's on purpose is listed in ``DIFFERS``, with why.

A self-check feeds it the Backlash module as it was written before (every one of these).
"""

from __future__ import annotations

import ast
import inspect
from pathlib import Path

import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.models._param_table import from_table

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "python" / "tendonsheath"
MODELS = PACKAGE / "models"

# the modules outside models/ whose classes take a table's rows: file -> (its structs, the
# Python callables built from them by table_constructor / table_defaults)
TABLE_BUILT = {
    "plant/single_tendon.py": (("SingleTendonParams",), (ts.SingleTendonPlant,)),
    "plant/pull_pull.py": (("PullPullParams",), (ts.PullPullPlant,)),
    "plant/continuum.py": (("ContinuumParams",), (ts.ContinuumPlant,)),
    "plant/motor.py": (("MotorParams",), (ts.Motor.position, ts.Motor.torque)),
    "plant/sensor.py": (("SensorParams",), (ts.Sensor,)),
    "plant/base.py": (("SingleTendonParams", "PullPullParams", "ContinuumParams"), ()),
    # a feedforward whose constructor is its table's rows (compensate/from_table.py)
    "compensate/dead_band_inverse.py": (
        ("DeadBandInverseParams",),
        (ts.compensate.DeadBandInverse,),
    ),
}

# the compensator modules built from their tables: file -> (struct, the callables built from it).
# Scanned for a row's literal default and a class docstring's entry for a row that holds a value
# (a nested struct such as ``limits`` takes Python forms of its own, documented by hand); their
# names lists (``_saved_settings``) and ``name=name`` forwards are not derived yet.
COMPENSATORS = {
    "compensate/encoder_loop.py": ("EncoderLoopParams", (ts.compensate.EncoderLoop,)),
    "compensate/tip_loop.py": ("TipLoopParams", (ts.compensate.TipLoop,)),
    "compensate/learned_feedforward.py": (
        "LearnedFeedforwardParams",
        (ts.compensate.LearnedFeedforward,),
    ),
    "compensate/inverse_feedforward.py": (
        "BacklashInverseParams",
        (ts.compensate.InverseFeedforward,),
    ),
    "compensate/curve_angle_feedforward.py": (
        "CurveAngleFeedforwardParams",
        (ts.compensate.CurveAngleFeedforward,),
    ),
    "compensate/continuum_feedforward.py": (
        "ContinuumFeedforwardParams",
        (ts.compensate.ContinuumFeedforward, ts.compensate.ContinuumFeedforward.from_model),
    ),
}

# (file, function, row) -> why its Python default is not the table's (written, documented by hand)
DIFFERS = {
    ("plant/motor.py", "torque", "inertia"): (
        "a torque motor needs inertia > 0: 1e-2; the table's 0 is the position motor's ideal lag"
    ),
}


def _module_rows() -> dict[str, set[str]]:
    """module file name -> the row names of the tables its classes take."""
    out: dict[str, set[str]] = {}
    for name in dir(ts.models):
        cls = getattr(ts.models, name)
        struct = getattr(cls, "_core_params", None)
        if not inspect.isclass(cls) or struct is None:
            continue
        file = Path(inspect.getfile(cls)).name
        out.setdefault(file, set()).update(r["name"] for r in struct.fields())
    return out


def _literal(node: ast.AST | None) -> bool:
    """A number, a string, a bool, or a tuple/list of them (None is "derived", not a copy)."""
    if isinstance(node, ast.Constant):
        return node.value is not None
    if isinstance(node, ast.UnaryOp):
        return _literal(node.operand)
    if isinstance(node, ast.Tuple | ast.List):
        return bool(node.elts) and all(_literal(e) for e in node.elts)
    return False


def _documented_rows(doc: str, rows: set[str]) -> list[str]:
    """The rows a docstring's own Parameters section documents."""
    lines = inspect.cleandoc(doc).splitlines()
    found, inside = [], False
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if line.strip() and set(nxt.strip()) == {"-"}:
            inside = line.strip() == "Parameters"
            continue
        if inside and line and not line[0].isspace() and " : " in line:
            names = [n.strip() for n in line.split(" : ")[0].split(",")]
            found += [n for n in names if n in rows]
    return found


def copies(source: str, rows: set[str], function_docs: bool = False) -> list[str]:
    """What the module's source writes again of the rows: one line per finding (a function's
    docstring too with ``function_docs``, where functions are built from a table: a model
    module's factory may document an argument of a row's name that is not the row)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        where = f"line {getattr(node, 'lineno', '?')}"
        if isinstance(node, ast.FunctionDef):
            args = node.args
            positional = args.posonlyargs + args.args
            pairs = list(
                zip(positional[len(positional) - len(args.defaults) :], args.defaults, strict=True)
            )
            pairs += [
                (a, d)
                for a, d in zip(args.kwonlyargs, args.kw_defaults, strict=True)
                if d is not None
            ]
            found += [
                f"{where}: default of {a.arg} in {node.name}()"
                for a, d in pairs
                if a.arg in rows and _literal(d)
            ]
        elif isinstance(node, ast.Dict):
            found += [
                f"{where}: default of {k.value} in a dict"
                for k, v in zip(node.keys, node.values, strict=True)
                if isinstance(k, ast.Constant) and k.value in rows and _literal(v)
            ]
        elif isinstance(node, ast.Assign | ast.AnnAssign):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            for t in targets:
                literal = isinstance(node.value, ast.Tuple | ast.List) and any(
                    isinstance(e, ast.Constant) and e.value in rows for e in node.value.elts
                )
                if isinstance(t, ast.Name) and t.id in ("param_names", "option_names") and literal:
                    found.append(f"{where}: {t.id} written by hand")
        elif isinstance(node, ast.Tuple | ast.List):
            named = [e.value for e in node.elts if isinstance(e, ast.Constant) and e.value in rows]
            if len(named) >= 2:
                found.append(f"{where}: the names {named} listed by hand")
        elif isinstance(node, ast.Call):
            found += [
                f"{where}: {k.arg}={k.arg} forwarded by hand"
                for k in node.keywords
                if k.arg in rows and isinstance(k.value, ast.Name) and k.value.id == k.arg
            ]
        if isinstance(node, ast.ClassDef) or (function_docs and isinstance(node, ast.FunctionDef)):
            doc = ast.get_docstring(node, clean=False) or ""
            found += [
                f"{where}: {name} documented by hand in {node.name}"
                for name in _documented_rows(doc, rows)
            ]
    return found


MODULE_ROWS = _module_rows()


def test_every_table_model_module_is_scanned():
    expected = {
        "backlash.py",
        "bouc_wen.py",
        "bouc_wen_backlash.py",
        "hysteretic_oscillator.py",
        "prandtl_ishlinskii.py",
        "generalized_prandtl_ishlinskii.py",
        "polynomial.py",
        "curve_angle.py",
        "plant_model.py",
    }
    assert expected <= set(MODULE_ROWS)


@pytest.mark.parametrize("module", sorted(MODULE_ROWS))
def test_no_model_module_writes_a_row_twice(module):
    source = (MODELS / module).read_text(encoding="utf-8")
    assert not copies(source, MODULE_ROWS[module])


def _differs(module: str, finding: str) -> bool:
    """A finding that DIFFERS lists (its default, and its entry documented by hand)."""
    return any(
        m == module and (f"of {row} in {func}()" in finding or f"{row} documented by hand in "
                         f"{func}" in finding)
        for m, func, row in DIFFERS
    )  # fmt: skip


@pytest.mark.parametrize("module", sorted(TABLE_BUILT))
def test_no_table_built_module_writes_a_row_twice(module):
    structs, _ = TABLE_BUILT[module]
    rows = {r["name"] for s in structs for r in getattr(core, s).fields()}
    source = (PACKAGE / module).read_text(encoding="utf-8")
    found = copies(source, rows, function_docs=True)
    assert [f for f in found if not _differs(module, f)] == []


def _value_rows(struct: str) -> set[str]:
    """The rows holding a number, a flag, a string, a list or an enum (not a nested struct)."""
    return {
        r["name"]
        for r in getattr(core, struct).fields()
        if isinstance(r["default"], float | int | bool | str | list)
        or hasattr(type(r["default"]), "__members__")
    }


@pytest.mark.parametrize("module", sorted(COMPENSATORS))
def test_no_compensator_module_writes_a_rows_default_or_entry(module):
    struct, _ = COMPENSATORS[module]
    source = (PACKAGE / module).read_text(encoding="utf-8")
    found = copies(source, _value_rows(struct))
    assert [f for f in found if "default of" in f or "documented by hand" in f] == []


@pytest.mark.parametrize("module", sorted(COMPENSATORS))
def test_every_table_built_compensator_shows_the_tables_defaults(module):
    struct, built = COMPENSATORS[module]
    for target in built:
        assert getattr(target, "_table_struct", None) is getattr(core, struct), target
        doc = "\n" + inspect.getdoc(target)
        for row in getattr(core, struct).fields():
            param = inspect.signature(target).parameters.get(row["name"])
            if param is None or row["name"] not in _value_rows(struct):
                continue
            shown = row["default"]
            shown = shown.name if hasattr(type(shown), "__members__") else shown
            assert param.default in (None, param.empty, shown), (target, row["name"])
            assert f"\n{row['name']} : " in doc, (target, row["name"])


@pytest.mark.parametrize("module", sorted(TABLE_BUILT))
def test_every_table_built_callable_shows_the_tables_defaults(module):
    """The signature's default of each row is the table's (None: the C++ default, or an effect
    left off), but where DIFFERS says why not; its docstring documents each row it takes."""
    structs, built = TABLE_BUILT[module]
    for target in built:
        assert getattr(target, "_table_struct", None) is getattr(core, structs[0]), target
        name = target.__name__
        doc = "\n" + inspect.getdoc(target)
        for row in getattr(core, structs[0]).fields():
            param = inspect.signature(target).parameters.get(row["name"])
            if param is None:
                continue
            if (module, name, row["name"]) not in DIFFERS:
                assert param.default in (None, row["default"]), (name, row["name"])
            assert f"\n{row['name']} : " in doc, (name, row["name"])


def test_every_table_model_is_built_from_its_table():
    """Each model class with a table is completed by from_table: its names, its signature's
    defaults and its Parameters entries are the table's."""
    for name in ts.models.__all__:
        cls = getattr(ts.models, name)
        if not inspect.isclass(cls) or getattr(cls, "_core_params", None) is None:
            continue
        rows = cls._core_params.fields()
        names = {r["name"] for r in rows}
        flat = set(cls.param_names) | set(cls.option_names)
        assert flat == names or name.startswith("GeneralizedPrandtlIshlinskii"), name
        signature = inspect.signature(cls)
        for row in rows:
            param = signature.parameters[row["name"]]
            if param.default is not None:
                assert param.default == cls._python_value(row["name"], row["default"]) or (
                    param.default == tuple(row["default"])
                ), (name, row["name"])
            assert f"\n{row['name']} : " in "\n" + inspect.getdoc(cls), (name, row["name"])


OLD_BACKLASH = '''
class Backlash(HysteresisModel, core.Backlash):
    """Exact piecewise backlash.

    Parameters
    ----------
    c_r, c_l : float, default 1.0
        Slopes of the rising and falling branches (> 0).
    B_r, B_l : float, default 0.1
        Half-widths of the band (input unit), >= 0.
    """

    _core_params = core.BacklashParams
    param_names = ("c_r", "c_l", "B_r", "B_l")
    added_params = {"B_l": 0.1}

    def __init__(self, c_r: float = 1.0, c_l: float = 1.0, B_r: float = 0.1, B_l: float = 0.1):
        super().__init__(c_r=c_r, c_l=c_l, B_r=B_r, B_l=B_l)
'''


def test_the_scan_can_fail():
    """Self-check: the Backlash module as it was written before this test (each copy found)."""
    found = copies(OLD_BACKLASH, {"c_r", "c_l", "B_r", "B_l"})
    assert sum("default of" in f and "__init__" in f for f in found) == 4
    assert sum("forwarded by hand" in f for f in found) == 4
    assert sum("documented by hand" in f for f in found) == 4
    assert any("param_names written by hand" in f for f in found)
    assert any("listed by hand" in f for f in found)
    assert any("default of B_l in a dict" in f for f in found)
    assert not copies("x = {'c_r': None}\ndef f(B_r=None): pass\n", {"c_r", "B_r"})


def test_from_table_needs_a_documented_python_only_argument():
    """An argument in no table row and not in the class's own Parameters section is refused
    when the class is made, not found later by the docs walk."""

    class _Toy(ts.models.Backlash):
        """A toy."""

        def __init__(self, gain: float = 2.0, **values):
            super().__init__(**values)

    with pytest.raises(TypeError, match=r"_Toy: argument 'gain' is in no table row"):
        from_table(_Toy)


def test_table_fills_only_a_rows_default():
    """TABLE is replaced by the row's default (positional and keyword-only arguments alike);
    TABLE for an argument in no row is refused when the function is made."""
    from tendonsheath._util.param_table import TABLE, table_defaults

    @table_defaults(core.SensorParams)
    def f(self, resolution=TABLE, *, history=TABLE, gain=2.0):  # a method: self aside
        """A toy.

        Parameters
        ----------
        gain : float, default 2.0
            A gain.
        """

    assert f.__defaults__ == (0.0,) and f.__kwdefaults__ == {"history": 1024, "gain": 2.0}
    assert "\nhistory : int, default 1024\n" in f.__doc__
    with pytest.raises(TypeError, match=r"argument 'gain' defaults to TABLE but is in no row"):

        @table_defaults(core.SensorParams)
        def g(self, gain=TABLE):
            """A toy."""
