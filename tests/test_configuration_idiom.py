"""One configuration idiom (issue 37, item 3) and plain control flow (item 4): models, plants
and compensators give ``get_params()``/``set_params(**)`` read from their constructor's
signature, and no class of the package rewrites its subclasses at creation."""

from __future__ import annotations

import ast
import inspect
import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest
from _saved_file_table import saved_kinds

import tendonsheath as ts
from tendonsheath.protocols import StreamingCompensator, bench_declarations

PACKAGE = Path(ts.__file__).resolve().parent


def _objects() -> dict:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ms, coupled, cs = saved_kinds()
        route = ts.Route.uniform(1.0, np.pi)
        plants = {
            "PullPullPlant": ts.PullPullPlant(route, elements=20, friction=0.12),
            "SingleTendonPlant": ts.SingleTendonPlant(route, elements=20),
            "ContinuumPlant": ts.ContinuumPlant(elements=20, pretension=12.0),
            "CoupledPlant": ts.CoupledPlant([ts.PullPullPlant(route, elements=20)], [[0.0]]),
            "Motor": ts.Motor.position(20.0),
            "Sensor": ts.Sensor(noise_std=1e-3, seed=3),
        }
    return {**ms, "Coupled": coupled, **cs, **plants}


OBJECTS = _objects()


def _same(a, b) -> bool:
    """Equal configuration: the same saved file, or (no file) the same pickle."""
    if hasattr(a, "to_dict"):
        return a.to_dict() == b.to_dict()
    return pickle.dumps(a) == pickle.dumps(b)


@pytest.mark.parametrize("name", sorted(OBJECTS))
def test_get_params_rebuilds_an_equal_object_by_the_signature(name):
    obj = OBJECTS[name]
    params = obj.get_params()
    signature = inspect.signature(type(obj).__init__).parameters
    takes_more = any(p.kind is p.VAR_KEYWORD for p in signature.values())
    assert params and (takes_more or set(params) <= set(signature))
    assert _same(type(obj)(**params), obj)


def test_set_params_changes_one_argument_in_a_new_object():
    for name, key, value in (
        ("Backlash", "B_r", 0.07),
        ("InverseFeedforward", "smoothing", 0.09),
        ("PullPullPlant", "friction", 0.2),
        ("Scaled", "output_gain", 2.0),
    ):
        obj = OBJECTS[name]
        before = obj.get_params()
        changed = obj.set_params(**{key: value})
        assert type(changed) is type(obj) and changed.get_params()[key] == value
        assert obj.get_params()[key] == before[key]  # this one is left as it was
        others = {k: v for k, v in changed.get_params().items() if k != key}
        assert _same(type(obj)(**{**others, key: before[key]}), obj)


def test_set_params_names_an_argument_the_constructor_does_not_take():
    with pytest.raises(TypeError, match="no_such_setting"):
        OBJECTS["PullPullPlant"].set_params(no_such_setting=1.0)
    with pytest.raises(TypeError, match="no_such_setting"):
        OBJECTS["EncoderLoop"].set_params(no_such_setting=1.0)


def test_the_set_params_check_can_fail():
    # a changed value reaches the constructor, which validates it as at construction
    with pytest.raises(ValueError, match="elements"):
        OBJECTS["PullPullPlant"].set_params(elements=1)


def test_no_class_of_the_package_rewrites_its_subclasses():
    hooks = []
    for path in sorted(PACKAGE.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef) and node.name == "__init_subclass__":
                hooks.append(f"{path.relative_to(PACKAGE)}:{node.lineno}")
    assert hooks == []


class _Stage:
    """A Python compensator that declares a second outer loop around itself: refused."""

    def __init__(self, inner):
        self.inner = inner

    def reset(self):
        self.inner.reset()

    def step(self, y_d, dt):
        return self.inner.step(y_d, dt)

    def bench_stage(self):
        return OBJECTS["EncoderLoop"].bench_stage()[0], self.inner


def test_the_bench_reads_the_declarations_of_its_protocol():
    class Bare:
        def reset(self):
            pass

        def step(self, y_d, dt):
            return y_d

    bare = bench_declarations(Bare())
    assert isinstance(Bare(), StreamingCompensator)
    assert (bare.step_inputs, bare.control_output, bare.engine, bare.stage) == (
        ("y_d",),
        "x",
        None,
        None,
    )
    loop = OBJECTS["EncoderLoop"]
    declared = bench_declarations(loop)
    assert declared.engine is None and declared.stage[1] is loop.feedforward
    assert bench_declarations(loop.feedforward).engine is loop.feedforward
    t = np.arange(0.0, 0.2, 1e-3)
    plant = ts.PullPullPlant(ts.Route.uniform(1.0, np.pi), elements=10)
    with pytest.raises(ValueError, match="second outer_loop"):
        ts.bench.run(plant, _Stage(loop), t, 0.1 * np.sin(t))
