"""Walk the public API (issue 14, item 1), in the spirit of python-control's ``kwargs_test.py``
and ``docstrings_test.py``.

Every public name is walked: a module's ``__all__`` where it has one, else the functions and
classes it defines whose names do not start with ``_``; and each public class's own public
methods and properties. For every public callable:

* its docstring is in numpydoc form (parsed with ``numpydoc.docscrape``), with a ``Parameters``
  section listing exactly the signature's parameters (less ``self``/``cls``; ``*args`` and
  ``**kwargs`` under their starred names) and a ``Returns`` (or ``Yields``) section when it
  returns something; a class documents its constructor's parameters in the class docstring;
* it rejects an unknown keyword with a TypeError that names the keyword;
* no parameter has a deprecated name (``DEPRECATED`` below);

and no call inside the package passes a deprecated keyword.

A check that cannot apply to a name is listed in ``NOT_APPLICABLE`` with the reason.
"""

from __future__ import annotations

import ast
import importlib
import inspect
import re
import textwrap
import warnings
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from numpydoc.docscrape import NumpyDocString

import tendonsheath as ts

# The public modules, in the order their docstrings were written.
PUBLIC_MODULES = [
    "tendonsheath.models",
    "tendonsheath.plant.loads",
    "tendonsheath.plant.route",
    "tendonsheath.plant.sensor",
    "tendonsheath.plant.motor",
    "tendonsheath.status",
    "tendonsheath.plant.presets",
    "tendonsheath.plant.physics",
    "tendonsheath.io",
    "tendonsheath.compensate",
    "tendonsheath.simulation_result",  # before plant, which re-exports SimulationResult
    "tendonsheath.plant.coupled",  # before plant, which re-exports CoupledPlant
    "tendonsheath.plant",
    "tendonsheath.sweep",
    "tendonsheath.bench",
    "tendonsheath.report.build",
    "tendonsheath.report.summary",
    "tendonsheath.identify",
    "tendonsheath.apps.compare",
    "tendonsheath.apps.session",
    "tendonsheath.apps.inverse_error",
    "tendonsheath.control_interop",
    "tendonsheath.apps.export_cpp",
    "tendonsheath.protocols",
    "tendonsheath.ros2",
    "tendonsheath",
]

# The package's other modules, and why the walk leaves them out (they are not a Python API:
# none is exported by tendonsheath.__all__ or a subpackage's __all__).
NOT_WALKED = {
    "tendonsheath.apps": "the applications' folder (its modules walked or listed here)",
    "tendonsheath.apps.cli": "the `tendonsheath` command (typer): documented by its --help",
    "tendonsheath.apps.export_cpp_multi": "the multi-input compensators of export_cpp (walked)",
    "tendonsheath.apps.demo": "the `tendonsheath demo` job, run by the command",
    "tendonsheath._util.outputs": "output-path checks of the commands",
    "tendonsheath.plots": "the figure behind the plants' plot_tensions() (walked there)",
    "tendonsheath.report": "the report's folder (report.build and report.summary walked)",
    "tendonsheath.report.figures": "figures of report.build (walked)",
    "tendonsheath.report.html": "HTML of report.build (walked)",
    "tendonsheath.report.interactive": "Plotly figures of report.build (walked)",
    "tendonsheath.report.units": "angle units of report.build (walked)",
}

# Modules whose docstrings are not written yet: the docstring check does not walk them (the
# keyword and vocabulary checks do). Remove a module from here once its docstrings are written.
DOCSTRINGS_NOT_YET_WRITTEN: set[str] = set()

# Deprecated parameter names, from issue 14 (docs/vocabulary.md adds the rest at merge):
# old name -> (the name to use, the classes it is deprecated in; None: everywhere)
DEPRECATED = {
    "total_angle": ("curve_angle", None),
    "v_eps": ("smoothing", None),
    "a": ("alpha", ("BoucWen",)),  # BoucWen's share of the linear path
    "sheath_length": ("length", ("ContinuumFeedforward",)),
    "compliance": ("stiffness", ("CurveAngleFeedforward",)),
    # CurveAngleModel's scalar loads at the tendon (a plant's load= is a load object: kept)
    "load": ("load_force", ("CurveAngleModel",)),
    "spring": ("load_stiffness", ("CurveAngleModel",)),
}


