"""docs/contributing.md's "Adding a compensator", followed with its worked example
(``DeadBandInverse``, the dead-zone inverse): (a) the compensator is named in no source file
(include/, src/, python/) but the ones the section lists, at most four; (b) with only those, it
runs in bench.run's C++ closed loop, saves and loads (Python; the C++ loader reads the same file
in tests/cpp/test_io_json.cpp), and inverts a dead zone to its closed form."""

from __future__ import annotations

import json
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import tendonsheath as ts
from tendonsheath import _core as core
from tendonsheath.compensate import DeadBandInverse

ROOT = Path(__file__).resolve().parents[1]
NAME = "DeadBandInverse"
SOURCE_DIRS = ("include", "src", "python")


def _section() -> str:
    text = (ROOT / "docs" / "contributing.md").read_text(encoding="utf-8")
    start = text.index("## Adding a compensator\n")
    end = text.find("\n## ", start + 1)
    return text[start : end if end > 0 else len(text)]


def _listed_files() -> set[str]:
    """The files the section's numbered steps name (their bold-lead paths in backticks)."""
    steps = re.findall(r"^\d+\. \*\*[^*]+\*\*,? ?`([^`]+)`", _section(), flags=re.M)
    return set(steps)


def _source_files() -> list[str]:
    """The source files of the checkout (tracked or new, not ignored), less the extension's
    stub (``_core.pyi``, written by the build)."""
    out = subprocess.run(
        ["git", "ls-files", "--cached", "--others", "--exclude-standard", *SOURCE_DIRS],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
    ).stdout.split()
    return [f for f in out if (ROOT / f).is_file() and not f.endswith("_core.pyi")]


def test_the_section_lists_at_most_four_files():
    listed = _listed_files()
    assert listed == {
        "include/tendonsheath/compensators/dead_band_inverse.hpp",
        "include/tendonsheath/compensators/compensator_list.hpp",
        "python/tendonsheath/compensate/dead_band_inverse.py",
        "python/tendonsheath/compensate/__init__.py",
    }
    assert len(listed) <= 4


def test_the_compensator_is_named_only_in_the_listed_files():
    listed = _listed_files()
    naming = {
        f
        for f in _source_files()
        if NAME in (ROOT / f).read_text(encoding="utf-8", errors="replace")
    }
    outside = naming - listed
    assert not outside, f"{NAME} had to be named outside the section's files: {sorted(outside)}"
    assert naming == listed  # each step's file does name it


def test_the_check_can_fail():
    """A file naming it beyond the list is seen (the walk is not vacuous)."""
    assert "python/tendonsheath/compensate/dead_band_inverse.py" in _source_files()
    assert "python/tendonsheath/compensate/base.py" not in _listed_files()


# -- (b) it runs where the section says it does ---------------------------------------------


class DeadZone:
    """The plant the compensator inverts: y = c_r (u - d_r) for u > d_r, 0 in [-d_l, d_r],
    c_l (u + d_l) for u < -d_l (a static map, reset() and step(command, dt) only)."""

    def __init__(self, c_r: float, c_l: float, d_r: float, d_l: float) -> None:
        self.c_r, self.c_l, self.d_r, self.d_l = c_r, c_l, d_r, d_l

    def reset(self) -> None:
        pass

    def step(self, u: float, dt: float) -> float:
        if u > self.d_r:
            return self.c_r * (u - self.d_r)
        if u < -self.d_l:
            return self.c_l * (u + self.d_l)
        return 0.0


def _random_cases(n: int):
    rng = np.random.default_rng(21)
    for _ in range(n):
        c_r, c_l = rng.uniform(0.2, 5.0, 2)
        d_r, d_l = rng.uniform(0.0, 0.5, 2)
        eps = rng.choice([0.0, rng.uniform(1e-3, 0.2)])
        yield float(c_r), float(c_l), float(d_r), float(d_l), float(eps)


def test_it_is_listed_bound_and_reexported_from_the_list():
    assert NAME in core.compensator_kinds()
    from tendonsheath.compensate import _bound

    assert _bound.DeadBandInverse is core.DeadBandInverse
    assert _bound.DeadBandInverseParams is core.DeadBandInverseParams
    assert [r["name"] for r in core.DeadBandInverseParams.fields()] == [
        "c_r",
        "c_l",
        "d_r",
        "d_l",
        "eps",
    ]


