"""One rule for "did you mean degrees / mm / ms?" (step 22 item 4), walked over the entry points.

An angle, a length or a time past its quantity's physical bound (``tendonsheath._util.units``) warns
a :class:`ts.UnitWarning` naming the entry point, the argument and the value converted from the
smaller unit; a plausible value says nothing. The entry points are found, not listed by hand:

- every C++ parameter table's field in rad, m or s (``fields()``' unit column) through every
  Python constructor that sets it (test_core_field_names.PYTHON_OF): a field added to a table is
  walked at once;
- every public callable whose signature takes a quantity by a name of the tables or a known one
  (curve_angle, length, delay, latency, amplitude, ...): each is either walked in ``EXTRA``
  below, or one of the kinds ``NOT_SETTINGS`` names with its reason; a new one fails the walk
  until it is one or the other.
"""

from __future__ import annotations

import inspect
import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from test_core_field_names import PYTHON_OF, _arguments

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath._util import units as _units
from tendonsheath.bench import ShapeSensing, user_scenario
from tendonsheath.compensate import InverseFeedforward, TipLoop

ROOT = Path(__file__).resolve().parents[1]
ROUTE = ts.Route.uniform(1.0, math.pi)


def _inverse():
    return InverseFeedforward(ts.models.Backlash())


# the arguments a constructor needs besides the walked field
REQUIRED = {
    ts.PullPullPlant: lambda: {"route": ROUTE},
    ts.SingleTendonPlant: lambda: {"route": ROUTE},
    ts.compensate.CurveAngleFeedforward: lambda: {
        "friction": 0.1,
        "stiffness": 2e4,
        "length": 1.0,
        "pretension": 10.0,
    },
    ts.compensate.EncoderLoop: lambda: {"feedforward": _inverse()},
    ts.compensate.TipLoop: lambda: {"feedforward": _inverse()},
    ts.compensate.LearnedFeedforward: lambda: {
        "feedforward": _inverse(),
        "table": [0.0, 0.1],
        "table_dt": 1e-3,
    },
}