def _deprecated_in(qual: str, name: str) -> str | None:
    if name not in DEPRECATED:
        return None
    new, scope = DEPRECATED[name]
    parts = qual.split(".")
    return new if scope is None or any(c in parts for c in scope) else None


# name -> why a check cannot apply to it ("docstring", "keywords")
NOT_APPLICABLE = {
    "docstring": {
        # enum members and flags take a value, documented in the class's table of members
        "tendonsheath.status.Status": "an IntFlag: constructed from an int, no Parameters",
    },
    "keywords": {
        "tendonsheath.status.Status": "an IntFlag: Status(value) is Enum's constructor",
        "tendonsheath.bench.calibration.Calibration.told": (
            "its keywords are the user's declared values (name=(value, source)): any name"
        ),
        # a typing.Protocol is never instantiated: any call raises "Protocols cannot be
        # instantiated", whatever the keywords (its members are walked)
        **{
            f"tendonsheath.protocols.{name}": "a typing.Protocol: it cannot be instantiated"
            for name in (
                "BenchCompensator",
                "Compensator",
                "FeedforwardCompensator",
                "Plant",
                "SteppedPlant",
                "StreamingCompensator",
            )
        },
    },
}

BOGUS = "no_such_keyword_xyz"
# the TypeError names the keyword, or says that no keyword is taken at all (BaseException)
REJECTED = f"{BOGUS}|takes no keyword arguments|takes no arguments"


def _module_names(module) -> list[str]:
    names = getattr(module, "__all__", None)
    if names is not None:
        return [n for n in names if not n.startswith("_")]
    return [
        n
        for n, obj in vars(module).items()
        if not n.startswith("_")
        and (inspect.isfunction(obj) or inspect.isclass(obj))
        and getattr(obj, "__module__", None) == module.__name__
    ]


def _own_members(cls) -> list[tuple[str, object]]:
    """A class's public methods and properties: its own, and those it inherits from a
    private base of the package (a public base's are walked on that base)."""
    members, seen = [], set()
    for klass in cls.__mro__:
        inherited = klass is not cls
        if inherited and not (klass.__module__.startswith("tendonsheath") and _private_base(klass)):
            continue
        for name, raw in vars(klass).items():
            if name.startswith("_") or name in seen:
                continue
            seen.add(name)
            if isinstance(raw, (classmethod, staticmethod)):
                members.append((name, raw.__func__))
            elif isinstance(raw, property) or inspect.isfunction(raw):
                members.append((name, raw))
    return members


def _private_base(klass) -> bool:
    """A base class no public module exports (e.g. ``_GeneralizedBase``, ``Feedforward``)."""
    for modname in PUBLIC_MODULES:
        module = importlib.import_module(modname)
        if any(getattr(module, n, None) is klass for n in _module_names(module)):
            return False
    return True


def _is_exception(obj) -> bool:
    return inspect.isclass(obj) and issubclass(obj, BaseException)


def _is_protocol(obj) -> bool:
    return inspect.isclass(obj) and bool(getattr(obj, "_is_protocol", False))


def public_objects() -> dict[str, tuple[str, object]]:
    """qualified name -> (module it is walked under, object); each object once."""
    found: dict[str, tuple[str, object]] = {}
    seen: set[int] = set()
    for modname in PUBLIC_MODULES:
        module = importlib.import_module(modname)
        for name in _module_names(module):
            obj = getattr(module, name)
            if inspect.ismodule(obj) or not callable(obj) or id(obj) in seen:
                continue
            seen.add(id(obj))
            qual = f"{getattr(obj, '__module__', modname)}.{obj.__qualname__}"
            found[qual] = (modname, obj)
            if inspect.isclass(obj) and not _is_exception(obj):
                for mname, member in _own_members(obj):
                    found[f"{qual}.{mname}"] = (modname, member)
    return found