def test_bench_run_takes_it_at_cpp_speed():
    """The loop steps the bound C++ object: a subclass whose Python step raises runs, and gives
    what a pure-Python wrapper of the same compensator gives through the Python loop."""

    class NeverFromPython(DeadBandInverse):
        def step(self, y_d, dt):  # bench.run's C++ loop never calls it
            raise AssertionError("bench.run stepped the compensator from Python")

    class PythonWrapper:  # no C++ core: bench.run steps it from Python
        def __init__(self, inner):
            self.inner = inner

        def reset(self):
            self.inner.reset()

        def step(self, y_d, dt):
            return self.inner.step(y_d, dt)

    t = np.arange(0.0, 0.2, 1e-3)
    y_d = 0.3 * np.sin(2 * np.pi * 7 * t)
    for c_r, c_l, d_r, d_l, eps in _random_cases(4):
        settings = {"c_r": c_r, "c_l": c_l, "d_r": d_r, "d_l": d_l, "eps": eps}
        plant = DeadZone(c_r, c_l, d_r, d_l)
        fast = ts.bench.run(plant, NeverFromPython(**settings), t, y_d)
        slow = ts.bench.run(plant, PythonWrapper(DeadBandInverse(**settings)), t, y_d)
        np.testing.assert_array_equal(fast.command, slow.command)
        np.testing.assert_array_equal(fast.output, slow.output)


def test_it_inverts_a_dead_zone_to_its_closed_form():
    t = np.arange(0.0, 0.5, 1e-3)
    rng = np.random.default_rng(37)
    for c_r, c_l, d_r, d_l, eps in _random_cases(20):
        y_d = rng.uniform(-1.0, 1.0) * np.sin(2 * np.pi * rng.uniform(1, 10) * t)
        comp = DeadBandInverse(c_r=c_r, c_l=c_l, d_r=d_r, d_l=d_l, eps=eps)
        result = ts.bench.run(DeadZone(c_r, c_l, d_r, d_l), comp, t, y_d)
        outside = np.abs(y_d) >= eps
        # exact but for rounding outside the smoothing width: c (y/c + d - d) = y
        np.testing.assert_allclose(result.output[outside], y_d[outside], rtol=0, atol=1e-12)
        middle = 0.5 * (d_r - d_l)
        u = np.where(y_d > 0, y_d / c_r + d_r, np.where(y_d < 0, y_d / c_l - d_l, middle))
        np.testing.assert_allclose(result.command[outside], u[outside], rtol=0, atol=1e-12)
        inside = ~outside
        if inside.any():  # the line joining the branches: same sign, no larger than desired
            out, want = result.output[inside], y_d[inside]
            assert np.all(np.abs(out) <= np.abs(want) + 1e-12)
            assert np.all(out * want >= -1e-15)
        # the whole trajectory in C++ equals the loop's commands
        np.testing.assert_array_equal(comp.command(t, y_d), result.command)


def test_it_saves_and_loads():
    comp = DeadBandInverse(c_r=2.0, c_l=0.5, d_r=0.1, d_l=0.2, eps=0.01)
    data = json.loads(comp.to_json())
    # the file the C++ loader reads (tests/cpp/test_io_json.cpp: DeadBandInverseFromItsTable)
    assert data == {
        "format": "tendonsheath.compensator",
        "version": 1,
        "compensator": NAME,
        "c_r": 2.0,
        "c_l": 0.5,
        "d_r": 0.1,
        "d_l": 0.2,
        "eps": 0.01,
    }
    back = ts.compensate.load(comp.to_json())
    assert type(back) is DeadBandInverse and back.params == comp.params
    t = np.linspace(0.0, 1.0, 200)
    y_d = np.sin(6 * t)
    np.testing.assert_array_equal(back.command(t, y_d), comp.command(t, y_d))
    with pytest.raises(ValueError, match="DeadBandInverse file: key\\(s\\) \\['eps'\\] missing"):
        ts.compensate.load({k: v for k, v in data.items() if k != "eps"})


def test_bad_parameters_and_input_are_named():
    with pytest.raises(ValueError, match="^DeadBandInverse: c_r must be > 0"):
        DeadBandInverse(c_r=0.0)
    with pytest.raises(ValueError, match="^DeadBandInverse: d_l must be >= 0"):
        DeadBandInverse(d_l=-0.1)
    with pytest.raises(TypeError, match="^DeadBandInverse: eps must be a number"):
        DeadBandInverse(eps="wide")
    comp = DeadBandInverse(c_r=2.0, d_r=0.1)
    u = comp.step(0.4, 1e-3)
    assert comp.step(float("nan"), 1e-3) == u  # held, and said
    assert comp.status() == ts.Status.HELD_NONFINITE_INPUT
