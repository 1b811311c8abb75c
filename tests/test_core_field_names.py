"""One vocabulary across the language boundary (docs/vocabulary.md, issue 26): every field of a
C++ parameter struct bound in ``tendonsheath._core`` is named as the Python argument that sets
it, so nothing translates the core's names or messages on the way to a Python user. A field that
no Python argument sets is listed below with the reason; a new struct or field must be one or
the other, so a translation table cannot come back unseen."""

from __future__ import annotations

import inspect
from pathlib import Path

import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath._util import args as _args
from tendonsheath.compensate import (
    AdaptiveController,
    ContinuumFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    LearnedFeedforward,
    TipLoop,
)
from tendonsheath.compensate.adaptive_controller import _GAINS

m = ts.models
ROOT = Path(__file__).resolve().parents[1]

# struct -> the Python callables whose arguments (a model's parameters and options) set its
# fields: every model of the core's list (model_list.hpp) by its kind, then the others
PYTHON_OF = {
    **{k["params"].__name__: (getattr(m, k["kind"]),) for k in core.model_kinds()},
    "LagInverseParams": (m.FirstOrderLag, m.SecondOrderLag, InverseFeedforward),
    # the inverse of a Backlash model: its parameters and the feedforward's settings
    "BacklashInverseParams": (m.Backlash, InverseFeedforward),
    "CurveAngleFeedforwardParams": (CurveAngleFeedforward,),
    "ContinuumFeedforwardParams": (ContinuumFeedforward,),
    "AdaptiveControllerParams": (AdaptiveController,),
    "EncoderLoopParams": (EncoderLoop,),
    "TipLoopParams": (TipLoop,),
    "LearnedFeedforwardParams": (LearnedFeedforward,),
    "SingleTendonParams": (ts.SingleTendonPlant,),
    "PullPullParams": (ts.PullPullPlant,),
    "ContinuumParams": (ts.ContinuumPlant,),
    "MotorParams": (ts.Motor.position, ts.Motor.torque),
    "SensorParams": (ts.Sensor,),
}
# the compensators of the core's list bound from their tables (compensator_list.hpp): the
# struct "<kind>Params" set by the Python class of the same name (docs/contributing.md)
PYTHON_OF.update(
    {
        kind + "Params": (getattr(ts.compensate, kind),)
        for kind in core.compensator_kinds()
        if hasattr(core, kind + "Params") and hasattr(ts.compensate, kind)
    }
)

# struct -> {field: why no Python argument of that name sets it}
INTERNAL = {
    "LagInverseParams": {"order": "which lag model: FirstOrderLag (1) or SecondOrderLag (2)"},
    "AdaptiveControllerParams": {
        "has_feedforward": "set when a feedforward_model is given",
        "feedforward": "the BacklashInverseParams of the feedforward_model",
    },
    "SingleTendonParams": {
        "elements": "the route's discretisation (Python: elements=, checked first)",
        "load_force": "from the load object (load=LinearSpring(...))",
        "load_stiffness": "from the load object (load=LinearSpring(...))",
        "options": "ChainOptions from max_increment= and fast_path=",
    },
    "PullPullParams": {
        "load_torque": "from the load object (load=SpringDamper(...))",
        "load_stiffness": "from the load object (load=SpringDamper(...))",
        "load_damping": "from the load object (load=SpringDamper(...))",
        "options": "ChainOptions from max_increment= and fast_path=",
    },
    "ContinuumParams": {"options": "ChainOptions from max_increment= and fast_path="},
    "MotorParams": {
        "kind": "Motor.position or Motor.torque",
        "max_substeps": "the work bound of one step (C++ only)",
    },
    "TipLoopParams": {
        "schedule_angles": "read-only: the schedule= rows' curve angles",
        "schedule_gains": "read-only: the schedule= rows' gains",
    },
}

# the C++ field names that once differed from Python's (docs/vocabulary.md); none may come back
OLD_CPP_NAMES = {
    "v_eps",
    "total_angle",
    "sheath_length",
    "reflected_inertia",
    "compliance",
    "load",
    "spring",
    "input_reconstruction",
}


def _fields(struct: type) -> set[str]:
    """The data members bound on a nanobind struct (its properties)."""
    return {
        name
        for klass in struct.__mro__
        for name, d in vars(klass).items()
        if isinstance(d, property) and not name.startswith("_")
    }