PUBLIC = public_objects()
CALLABLES = {q: v for q, v in PUBLIC.items() if not isinstance(v[1], property)}


def _nanobind_signature(obj) -> tuple[list[str], bool] | None:
    """(parameter names, whether it returns None) of a nanobind function or class (its first
    overload, from ``__nb_signature__``: ``inspect.signature`` cannot read those)."""
    sigs = getattr(obj.__init__ if inspect.isclass(obj) else obj, "__nb_signature__", None)
    if not sigs:
        return None
    text = sigs[0][0]
    inner, returns = text[text.index("(") + 1 : text.rindex(")")], text[text.rindex(")") + 1 :]
    names, depth, part = [], 0, ""
    for ch in inner + ",":
        if ch == "," and depth == 0:
            names.append(re.split(r"[:=]", part)[0].strip())
            part = ""
            continue
        depth += (ch in "([{") - (ch in ")]}")
        part += ch
    names = [n for n in names if n not in ("", "/", "*")]
    return names, returns.strip() in ("", "-> None")


def _raw_params(obj) -> list[str]:
    """The signature's names, ``self`` included, starred as numpydoc writes them."""
    nb = _nanobind_signature(obj)
    if nb is not None:
        return nb[0]
    names = []
    for p in inspect.signature(obj).parameters.values():
        prefix = {p.VAR_POSITIONAL: "*", p.VAR_KEYWORD: "**"}.get(p.kind, "")
        names.append(prefix + p.name)
    return names


def _signature_params(obj) -> list[str]:
    """The names a caller passes, as numpydoc writes them (``*args``, ``**kwargs``)."""
    names = _raw_params(obj)
    if names and names[0] in ("self", "cls"):
        names = names[1:]
    return names


def _documented_params(doc: NumpyDocString) -> list[str]:
    names = []
    for entry in doc["Parameters"]:
        names += [n.strip() for n in entry.name.split(",") if n.strip()]
    return names


def _function_node(func) -> ast.FunctionDef | None:
    try:
        source = textwrap.dedent(inspect.getsource(func))
    except (OSError, TypeError):
        return None
    node = ast.parse(source).body[0]
    return node if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)) else None


def _own_nodes(node):
    """The nodes of a function body, not those of functions or classes nested in it."""
    stack = list(node.body)
    while stack:
        child = stack.pop()
        yield child
        if not isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda, ast.ClassDef)):
            stack.extend(ast.iter_child_nodes(child))


def _what_it_gives(func) -> str | None:
    """The section the function needs: Yields, Returns or None (it returns None)."""
    nb = _nanobind_signature(func)
    if nb is not None:
        return None if nb[1] else "Returns"
    node = _function_node(func)
    if node is None:
        return "Returns"
    nodes = list(_own_nodes(node))
    if any(isinstance(n, (ast.Yield, ast.YieldFrom)) for n in nodes):
        return "Yields"
    for n in nodes:
        if isinstance(n, ast.Return) and n.value is not None:
            if not (isinstance(n.value, ast.Constant) and n.value.value is None):
                return "Returns"
    return None


def _docstring_problems(obj) -> list[str]:
    text = inspect.getdoc(obj.fget if isinstance(obj, property) else obj)
    if not text or not text.strip():
        return ["no docstring"]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpydoc warns on an unknown section: a malformed doc
        try:
            doc = NumpyDocString(text)
        except Exception as err:  # noqa: BLE001 - any parse failure is the finding
            return [f"not numpydoc: {err}"]
    if not doc["Summary"]:
        return ["no summary line"]
    if isinstance(obj, property) or _is_exception(obj) or _is_protocol(obj):
        # numpydoc: a property is documented by its summary, as an attribute; an exception
        # or warning takes its message as BaseException does; a typing.Protocol has no
        # constructor (its members' docstrings are checked on their own)
        return []
    problems = []
    wanted = _signature_params(obj)
    if _documented_params(doc) != wanted:
        problems.append(f"Parameters {_documented_params(doc)} != signature {wanted}")
    if not inspect.isclass(obj):
        gives = _what_it_gives(obj)
        if gives and not doc[gives]:
            problems.append(f"no {gives} section")
    return problems