def _unit_warnings(build) -> tuple[list[str], Exception | None]:
    """The UnitWarning messages build() raises, and the ValueError it ends with (if any)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            build()
            error = None
        except ValueError as exc:
            error = exc
    return [str(w.message) for w in caught if issubclass(w.category, ts.UnitWarning)], error


def _table_rows():
    """(struct, field, unit, quantity, Python target) for every table field in rad, m or s."""
    rows = []
    for struct, targets in sorted(PYTHON_OF.items()):
        for row in getattr(core, struct).fields():
            q = _units.quantity_of(row["name"], row["unit"], struct)
            if q is None:
                continue
            for target in targets:
                if row["name"] in _arguments(target):
                    rows.append((struct, row["name"], q, target))
    return rows


TABLE_ROWS = _table_rows()


def _build(target, **kw):
    return target(**{**REQUIRED.get(target, dict)(), **kw})


def test_the_table_walk_finds_the_quantities():
    """Angles, lengths and times of models, plants, the motor, the sensor and compensators."""
    fields = {(s, f) for s, f, _, _ in TABLE_ROWS}
    assert len(fields) >= 20, len(fields)  # 23 fields today
    units = {q.unit for _, _, q, _ in TABLE_ROWS}
    assert units == {"rad", "m", "s"}
    assert ("CurveAngleFeedforwardParams", "curve_angle") in fields
    assert ("SensorParams", "delay") in fields
    assert ("LagInverseParams", "time_constant") in fields  # FirstOrderLag's
    assert ("TipLoopParams", "kd") not in fields  # a gain in s, not a duration


@pytest.mark.parametrize(
    ("struct", "field", "quantity", "target"),
    TABLE_ROWS,
    ids=[f"{getattr(t, '__qualname__', t)}-{f}" for _, f, _, t in TABLE_ROWS],
)
def test_a_table_quantity_in_the_smaller_unit_warns(struct, field, quantity, target):
    """10x past the bound: a UnitWarning naming the field and the smaller unit (or the
    constructor's one-line ValueError naming it); the bound itself: nothing."""
    slipped = 10 * quantity.bound
    messages, error = _unit_warnings(lambda: _build(target, **{field: slipped}))
    if error is None:
        assert any(field in m and f"did you give {quantity.slip_name}?" in m for m in messages), (
            target,
            field,
            messages,
        )
    else:
        assert field in str(error) and "\n" not in str(error), error
    quiet, error = _unit_warnings(lambda: _build(target, **{field: 0.9 * quantity.bound}))
    assert not quiet, quiet


@settings(max_examples=200, deadline=None)
@given(row=st.sampled_from(TABLE_ROWS), factor=st.floats(0.0, 100.0))
def test_a_warning_exactly_past_the_bound(row, factor):
    """Any field, any value from 0 to 100x its bound: a warning exactly when past the bound,
    or the constructor's one-line refusal naming the field."""
    _, field, quantity, target = row
    value = factor * quantity.bound
    messages, error = _unit_warnings(lambda: _build(target, **{field: value}))
    if error is not None:
        assert field in str(error) and "\n" not in str(error), error
        return
    assert bool(messages) == (value > quantity.bound), (target, field, value, messages)


@pytest.mark.parametrize("target", sorted({t for *_, t in TABLE_ROWS}, key=str))
def test_the_defaults_are_plausible(target):
    messages, error = _unit_warnings(lambda: _build(target))
    assert error is None and not messages, (error, messages)


# -- the entry points no parameter table describes: (label, call with a value, quantity)
def _read_log_angle(tmp_path, value):
    path = tmp_path / "run.csv"
    t = np.linspace(0, 1, 20)
    np.savetxt(path, np.c_[t, np.sin(t), np.sin(t)], delimiter=",", header="t,x,y", comments="")
    return ts.io.read_log(path, time="t", input="x", output="y", curve_angle=value)


def _identify_angle(value):
    t = np.linspace(0, 2, 100)
    x = np.sin(2 * np.pi * t)
    # y = 0.5 x: the output may not be the input itself (identify refuses that)
    return ts.identify(ts.models.CurveAngleModel, t, x, 0.5 * x, curve_angle=value, maxiter=0)


def _scenario(value, where):
    tables = {
        "reference": f"[reference]\nsines = [[{value}, 0.25, 0.0]]\n",
        "calibration": f"[calibration]\namplitude = {value}\n",
    }
    return user_scenario.parse(tables[where], "s.toml")


Q = _units
EXTRA = {
    # (callable's qualified name, argument): (call(value, tmp_path), quantity)
    ("Route.uniform", "length"): (lambda v, _: ts.Route.uniform(v, 1.0), Q.LENGTH),
    ("Route.uniform", "curve_angle"): (lambda v, _: ts.Route.uniform(1.0, v), Q.CURVE_ANGLE),
    ("Route.arcs", "pieces"): (lambda v, _: ts.Route.arcs([(1.0, v)]), Q.CURVE_ANGLE),
    ("Route.arcs", "pieces (length)"): (lambda v, _: ts.Route.arcs([(v, 1.0)]), Q.LENGTH),
    ("Route", "s"): (lambda v, _: ts.Route([0.0, v], [0.0, 1.0]), Q.LENGTH),
    ("Route.from_points", "xyz"): (
        lambda v, _: ts.Route.from_points([[0, 0, 0], [v, 0, 0]]),
        Q.LENGTH,
    ),
    ("read_log", "curve_angle"): (lambda v, tmp: _read_log_angle(tmp, v), Q.CURVE_ANGLE),
    ("identify", "curve_angle"): (lambda v, _: _identify_angle(v), Q.CURVE_ANGLE),
    ("ShapeSensing", "noise_std"): (lambda v, _: ShapeSensing(noise_std=v), Q.ANGLE_NOISE),
    ("ShapeSensing", "delay"): (lambda v, _: ShapeSensing(delay=v), Q.DELAY),
    ("TipLoop", "schedule"): (
        lambda v, _: TipLoop(_inverse(), schedule=[(0.0, 1.0), (v, 1.0)]),
        Q.CURVE_ANGLE,
    ),
    ("AdaptiveController.from_model", "noise_std"): (
        lambda v, _: ts.compensate.AdaptiveController.from_model(
            ts.models.Backlash(), inertia=1e-3, viscous=0.01, noise_std=v
        ),
        Q.ANGLE_NOISE,
    ),
    ("measured_mse", "delay"): (
        lambda v, _: ts.bench.measured_mse(_FakeResult(), delay=v),
        Q.DELAY,
    ),
    ("calibrate", "amplitude"): (
        lambda v, _: ts.bench.calibration.calibration_input(2.0, v),
        Q.JOINT_ANGLE,
    ),
    ("calibrate", "duration"): (
        lambda v, _: ts.bench.calibration.calibration_input(v, 1.0, rate=1e-3),
        Q.DURATION,
    ),
    ("scenario [reference]", "sines"): (lambda v, _: _scenario(v, "reference"), Q.JOINT_ANGLE),
    ("scenario [calibration]", "amplitude"): (
        lambda v, _: _scenario(v, "calibration"),
        Q.JOINT_ANGLE,
    ),
}


class _FakeResult:
    """The four arrays measured_mse reads from a bench run."""

    t = np.linspace(0, 1, 11)
    reference = np.zeros(11)
    measured = np.zeros(11)
    scored = np.ones(11, dtype=bool)


@pytest.mark.parametrize("key", sorted(EXTRA), ids=lambda k: "-".join(k))
def test_each_other_entry_point_warns_in_the_smaller_unit(key, tmp_path):
    call, quantity = EXTRA[key]
    messages, error = _unit_warnings(lambda: call(10 * quantity.bound, tmp_path))
    assert any(f"did you give {quantity.slip_name}?" in m for m in messages), (key, messages)
    quiet, _ = _unit_warnings(lambda: call(0.5 * quantity.bound, tmp_path))
    assert not quiet, (key, quiet)


# -- the walk over signatures: which public callables take such a quantity
# the argument names that are an angle, a length or a time: every table field that is one,
# and the names the Python-only entry points use
QUANTITY_NAMES = {
    row["name"]
    for name in dir(core)
    if name.endswith("Params") and hasattr(getattr(core, name), "fields")
    for row in getattr(core, name).fields()
    if _units.quantity_of(row["name"], row["unit"]) is not None
} | {"curve_angle", "curve_angles", "length", "delay", "latency", "noise_std", "amplitude"}

# kinds of callables whose such arguments are not settings to check, each with its reason
NOT_SETTINGS = {
    r"\.(step|measure|command|set_curve_angle)$": "per-step, real-time arguments (a warning a "
    "step would flood the loop; the C++ holds its last value and flags input_clamped)",
    r"\.(simulate|predict|validate|params_at|at|backlash_half_width|load_offset|slope|"
    r"to_control)$": "per-sample arrays of a model already built (its settings were checked)",
    r"^(ServoFit|LoopDynamics|EncoderLoopDesign|LearningDesign|Log)\b": "results the library "
    "computes (an identified servo, a design, a log read), not a user's settings",
    r"(calibrate\w*|calibration_trial|loop_calibration_input|motor_calibration_input|"
    r"static_reading|static_route|PlantDraw\.\w+)$": "a run's duration or a calibration "
    "amplitude: passed to calibration_input or a Sensor, walked there",
    r"(Identifier\.fit\w*|cross_validate|compare_models|honesty_entry|in_class_fit)$": "data "
    "for identify: its curve angle goes through identify's recordings, walked as identify",
    r"frequency_response$": "an excitation amplitude in the data's units (any model's input)",
    r"ContinuumFeedforward\.from_model$": "builds a ContinuumFeedforward: walked by its table",
    r"TipLoop\.from_calibration$": "its curve_angles go to tune_tip_loop's check, the same "
    "CURVE_ANGLE as TipLoop's schedule",
    r"AdaptiveController\.from_calibration$": "noise_std goes to from_model, walked",
    r"^Motor\.(position|torque)$|^Sensor$|Plant$|^models\.\w+$|^compensate\.\w+$": "a "
    "constructor walked by its parameter table",
}
# the EXTRA rows by the callable's short name, as the walk names it
EXTRA_NAMES = {k[0] for k in EXTRA}


def _public_callables():
    """(short qualified name, callable) of the public API: each module's __all__, and the
    public methods of its classes."""
    mods = {
        "": ts,
        "models.": ts.models,
        "compensate.": ts.compensate,
        "bench.": ts.bench,
        "io.": ts.io,
        "identify.": ts.identify,
        "presets.": ts.presets,
    }
    seen, out = set(), []
    for prefix, mod in mods.items():
        for name in mod.__all__:
            obj = getattr(mod, name, None)
            if obj is None or inspect.ismodule(obj) and obj is not ts.identify or id(obj) in seen:
                continue
            seen.add(id(obj))
            out.append(
                (name if prefix in ("", "bench.", "io.", "identify.") else prefix + name, obj)
            )
            if inspect.isclass(obj):
                for attr, value in vars(obj).items():
                    f = getattr(value, "__func__", value)
                    if not attr.startswith("_") and inspect.isfunction(f):
                        out.append((f"{name}.{attr}", f))
    return out


def _walked():
    found = []
    for name, obj in _public_callables():
        try:
            params = inspect.signature(obj).parameters
        except (TypeError, ValueError):
            continue
        found += [(name, p) for p in params if p in QUANTITY_NAMES and p != "dt"]
    return found


def test_every_entry_point_taking_a_quantity_is_walked_or_says_why():
    """A public callable with an argument named as an angle, a length or a time is walked
    (EXTRA, or a constructor of a parameter table) or of a kind NOT_SETTINGS explains."""
    found = _walked()
    assert len(found) > 40, len(found)
    unexplained = [
        (name, p)
        for name, p in found
        if name not in EXTRA_NAMES and not any(re.search(k, name) for k in NOT_SETTINGS)
    ]
    assert not unexplained, f"take a quantity, neither walked nor explained: {unexplained}"


def test_the_walk_can_fail():
    def tool(length: float = 1.0) -> None: ...

    assert "length" in QUANTITY_NAMES
    assert not any(re.search(k, "bench.tool") for k in NOT_SETTINGS)


def test_the_rule_lives_in_one_place():
    """Every "did you give ..." and every UnitWarning comes from _util/units.py."""
    package = ROOT / "python" / "tendonsheath"
    for path in package.rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        if path.name == "units.py" and path.parent.name == "_util":
            continue
        assert "did you give" not in text, path
        assert "class UnitWarning" not in text, path
    assert ts.UnitWarning is _units.UnitWarning


def test_the_message_names_the_value_converted():
    with pytest.warns(ts.UnitWarning) as caught:
        ts.models.FirstOrderLag(time_constant=50)
    assert str(caught[0].message) == (
        "FirstOrderLag: time_constant 50 s is above 10 s (10 s: the drive's lags and loop "
        "times are below a second); did you give milliseconds? 50 ms = 0.05 s"
    )
    assert caught[0].filename == __file__  # the user's line, not the package's


def test_an_identified_geometry_in_normalised_units_does_not_warn():
    """The demo's identified CurveAngleModel holds radii near 1 (the data's units); the
    feedforwards built from it too: no warning. A plant's radius of 1 m does warn."""
    messages, _ = _unit_warnings(
        lambda: ts.models.CurveAngleModel(proximal_radius=1.0, distal_radius=1.00088)
    )
    assert not messages
    messages, _ = _unit_warnings(lambda: ts.PullPullPlant(ROUTE, proximal_radius=5.0))
    assert messages and "did you give millimetres? 5 mm = 0.005 m" in messages[0]
