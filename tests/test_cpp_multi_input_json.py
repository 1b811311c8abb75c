"""LoadCompensated and CoupledFeedforward saved by Python load in C++
(tendonsheath/io/json_multi_input.hpp, run by example 12) and give Python's commands to 1e-12 over
random models, loads (with dropouts) and coupled joints; in Python the files round-trip bit for
bit and load strictly; ``export --cpp`` writes their headers, and points their models to them."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_cpp_example_12 import example  # noqa: E402,F401  (the fixture: the built example)

from tendonsheath.apps.cli import app  # noqa: E402
from tendonsheath.apps.export_cpp import cpp_header  # noqa: E402
from tendonsheath.compensate import CoupledFeedforward, LoadCompensated, load_compensator  # noqa: E402
from tendonsheath.models import (  # noqa: E402
    Backlash,
    BoucWenBacklash,
    Coupled,
    Loaded,
    PrandtlIshlinskii,
    Scaled,
)

T = np.arange(0.0, 2.0, 1e-3)  # 1 kHz
DTS = np.concatenate([[0.0], np.diff(T)])  # as example 12 computes them


def _base(rng, k):
    """One of four invertible bases (direct, Bouc-Wen, Scaled, exact PI inverses)."""
    if k % 4 == 0:
        c = rng.uniform(0.8, 1.2)
        return Backlash(c_r=c, c_l=c, B_r=rng.uniform(0.0, 0.1), B_l=rng.uniform(0.0, 0.1))
    if k % 4 == 1:
        return BoucWenBacklash(B_r=rng.uniform(0.02, 0.1), B_l=rng.uniform(0.02, 0.1), rho=12.0)
    if k % 4 == 2:
        inner = Backlash(B_r=rng.uniform(0.02, 0.1), B_l=rng.uniform(0.02, 0.1))
        return Scaled(inner, input_offset=0.1, input_scale=1.5, output_gain=-1.2)
    weights = list(rng.uniform(0.1, 1.0, 4))
    return PrandtlIshlinskii(thresholds=[0.0, 0.05, 0.1, 0.2], weights=weights)


def _load_compensated(k: int) -> LoadCompensated:
    rng = np.random.default_rng(40 + k)
    model = Loaded(
        _base(rng, k),
        gain=rng.uniform(-2.0, 2.0),
        slack=rng.uniform(0.0, 0.05),
        slack_load=rng.uniform(0.02, 0.5),
        friction=rng.uniform(0.0, 0.2),
    )
    model.base.input_range = (-0.8, 0.9) if k % 3 == 2 else None  # "identified": the base's
    return LoadCompensated(
        model,
        switch=None if k % 2 else rng.uniform(1e-3, 1e-2),
        smoothing=rng.uniform(0.01, 0.1),
        limits=(None, (-2.0, 2.0, 40.0), {"max_rate": 30.0})[k % 3],
        input_range=(-0.6, 0.7) if k % 3 == 1 else "identified",
        range_margin=rng.uniform(0.0, 0.2),
    )


def _coupled(k: int) -> CoupledFeedforward:
    rng = np.random.default_rng(60 + k)
    joints = 2 + k % 2
    models = [_base(rng, k + i) for i in range(joints)]
    for i, m in enumerate(models):
        m.input_range = (-0.5 - 0.1 * i, 0.6) if i % 2 == 0 else None
    c = rng.uniform(-0.3, 0.3, (joints, joints))
    np.fill_diagonal(c, 0.0)
    given = ({}, {"input_range": (-0.7, 0.8)}, {"input_range": None})[k % 3]
    limits = None if k % 2 else (-2.5, 2.5, 50.0)
    return CoupledFeedforward(Coupled(models, c), smoothing=0.03, limits=limits, **given)


def _desired(rng, joints: int = 1) -> np.ndarray:
    cols = [
        rng.uniform(0.3, 0.8) * np.sin(2 * np.pi * rng.uniform(0.4, 1.5) * T + rng.uniform(0, 6))
        + 0.05 * np.sin(2 * np.pi * 7.0 * T)
        for _ in range(joints)
    ]
    return np.column_stack(cols) if joints > 1 else cols[0]


def _run(example, file: Path, rows, tmp_path: Path) -> np.ndarray:  # noqa: F811
    trajectory, out = tmp_path / "trajectory.csv", tmp_path / "out.csv"
    trajectory.write_text("".join(",".join(repr(float(v)) for v in row) + "\n" for row in rows))
    run = subprocess.run([example, file, trajectory, out], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return np.loadtxt(out, delimiter=",")


@pytest.mark.parametrize("k", range(8))
def test_cpp_load_compensated_equals_python(example, tmp_path, k):  # noqa: F811
    """Random Loaded models over four bases, settings and loads (with dropouts, held): the C++
    commands are Python's to 1e-12."""
    ff = _load_compensated(k)
    ff.to_json(tmp_path / "lc.json")
    rng = np.random.default_rng(80 + k)
    y_d = _desired(rng)
    load = 0.3 * np.sin(2 * np.pi * rng.uniform(0.2, 1.0) * T + 1.0) + rng.normal(0, 0.01, T.size)
    load[rng.integers(0, T.size, 5)] = np.nan  # lost load samples: the last one is held
    cpp = _run(example, tmp_path / "lc.json", zip(T, y_d, load, strict=True), tmp_path)
    ff.reset()
    python = np.array([ff.step(a, dt, b) for a, dt, b in zip(y_d, DTS, load, strict=True)])
    assert np.ptp(python) > 0.3 and np.all(np.isfinite(python))
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