@pytest.mark.parametrize("modname", PUBLIC_MODULES)
def test_every_public_module_has_public_names(modname):
    module = importlib.import_module(modname)
    assert (module.__doc__ or "").strip(), f"{modname} has no module docstring"
    assert any(q for q, (m, _) in PUBLIC.items() if m == modname) or modname == "tendonsheath"


def test_every_module_of_the_package_is_walked_or_listed():
    package = Path(ts.__file__).parent
    modules = set()
    for path in package.rglob("*.py"):
        parts = path.relative_to(package).with_suffix("").parts
        if len(parts) == 1 or parts[0] == "report":  # top-level modules; report's modules
            modules.add(".".join(("tendonsheath", *parts)))
        else:
            modules.add(f"tendonsheath.{parts[0]}")  # a subpackage: walked through its __all__
    modules = {m.removesuffix(".__init__") for m in modules if not m.split(".")[-1][0] == "_"}
    modules.discard("tendonsheath.__main__")
    unlisted = modules - set(PUBLIC_MODULES) - set(NOT_WALKED)
    assert not unlisted, f"modules neither walked nor listed in NOT_WALKED: {sorted(unlisted)}"


def test_the_walk_covers_what_the_package_exports():
    # every name in tendonsheath.__all__ and each subpackage's __all__ is walked
    for modname in PUBLIC_MODULES:
        module = importlib.import_module(modname)
        for name in getattr(module, "__all__", []):
            obj = getattr(module, name)
            if callable(obj) and not inspect.ismodule(obj):
                assert any(o is obj for _, o in PUBLIC.values()), f"{modname}.{name} not walked"
    # the walk found the API (278 callables when written), not a handful of names
    assert len(CALLABLES) > 250


@pytest.mark.parametrize(
    "qual",
    sorted(q for q, (m, _) in PUBLIC.items() if m not in DOCSTRINGS_NOT_YET_WRITTEN),
)
def test_docstring_has_parameters_and_returns(qual):
    if qual in NOT_APPLICABLE["docstring"]:
        assert inspect.getdoc(PUBLIC[qual][1]), f"{qual}: no docstring"
        return
    problems = _docstring_problems(PUBLIC[qual][1])
    assert not problems, f"{qual}: " + "; ".join(problems)


def test_the_docstring_check_can_fail():
    def undocumented(x, y=1):
        return x + y

    def wrong(x, y=1):
        """Add.

        Parameters
        ----------
        x : float
            A number.
        """
        return x + y

    def right(x, *rest, y=1, **options):
        """Add.

        Parameters
        ----------
        x : float
            A number.
        *rest : float
            More numbers.
        y : float
            Another.
        **options
            Ignored.

        Returns
        -------
        float
            The sum.
        """
        return x + y

    assert _docstring_problems(undocumented) == ["no docstring"]
    assert len(_docstring_problems(wrong)) == 2  # y missing, no Returns
    assert _docstring_problems(right) == []


# Callables that take **kwargs run their body on a call: they get the smallest valid arguments.
def _model():
    return ts.models.Backlash()


def _log():
    t = np.linspace(0.0, 1.0, 50)
    x = np.sin(2 * np.pi * t)
    return t, x, x


def _chain():
    return ts.models.Chain(ts.models.Backlash(), ts.models.Polynomial(degree=1))


def _sprung():
    return ts.models.CurveAngleModel(load_stiffness=100.0)


def _calibration():
    """A Calibration holding default models (as if identified): its methods only read them."""
    fits = {
        "BoucWenBacklash": SimpleNamespace(model=ts.models.BoucWenBacklash()),
        "CurveAngleModel": SimpleNamespace(model=_sprung()),
    }
    from tendonsheath.identify import ServoFit

    servo = ts.bench.MotorCalibration(
        ServoFit(40.0, 0.7, 1.0, 0.0, 0, 1e-3, 0.0, 0.0), *np.zeros((3, 2))
    )
    return ts.bench.Calibration(fits=fits, runs=[], declared={}, groups={}, shape=None, servo=servo)


