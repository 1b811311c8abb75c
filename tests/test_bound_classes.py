"""A shipped model, compensator or plant *is* its bound C++ class (a Python subclass of it), not
a wrapper holding an engine: the core's own functions take it as it is, and no module outside
the binding layer (the per-layer ``_bound.py``) names ``_core`` or ``_engine``."""

import io
import math
import tokenize
from pathlib import Path

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath._util.pyobject import bound_attribute, bound_base
from tendonsheath.compensate import (
    AdaptiveController,
    ContinuumFeedforward,
    CoupledFeedforward,
    CurveAngleFeedforward,
    EncoderLoop,
    InverseFeedforward,
    LearnedFeedforward,
    TipLoop,
)
from tendonsheath.models import (
    BoucWenBacklash,
    GeneralizedPrandtlIshlinskiiInverse,
    PrandtlIshlinskiiInverse,
)

PACKAGE = Path(ts.__file__).resolve().parent

# each Python class and the C++ class it is built on: every model of the core's list
# (model_list.hpp) that the core binds as a class, then the others
BUILT_ON = {
    **{getattr(ts.models, k["kind"]): k["model"] for k in core.model_kinds() if k["model"]},
    PrandtlIshlinskiiInverse: core.PrandtlIshlinskiiInverse,
    GeneralizedPrandtlIshlinskiiInverse: core.GeneralizedPrandtlIshlinskiiInverse,
    InverseFeedforward: core.ModelInverse,
    CurveAngleFeedforward: core.CurveAngleFeedforward,
    ContinuumFeedforward: core.ContinuumFeedforward,
    AdaptiveController: core.AdaptiveController,
    EncoderLoop: core.EncoderLoop,
    TipLoop: core.TipLoop,
    LearnedFeedforward: core.LearnedCorrection,
    CoupledFeedforward: core.CoupledFeedforward,
    ts.Route: core.Route,
    ts.Motor: core.Motor,
    ts.Sensor: core.Sensor,
    ts.SingleTendonPlant: core.SingleTendonPlant,
    ts.PullPullPlant: core.PullPullPlant,
    ts.ContinuumPlant: core.ContinuumPlant,
}


@pytest.mark.parametrize("cls", list(BUILT_ON), ids=lambda c: c.__name__)
def test_each_class_is_its_bound_class(cls):
    assert bound_base(cls) is BUILT_ON[cls]
    assert issubclass(cls, BUILT_ON[cls])


def test_pure_python_classes_have_no_bound_base():
    assert bound_base(ts.models.Chain) is None
    assert bound_base(ts.compensate.LoadCompensated) is None


def _named(source: str) -> list[tuple[int, str]]:
    tokens = tokenize.generate_tokens(io.StringIO(source).readline)
    return [(t.start[0], t.string) for t in tokens if t.type == tokenize.NAME and t.string in
            ("_core", "_engine")]  # fmt: skip


def test_no_module_outside_the_binding_layer_names_core_or_engine():
    modules = [m for m in sorted(PACKAGE.rglob("*.py")) if m.name != "_bound.py"]
    assert len(modules) > 100
    found = {str(m.relative_to(PACKAGE)): _named(m.read_text()) for m in modules}
    assert {k: v for k, v in found.items() if v} == {}


def test_the_scan_sees_a_wrapper_attribute():
    # the check above can fail: code naming the attribute (not a docstring mentioning it)
    assert _named("self._engine = core.Motor(p)\nx = plant._core\n") == [
        (1, "_engine"),
        (2, "_core"),
    ]
    assert _named('"""the tendonsheath._core extension"""\n') == []


def test_the_core_functions_take_the_python_objects_as_they_are():
    """A model's, a route's and a feedforward's C++ functions run on the Python object itself,
    giving what the Python method gives."""
    model = BoucWenBacklash(B_r=0.05, B_l=0.05)
    t = np.arange(0.0, 1.0, 1e-3)
    x = 0.5 * np.sin(2 * np.pi * t)
    np.testing.assert_array_equal(
        core.BoucWenBacklash.simulate(model, t, x, False), model.simulate(t, x)
    )
    ff = InverseFeedforward(model)
    commands = core.ModelInverse.command(ff, t, x, None, None, None, False)
    np.testing.assert_array_equal(commands, ff.command(t, x))
    route = ts.Route.uniform(1.0, math.pi)
    plant = ts.PullPullPlant(route, elements=20)
    # the C++ plant's own constructor takes the Python Route
    bare = core.PullPullPlant(bound_attribute(plant, "params"), route, route)
    for u in np.linspace(0.0, 0.3, 30):
        assert bare.step(u, 1e-3) == plant.step(u, 1e-3)
    # a copy made by the bound class is the bare C++ object, with the same state
    again = core.PullPullPlant(plant)
    assert type(again) is core.PullPullPlant and again.output() == plant.output()