@pytest.mark.parametrize("k", range(6))
def test_cpp_coupled_feedforward_equals_python(example, tmp_path, k):  # noqa: F811
    """Random coupled joints (2 or 3, four bases), their own ranges or the file's, and a desired
    angle lost now and then (held): the C++ commands are Python's to 1e-12."""
    ff = _coupled(k)
    ff.to_json(tmp_path / "cf.json")
    rng = np.random.default_rng(90 + k)
    y_d = _desired(rng, ff.model.joints)
    y_d[rng.integers(0, T.size, 4), rng.integers(0, ff.model.joints, 4)] = np.nan
    cpp = _run(
        example, tmp_path / "cf.json", (np.r_[t, y] for t, y in zip(T, y_d, strict=True)), tmp_path
    )
    ff.reset()
    python = np.array([ff.step(y, dt) for y, dt in zip(y_d, DTS, strict=True)])
    assert cpp.shape == python.shape and np.all(np.isfinite(python))
    np.testing.assert_allclose(cpp, python, rtol=0, atol=1e-12)


@pytest.mark.parametrize("k", range(4))
def test_files_round_trip_bit_for_bit(k):
    """The file read back is the same file, and its commands the same bits."""
    rng = np.random.default_rng(100 + k)
    lc = _load_compensated(k)
    back = load_compensator(lc.to_json())
    assert type(back) is LoadCompensated and back.to_dict() == lc.to_dict()
    assert LoadCompensated.load(lc.to_dict()).to_dict() == lc.to_dict()
    y_d, load = _desired(rng), 0.2 * np.sin(3.0 * T)
    np.testing.assert_array_equal(back.command(T, y_d, load), lc.command(T, y_d, load))
    cf = _coupled(k)
    back = CoupledFeedforward.load(json.loads(cf.to_json()))
    assert back.to_dict() == cf.to_dict()
    assert ("input_range" in cf.to_dict()) == (k % 3 != 0)  # absent: each joint's own range
    y = _desired(rng, cf.model.joints)
    np.testing.assert_array_equal(back.command(T, y), cf.command(T, y))


def _lc_dict():
    return _load_compensated(0).to_dict()


def _cf_dict():
    return _coupled(0).to_dict()


@pytest.mark.parametrize(
    ("make", "change", "message"),
    [
        (_lc_dict, lambda d: d.pop("switch"), r"\['switch'\] missing"),
        (_lc_dict, lambda d: d.update(extra=1), r"unknown key\(s\) \['extra'\]"),
        (_lc_dict, lambda d: d.update(switch="0.1"), r"'switch' must be a number"),
        (_lc_dict, lambda d: d.update(switch=float("inf")), r"switch must be > 0"),
        (_lc_dict, lambda d: d.update(version=1.0), r"unsupported compensator file version 1.0"),
        (_lc_dict, lambda d: d.update(model=Backlash().to_dict()), r"must be a Loaded model"),
        (_lc_dict, lambda d: d["model"]["terms"].pop("gain"), r"\['gain'\] missing"),
        (_cf_dict, lambda d: d.pop("smoothing"), r"\['smoothing'\] missing"),
        (_cf_dict, lambda d: d["model"].update(extra=0), r"Coupled file: unknown key\(s\)"),
        (_cf_dict, lambda d: d["model"].pop("models"), r"Coupled file: key\(s\) \['models'\]"),
        (_cf_dict, lambda d: d["model"]["coupling"][0].append(True), r"rows of numbers"),
        (_cf_dict, lambda d: d.update(input_range="wide"), r"'input_range' must be"),
    ],
)
def test_strict_loading_names_the_key(make, change, message):
    data = make()
    change(data)
    with pytest.raises(ValueError, match=message):
        load_compensator(data)


def test_export_cpp_writes_these_files_and_points_their_models_to_them(tmp_path):
    """export --cpp writes a header for both compensator files (tests/test_export_cpp_multi.py
    runs them); a Loaded or Coupled model file is one line naming the compensator to save."""
    lc, cf = _load_compensated(0), _coupled(0)
    lc.to_json(tmp_path / "lc.json")
    cf.to_json(tmp_path / "cf.json")
    lc.model.to_json(tmp_path / "loaded.json")
    cf.model.to_json(tmp_path / "coupled.json")
    for name in ("lc.json", "cf.json"):
        result = CliRunner().invoke(
            app, ["export", str(tmp_path / name), "--cpp", str(tmp_path / f"{name}.hpp")]
        )
        assert result.exit_code == 0, result.output
        assert "make_compensator()" in (tmp_path / f"{name}.hpp").read_text()
    expected = {
        "loaded.json": "LoadCompensated(model).to_json",
        "coupled.json": "CoupledFeedforward(model).to_json",
    }
    for name, words in expected.items():
        with pytest.raises(ValueError, match=r"and export that file") as err:
            cpp_header(tmp_path / name)
        assert words in str(err.value) and "\n" not in str(err.value), name
        result = CliRunner().invoke(
            app, ["export", str(tmp_path / name), "--cpp", str(tmp_path / "x.hpp")]
        )
        assert result.exit_code == 2 and "Traceback" not in result.output, name