def _quality():
    overall = {"rmse": 0.0, "nrmse": 0.0, "fit_percent": 100.0}
    return SimpleNamespace(overall=overall, per_recording=[], n=1)


def _loop_dynamics():
    from tendonsheath.identify.loop_dynamics import LoopDynamics
    from tendonsheath.identify.servo import ServoFit

    servo = ServoFit(60.0, 0.9, 1.0, 0.0, 0, 1e-3, 0.0, 0.0)
    return LoopDynamics(servo, 40.0, 0.3, 1.0, 1, 1e-3, 40.0, 0.0, 0.0)


def _coupled_log():
    """_log() on two joints (the second shifted by a quarter of the record: a reversed one
    can be the same signal, which identify_coupled refuses)."""
    t, x, y = _log()
    shift = x.size // 4
    return t, np.column_stack([x, np.roll(x, shift)]), np.column_stack([y, np.roll(y, shift)])


MINIMAL_CALLS = {
    # a model's further inputs (curve_angle, load, ...) go to its _simulate, which names an
    # unknown one
    "tendonsheath.models.base.HysteresisModel.simulate": (
        lambda kw: ts.models.Backlash().simulate(None, np.zeros(3), **kw)
    ),
    "tendonsheath.identify.coupled.identify_coupled": (
        lambda kw: ts.identify_coupled(ts.models.Backlash, *_coupled_log(), **kw)
    ),
    "tendonsheath.compensate.coupled_feedforward.CoupledFeedforward": (
        lambda kw: ts.compensate.CoupledFeedforward(
            ts.models.Coupled([_model(), _model()], np.zeros((2, 2))), **kw
        )
    ),
    "tendonsheath.identify.estimator.identify": (
        lambda kw: ts.identify(ts.models.Backlash, *_log(), **kw)
    ),
    "tendonsheath.identify.estimator.Identifier": lambda kw: ts.Identifier(
        ts.models.Backlash, **kw
    ),
    "tendonsheath.identify.estimator.Identifier.set_params": (
        lambda kw: ts.Identifier(ts.models.Backlash).set_params(**kw)
    ),
    "tendonsheath.identify.fit.Fit.from_quality": (
        lambda kw: ts.Fit.from_quality(_model(), _quality(), **kw)
    ),
    "tendonsheath.models.bouc_wen.BoucWen": lambda kw: ts.models.BoucWen(**kw),
    "tendonsheath.models.chain.Chain.with_params": lambda kw: _chain().with_params(**kw),
    "tendonsheath.models.generalized_prandtl_ishlinskii.GeneralizedPrandtlIshlinskii": (
        lambda kw: ts.models.GeneralizedPrandtlIshlinskii(**kw)
    ),
    "tendonsheath.models.generalized_prandtl_ishlinskii.GeneralizedPrandtlIshlinskiiInverse": (
        lambda kw: ts.models.GeneralizedPrandtlIshlinskiiInverse(**kw)
    ),
    "tendonsheath.models.linear_block.LinearBlock": lambda kw: ts.models.FirstOrderLag(**kw),
    "tendonsheath.models.base.HysteresisModel": lambda kw: ts.models.Backlash(**kw),
    "tendonsheath.models.base.HysteresisModel.with_params": lambda kw: _model().with_params(**kw),
    "tendonsheath.models.scaled.Scaled.with_params": (
        lambda kw: ts.models.Scaled(_model()).with_params(**kw)
    ),
    "tendonsheath.models.scaled.Scaled.simulate": (
        lambda kw: ts.models.Scaled(_model()).simulate(np.arange(3.0), np.zeros(3), **kw)
    ),
    "tendonsheath.models.loaded.Loaded.with_params": (
        lambda kw: ts.models.Loaded(_model()).with_params(**kw)
    ),
    "tendonsheath.models.loaded.Loaded.simulate": (
        lambda kw: ts.models.Loaded(_model()).simulate(np.arange(3.0), np.zeros(3), 0.0, **kw)
    ),
    "tendonsheath.compensate.load_compensated.LoadCompensated": (
        lambda kw: ts.compensate.LoadCompensated(ts.models.Loaded(_model()), **kw)
    ),
    "tendonsheath.plant.presets.realistic_motor": lambda kw: ts.presets.realistic_motor(**kw),
    "tendonsheath.plant.presets.realistic_plant": lambda kw: ts.presets.realistic_plant(**kw),
    "tendonsheath.compensate.adaptive_controller.AdaptiveController": (
        lambda kw: ts.compensate.AdaptiveController(**kw)
    ),
    "tendonsheath.compensate.adaptive_controller.AdaptiveController.from_calibration": (
        lambda kw: ts.compensate.AdaptiveController.from_calibration(
            _model(), _loop_dynamics(), inertia=1e-4, **kw
        )
    ),
    "tendonsheath.compensate.adaptive_controller.AdaptiveController.from_model": (
        lambda kw: ts.compensate.AdaptiveController.from_model(_model(), inertia=1e-4, **kw)
    ),
    "tendonsheath.compensate.continuum_feedforward.ContinuumFeedforward.from_model": (
        # the curve angle positionally: its keyword is being renamed (issue 14)
        lambda kw: ts.compensate.ContinuumFeedforward.from_model(_sprung(), 0.002, 0.05, 1.0, **kw)
    ),
    "tendonsheath.compensate.curve_angle_feedforward.CurveAngleFeedforward.from_model": (
        lambda kw: ts.compensate.CurveAngleFeedforward.from_model(ts.models.CurveAngleModel(), **kw)
    ),
    "tendonsheath.sweep.studies.robustness_study": (
        lambda kw: importlib.import_module("tendonsheath.sweep").robustness_study(
            importlib.import_module("tendonsheath.bench.scenarios.do").robustness_run, n=1, **kw
        )
    ),
    "tendonsheath.bench.calibration.Calibration.inverse_feedforward": (
        lambda kw: _calibration().inverse_feedforward(**kw)
    ),
    "tendonsheath.bench.calibration.Calibration.encoder_loop": (
        lambda kw: _calibration().encoder_loop(_calibration().inverse_feedforward(), **kw)
    ),
    "tendonsheath.bench.calibration.Calibration.curve_angle_feedforward": (
        lambda kw: _calibration().curve_angle_feedforward(**kw)
    ),
    "tendonsheath.bench.calibration.Calibration.continuum_feedforward": (
        lambda kw: _calibration().continuum_feedforward(sensed_angle=1.0, **kw)
    ),
    "tendonsheath.simulation_result.SimulationResult": (
        lambda kw: ts.SimulationResult(np.zeros(3), **kw)
    ),
}
# the models whose constructor @from_table writes from their parameter tables take the rows
# by **values (models/_param_table.py): every such class of ts.models
MINIMAL_CALLS.update(
    {
        f"{cls.__module__}.{cls.__name__}": (lambda kw, cls=cls: cls(**kw))
        for cls in (getattr(ts.models, name) for name in ts.models.__all__)
        if inspect.isclass(cls) and getattr(cls.__init__, "from_table", False)
    }
)
# likewise the compensators whose constructor @feedforward_from_table writes
# (compensate/from_table.py): every such class of ts.compensate
MINIMAL_CALLS.update(
    {
        f"{cls.__module__}.{cls.__name__}": (lambda kw, cls=cls: cls(**kw))
        for cls in (getattr(ts.compensate, name) for name in ts.compensate.__all__)
        if inspect.isclass(cls) and getattr(cls.__init__, "from_table", False)
    }
)
MINIMAL_CALLS["tendonsheath.models.polynomial.Polynomial"] = lambda kw: ts.models.Polynomial(
    1, **kw
)


