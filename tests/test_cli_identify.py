"""`tendonsheath identify` and `tendonsheath predict` on small generated files."""

import json

import numpy as np
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.cli import app

runner = CliRunner()


def _write(path, t, x, y, **extra):
    ts.io.write_csv(path, {"time": t, "motor": x, "tip": y, **extra})


def test_identify_then_predict(tmp_path):
    truth = ts.models.BoucWenBacklash(B_r=0.1, B_l=0.08, n=5.0)
    t = np.arange(0.0, 5.0, 4e-3)
    x = np.sin(2 * np.pi * 0.4 * t)
    rng = np.random.default_rng(0)
    _write(tmp_path / "train.csv", t, x, truth.simulate(t, x) + 0.002 * rng.standard_normal(t.size))
    x2 = 0.7 * np.sin(2 * np.pi * 0.9 * t)
    _write(tmp_path / "val.csv", t, x2, truth.simulate(t, x2))
    model_path = tmp_path / "model.json"
    result = runner.invoke(
        app,
        [
            "identify",
            str(tmp_path / "train.csv"),
            "--model",
            "BoucWenBacklash",
            "--input",
            "motor",
            "--output",
            "tip",
            "--time",
            "time",
            "--validate",
            str(tmp_path / "val.csv"),
            "-o",
            str(model_path),
            "--report",
            str(tmp_path / "fit.png"),
        ],
    )
    assert result.exit_code == 0, result.output
    assert "B_r" in result.output and "validation" in result.output
    assert (tmp_path / "fit.png").stat().st_size > 10_000
    saved = json.loads(model_path.read_text())
    assert saved["validation"]["nrmse"] < 0.01
    model = ts.load_model(model_path)
    assert abs(model.params["B_r"] - 0.1) < 0.005

    result = runner.invoke(
        app, ["predict", str(model_path), str(tmp_path / "val.csv"), "-o", str(tmp_path / "p.csv")]
    )
    assert result.exit_code == 0, result.output
    assert "rmse" in result.output
    pred = np.genfromtxt(tmp_path / "p.csv", delimiter=",", names=True)
    assert np.allclose(pred["predicted"], model.simulate(t, x2), atol=1e-8)


def test_identify_curve_angle_model_with_constant_angle_value(tmp_path):
    truth = ts.models.CurveAngleModel(friction=0.1, stiffness=2e3)
    t = np.arange(0.0, 4.0, 5e-3)
    x = 0.5 * np.sin(2 * np.pi * 0.5 * t)
    _write(tmp_path / "a.csv", t, x, truth.simulate(t, x, curve_angle=np.pi))
    result = runner.invoke(
        app,
        [
            "identify",
            str(tmp_path / "a.csv"),
            "--model",
            "CurveAngleModel",
            "--input",
            "motor",
            "--output",
            "tip",
            "--curve-angle",
            "3.14159",
            "-o",
            str(tmp_path / "m.json"),
        ],
    )
    assert result.exit_code == 0, result.output
    # predict without an output column: no rmse, still writes predictions
    ts.io.write_csv(tmp_path / "only_input.csv", {"time": t, "motor": x})
    result = runner.invoke(
        app,
        [
            "predict",
            str(tmp_path / "m.json"),
            str(tmp_path / "only_input.csv"),
            "-o",
            str(tmp_path / "p.csv"),
        ],
    )
    assert result.exit_code == 0, result.output
    assert "rmse" not in result.output


def test_bad_input_exits_nonzero_with_a_reason(tmp_path):
    t = np.arange(0.0, 1.0, 0.01)
    _write(tmp_path / "c.csv", t, np.ones_like(t), np.sin(t))
    result = runner.invoke(
        app,
        [
            "identify",
            str(tmp_path / "c.csv"),
            "--model",
            "Backlash",
            "--input",
            "motor",
            "--output",
            "tip",
        ],
    )
    assert result.exit_code == 2
    assert "constant" in result.output
    result = runner.invoke(
        app,
        [
            "identify",
            str(tmp_path / "c.csv"),
            "--model",
            "Backlash",
            "--input",
            "nope",
            "--output",
            "tip",
        ],
    )
    assert result.exit_code == 2 and "unknown input column 'nope'" in result.output
    result = runner.invoke(
        app,
        [
            "identify",
            str(tmp_path / "c.csv"),
            "--model",
            "Nonsense",
            "--input",
            "motor",
            "--output",
            "tip",
        ],
    )
    assert result.exit_code == 2 and "unknown model" in result.output