def _arguments(target) -> set[str]:
    """The argument names of a Python constructor or factory: a model's parameters and options
    else its signature's names."""
    if isinstance(target, type) and issubclass(target, m.HysteresisModel):
        names = set(target.param_names) | set(target.option_names)
        if target is m.GeneralizedPrandtlIshlinskii:  # the envelopes as sequences or flat
            names |= {"rising", "falling"}
        return names
    if target is AdaptiveController:
        return set(_GAINS) | set(inspect.signature(target).parameters)
    return set(inspect.signature(target).parameters)


def _params_structs() -> list[str]:
    return sorted(n for n, c in vars(core).items() if isinstance(c, type) and n.endswith("Params"))


def test_every_params_struct_of_the_core_is_checked():
    assert _params_structs() == sorted(PYTHON_OF)


@pytest.mark.parametrize("struct", sorted(PYTHON_OF))
def test_every_field_is_named_as_the_python_argument_that_sets_it(struct):
    fields = _fields(getattr(core, struct))
    assert fields, struct
    internal = INTERNAL.get(struct, {})
    assert set(internal) <= fields, f"{struct}: listed as internal but not a field"
    arguments = set().union(*(_arguments(t) for t in PYTHON_OF[struct]))
    unnamed = fields - arguments - set(internal)
    assert not unnamed, f"{struct}: fields that no Python argument names: {sorted(unnamed)}"
    assert not fields & OLD_CPP_NAMES, struct


def test_the_check_sees_a_field_python_names_otherwise():
    """The walk above can fail: a struct with a C++-only name is caught."""

    class Renamed:
        smoothing = property(lambda self: 0.0)
        v_eps = property(lambda self: 0.0)

    assert _fields(Renamed) - _arguments(InverseFeedforward) == {"v_eps"}


def test_no_translation_table_is_left():
    """The run-time translation of issue 26 is gone: the core's messages speak Python."""
    for gone in ("CORE_NAMES", "python_names", "to_python_names"):
        assert not hasattr(_args, gone), gone
    assert not hasattr(m.HysteresisModel, "core_names")
    assert not hasattr(m.HysteresisModel, "_core_field")
    loader = (ROOT / "include" / "tendonsheath" / "io" / "json.hpp").read_text(encoding="utf-8")
    assert "kFileNames" not in loader and "built_with_file_names" not in loader


def test_the_core_says_the_python_name():
    """A core struct refused directly names the field by its Python name (no wrapper between)."""
    p = core.BacklashInverseParams()
    p.smoothing = 0.0
    with pytest.raises(ValueError, match=r"^BacklashInverseFeedforward: smoothing must be > 0"):
        core.BacklashInverseFeedforward(p)
    f = core.CurveAngleFeedforwardParams()
    f.curve_angle = -1.0
    with pytest.raises(ValueError, match=r"^CurveAngleFeedforward: curve_angle must be >= 0"):
        core.CurveAngleFeedforward(f)
    c = core.ContinuumFeedforwardParams()
    c.length = 0.0
    with pytest.raises(ValueError, match=r"^ContinuumFeedforward: length must be > 0"):
        core.ContinuumFeedforward(c)
    mp = core.MotorParams()
    mp.coulomb_friction = 0.1
    with pytest.raises(ValueError, match=r"act through its inertia, which must then be > 0"):
        core.Motor(mp)
    cm = core.CurveAngleParams()
    cm.load_stiffness = -1.0
    with pytest.raises(ValueError, match=r"^CurveAngleModel: load_stiffness must be >= 0"):
        core.CurveAngleModel(cm)


def test_a_shape_says_curve_angle_and_its_old_name_warns():
    """ShapeIntegrals (what compensate.shape_of returns) holds the curve angle as curve_angle;
    reading total_angle still works for one release, with a DeprecationWarning naming the new."""
    shape = core.uniform_shape(friction=0.2, curve_angle=2.5)
    assert shape.curve_angle == 2.5
    with pytest.warns(DeprecationWarning, match="'total_angle' is now called 'curve_angle'"):
        assert shape.total_angle == 2.5
    route = ts.Route.uniform(1.0, 2.5)
    assert ts.compensate.shape_of(route, 0.2).curve_angle == pytest.approx(2.5, rel=1e-12)