def _configured(qual: str):
    """An object of the class ``qual``'s set_params belongs to (the saved kinds' table, a
    plant on a route), or a Backlash for a base class (the method is the same)."""
    from _saved_file_table import saved_kinds

    ms, coupled, cs = saved_kinds()
    route = ts.Route.uniform(1.0, np.pi)
    built = {type(o).__name__: o for o in [*ms.values(), coupled, *cs.values()]}
    built.update(
        PullPullPlant=ts.PullPullPlant(route, elements=10),
        SingleTendonPlant=ts.SingleTendonPlant(route, elements=10),
        ContinuumPlant=ts.ContinuumPlant(elements=10),
        CoupledPlant=ts.CoupledPlant([ts.PullPullPlant(route, elements=10)], [[0.0]]),
        Motor=ts.Motor.position(20.0),
        Sensor=ts.Sensor(),
    )
    return built.get(qual.split(".")[-2], ts.models.Backlash())


# set_params (tendonsheath._util.pyobject.PythonObject's, inherited by every model, plant and
# compensator): called on an object of its class
MINIMAL_CALLS.update(
    {
        qual: (lambda kw, qual=qual: _configured(qual).set_params(**kw))
        for qual, (_, obj) in CALLABLES.items()
        if qual.endswith(".set_params") and obj is ts.models.Backlash.set_params
    }
)


def _takes_kwargs(obj) -> bool:
    # the code object, not inspect.signature: a __signature__ that spells out the settings
    # (ts.identify) can hide the **options the body validates
    code = getattr(inspect.unwrap(getattr(obj, "__init__", obj) if inspect.isclass(obj) else obj),
                   "__code__", None)  # fmt: skip
    if code is not None and code.co_flags & inspect.CO_VARKEYWORDS:
        return True
    try:
        sig = inspect.signature(obj)
    except (TypeError, ValueError):
        return False
    return any(p.kind == p.VAR_KEYWORD for p in sig.parameters.values())


def _call_with_bogus(qual, obj):
    """Call with only the unknown keyword: binding fails before the body runs."""
    if not inspect.isclass(obj) and _raw_params(obj)[:1] in (["self"], ["cls"]):
        return obj(None, **{BOGUS: 1})
    return obj(**{BOGUS: 1})


@pytest.mark.parametrize("qual", sorted(CALLABLES))
def test_unknown_keyword_is_a_type_error(qual):
    if qual in NOT_APPLICABLE["keywords"]:
        return
    obj = CALLABLES[qual][1]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with pytest.raises(TypeError, match=REJECTED):
            if _takes_kwargs(obj):
                assert qual in MINIMAL_CALLS, f"{qual} takes **kwargs: add its minimal call"
                MINIMAL_CALLS[qual]({BOGUS: 1})
            else:
                _call_with_bogus(qual, obj)


def test_the_protocols_left_out_of_the_keyword_check_cannot_be_instantiated():
    # NOT_APPLICABLE lists them: it must not hide a class that a call could build
    listed = [q for q in NOT_APPLICABLE["keywords"] if q.startswith("tendonsheath.protocols.")]
    protocols = sorted(q for q, (_, obj) in PUBLIC.items() if _is_protocol(obj))
    assert sorted(listed) == protocols and len(protocols) == 6
    for qual in protocols:
        with pytest.raises(TypeError, match="Protocols cannot be instantiated"):
            PUBLIC[qual][1]()


@pytest.mark.parametrize("qual", sorted(CALLABLES))
def test_no_parameter_has_a_deprecated_name(qual):
    obj = CALLABLES[qual][1]
    try:
        names = [n.lstrip("*") for n in _signature_params(obj)]
    except (TypeError, ValueError):
        names = []
    old = {n: _deprecated_in(qual, n) for n in names if _deprecated_in(qual, n)}
    assert not old, f"{qual}: deprecated parameter name(s), use " + ", ".join(
        f"{new!r} for {name!r}" for name, new in old.items()
    )


def _deprecated_keyword_calls(source: str, filename: str) -> list[str]:
    """Calls in ``source`` that pass a deprecated keyword to a Python callable (the C++
    structs of ``_core`` keep their own names: they are left out)."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Call):
            continue
        callee = ast.unparse(node.func)
        if callee.split(".")[0] in ("core", "_core"):
            continue
        for kw in node.keywords:
            if kw.arg and _deprecated_in(callee, kw.arg):
                found.append(f"{filename}:{node.lineno}: {callee}({kw.arg}=...)")
    return found


def test_no_deprecated_keyword_is_used_inside_the_package():
    package = Path(ts.__file__).parent
    found = []
    for path in sorted(package.rglob("*.py")):
        found += _deprecated_keyword_calls(path.read_text(), str(path.relative_to(package)))
    assert not found, "deprecated keyword(s) used inside the package:\n" + "\n".join(found)


def test_the_deprecated_keyword_scan_can_fail():
    source = (
        "Route.uniform(1.0, total_angle=2.0)\nmodels.BoucWen(a=0.3)\ncore.X(v_eps=1)\nf(a=1)\n"
        "CurveAngleModel(load=1.0, spring=2.0)\nPullPullPlant(route, load=spring)\n"
    )
    found = _deprecated_keyword_calls(source, "x.py")
    assert found == [
        "x.py:1: Route.uniform(total_angle=...)",
        "x.py:2: models.BoucWen(a=...)",
        "x.py:5: CurveAngleModel(load=...)",
        "x.py:5: CurveAngleModel(spring=...)",
    ]


def test_the_walk_reads_nanobind_signatures():
    # a name bound from C++ (nanobind) is walked like a Python one
    from tendonsheath import _core

    assert _signature_params(_core.shape_integrals) == ["s", "theta", "friction"]
    assert _what_it_gives(_core.shape_integrals) == "Returns"
    assert _signature_params(_core.Route) == ["s", "theta"]
    assert _signature_params(_core.Route.angle_at) == ["s"]
    with pytest.raises(TypeError, match=REJECTED):
        _call_with_bogus("shape_integrals", _core.shape_integrals)


# Modules whose public signatures are not annotated yet: the annotation check does not walk
# them. Remove a module from here once its signatures are annotated.
ANNOTATIONS_NOT_YET_WRITTEN: set[str] = set()


def _annotation_problems(obj) -> list[str]:
    """The parameters of a public callable that have no annotation, and a missing return
    annotation (a class: its constructor's parameters). nanobind writes every type into its
    signatures (and ``_core.pyi``), so those are annotated by construction."""
    if isinstance(obj, property):
        obj = obj.fget
    if _nanobind_signature(obj) is not None:
        return []
    is_class = inspect.isclass(obj)
    if is_class:
        obj = obj.__init__
        if not getattr(obj, "__module__", "").startswith("tendonsheath"):
            return []  # the constructor of a base outside the package (object, Enum, ...)
    sig = inspect.signature(obj)
    params = list(sig.parameters.values())
    if params and params[0].name in ("self", "cls"):
        params = params[1:]
    problems = [
        f"parameter {p.name!r} has no annotation" for p in params if p.annotation is p.empty
    ]
    if not is_class and sig.return_annotation is sig.empty:
        problems.append("no return annotation")
    return problems


@pytest.mark.parametrize(
    "qual",
    sorted(q for q, (m, _) in PUBLIC.items() if m not in ANNOTATIONS_NOT_YET_WRITTEN),
)
def test_public_signature_is_annotated(qual):
    problems = _annotation_problems(PUBLIC[qual][1])
    assert not problems, f"{qual}: " + "; ".join(problems)


def test_the_annotation_check_can_fail():
    def bare(x, y: int = 1):
        return x

    class Holder:
        def __init__(self, x):
            self.x = x

        @property
        def value(self):
            return self.x

    def typed(x: float, *rest: float, **options: object) -> float:
        return x

    Holder.__init__.__module__ = "tendonsheath.fake"  # as if defined in the package
    assert _annotation_problems(bare) == ["parameter 'x' has no annotation", "no return annotation"]
    assert _annotation_problems(Holder) == ["parameter 'x' has no annotation"]
    assert _annotation_problems(Holder.value) == ["no return annotation"]
    assert _annotation_problems(typed) == []
