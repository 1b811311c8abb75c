"""Every command over its bad inputs: one line "error: ..." and exit 2 (or 1 for a bug,
said so), never a traceback. A table of (command line, what the error must say); the
inputs are small files built once, and every case fails before any long work."""

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app

runner = CliRunner()
COLS = ["--input", "x", "--output", "y", "--time", "t"]

# a user compensator whose step takes the measured output but that does not say so
_NO_STEP_INPUTS = """
class Tracker:
    def reset(self):
        pass

    def step(self, y_d, y, dt):
        return y_d + 0.5 * (y_d - y)
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    """The good and bad input files of the table, by name."""
    d = tmp_path_factory.mktemp("inputs")
    t = np.arange(400) * 0.01
    x = np.sin(2 * np.pi * 0.5 * t)
    ts.io.write_csv(
        d / "data.csv", {"t": t, "x": x, "y": ts.models.Backlash(B_r=0.05).simulate(t, x)}
    )
    ts.models.Backlash(B_r=0.05).to_json(d / "model.json")
    ctrl = ts.compensate.AdaptiveController.from_model(ts.models.Backlash(1, 1, 0.03, 0.03), 1e-5)
    ctrl.to_json(d / "adaptive.json")
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash(), 0.05, (-1.0, 1.0))
    ff.to_json(d / "class.json")  # its stem is a C++ keyword
    huge = json.loads(ff.to_json())
    huge["smoothing"] = 10**400
    (d / "huge.json").write_text(json.dumps(huge))
    model = ts.models.Backlash(B_r=0.05).to_dict()
    model["params"]["B_r"] = 10**400
    (d / "huge_model.json").write_text(json.dumps(model))
    (d / "digits.json").write_text(json.dumps(ff.to_dict())[:-1] + ', "x": ' + "9" * 5000 + "}")
    (d / "tracker.py").write_text(_NO_STEP_INPUTS)
    (d / "a_file").write_text("")
    for name, text in _SCENARIOS.items():
        (d / f"{name}.toml").write_text(text)
    (d / "sweep.toml").write_text('[run]\nscenario = "do2015"\n[sweep]\nn = 0\n')
    return d


# bad scenario files for `bench`: each a value the bench cannot run with
_SCENARIOS = {
    "rate": "[reference]\nrate = 5.0\n",
    "amplitude": "[calibration]\namplitude = 0.0\n",
    "noise": "[sensor]\nnoise_std = -1e-3\n",
    "bandwidth": "[motor]\nbandwidth_hz = 0.0\n",
    "angles": "[calibration]\nangles = []\n",
    "max_torque": "[torque_motor]\nmax_torque = 0.0\n",
    "cal_duration": "[calibration]\nduration = 0.5\n",
    "shape": "[calibration]\nshape_noise = -1.0\n",
    "user": '[[compare.user]]\nfile = "tracker.py"\nclass = "Tracker"\n',
    "typo": "[plant]\nfrction = 0.1\n",
    "arcs_and_angle": "[route]\ntotal_angle = 3.0\narcs = [[0.5, 0.0], [0.5, 1.5]]\n",
}

# (command line, text the one-line error must hold); {d} is the inputs' folder
CASES = [
    # demo
    (["demo", "--scale", "0"], "--scale must be"),
    (["demo", "--scenario", "nope"], "unknown scenario"),
    (["demo", "--angle-unit", "grad"], "--angle-unit must be"),
    (["demo", "-o", "{d}/a_file"], "is a file, not a folder"),
    (["demo", "--seed", "-1"], "--seed must be in [0, 2**32)"),
    (["demo", "--workers", "0"], "--workers must be at least 1"),
    # bench
    (["bench", "{d}/missing.toml"], "scenario file not found"),
    (["bench", "{d}/rate.toml"], "[reference]: 'rate'"),
    (["bench", "{d}/amplitude.toml"], "[calibration]: duration and amplitude must be > 0"),
    (["bench", "{d}/noise.toml"], "[sensor]: noise_std must be >= 0"),
    (["bench", "{d}/bandwidth.toml"], "[motor]: Motor.position: bandwidth_hz must be > 0"),
    (["bench", "{d}/angles.toml"], "[calibration]: 'angles'"),
    (["bench", "{d}/max_torque.toml"], "[torque_motor]: Motor.torque: max_torque must be > 0"),
    (["bench", "{d}/cal_duration.toml"], "[calibration]: 'duration'"),
    (
        ["bench", "{d}/shape.toml"],
        "[calibration]: 'shape_noise' (ShapeSensing noise_std) out of range",
    ),
    (["bench", "{d}/user.toml"], "declare the class attribute step_inputs"),
    (["bench", "{d}/typo.toml"], "unknown key 'frction'"),
    (["bench", "{d}/typo.toml", "-o", "{d}/a_file"], "unknown key 'frction'"),
    # identify
    (["identify", "{d}/missing.csv", "-m", "Backlash", *COLS], "missing.csv"),
    (["identify", "{d}/data.csv", "-m", "nope", *COLS], "nope"),
    (["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "-o", "{d}/m.csv"], "give a .json name"),
    (["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--maxiter", "-1"], "maxiter"),
    (["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--warmup", "-1"], "warmup"),
    (["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--seed", "-1"], "--seed must"),
    (["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--report", "{d}/r.xyz"], ".xyz"),
    (["identify", "{d}/data.csv", "-m", "Backlash", "--input", "x", "--output", "z"], "'z'"),
    # flags that do not apply to what was asked (step 22): refused, never ignored
    (
        ["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--resamples", "50"],
        "--resamples applies to --standard-errors bootstrap",
    ),
    (
        ["identify", "{d}/data.csv", "-m", "Backlash", *COLS, "--curve-angle", "2"],
        "--curve-angle: Backlash takes no curve angle",
    ),
    (["identify", "{d}/data.csv", "-m", "lag1+lag1", *COLS], "a lag chained with a lag"),
    (["identify", "{d}/data.csv", "-m", "lag2", *COLS], "a lag alone is linear"),
    (["identify", "{d}/data.csv", "-m", "bwb+poly3+lag1", *COLS], "3 parts; at most two"),
    (["identify", "{d}/data.csv", "-m", "bwb+", *COLS], "an empty part around '+'"),
    (
        ["predict", "{d}/model.json", "{d}/data.csv", *COLS, "--curve-angle", "2"],
        "--curve-angle: the saved Backlash takes no curve angle",
    ),
    (
        ["predict", "{d}/model.json", "{d}/data.csv", *COLS, "--load", "x"],
        "--load: the saved Backlash takes no measured load",
    ),
    (["bench", "{d}/arcs_and_angle.toml"], "give arcs or total_angle, not both"),
    # predict
    (["predict", "{d}/missing.json", "{d}/data.csv", *COLS], "missing.json"),
    (["predict", "{d}/huge_model.json", "{d}/data.csv", *COLS], "huge_model.json"),
    (["predict", "{d}/digits.json", "{d}/data.csv", *COLS], "digits.json"),
    (
        ["predict", "{d}/model.json", "{d}/data.csv", *COLS, "-o", "{d}/data.csv"],
        "is the data file",
    ),
    (["predict", "{d}/model.json", "{d}/data.csv", *COLS, "-o", "{d}/p.json"], "unknown file type"),
    (["predict", "{d}/model.json", "{d}/data.csv", *COLS, "--warmup", "-1"], "--warmup"),
    # compare
    (["compare", "{d}/data.csv", *COLS, "--holdout", "2"], "--holdout must be"),
    (["compare", "{d}/data.csv", *COLS, "--objective", "speed"], "--objective must be"),
    (["compare", "{d}/data.csv", *COLS, "--range-margin", "-1"], "--range-margin"),
    (["compare", "{d}/data.csv", *COLS, "--parsimony", "-0.05"], "--parsimony must be"),
    (["compare", "{d}/data.csv", *COLS, "--models", "nope"], "nope"),
    (["compare", "{d}/missing.csv", *COLS], "missing.csv"),
    (["compare", "{d}/data.csv", *COLS, "--seed", "-3"], "--seed must be"),
    # sweep
    (["sweep", "{d}/missing.toml"], "missing.toml"),
    (["sweep", "{d}/sweep.toml", "--n", "0"], "--n must be"),
    (["sweep", "{d}/sweep.toml", "--bound", "-1"], "--bound must be"),
    (["sweep", "{d}/sweep.toml", "--seed", "-1"], "--seed must be"),
    (["sweep", "{d}/sweep.toml", "-o", "{d}/a_file"], "is a file, not a folder"),
    # export
    (["export", "{d}/adaptive.json", "--cpp", "{d}/a.hpp"], "(got AdaptiveController)"),
    (["export", "{d}/huge.json", "--cpp", "{d}/a.hpp"], "'smoothing' is too large"),
    (["export", "{d}/model.json", "--cpp", "{d}/a.hpp", "--namespace", "class"], "C++ keyword"),
    (["export", "{d}/class.json", "--cpp", "{d}/a.hpp"], "give --namespace"),
    (["export", "{d}/model.json", "--cpp", "{d}/model.json"], "unknown file type '.json'"),
    (["export", "{d}/model.json", "--cpp", "{d}/params.txt"], "use one of .h, .hh, .hpp, .hxx"),
    (["export", "{d}/model.json", "--cpp", "{d}/none/a.hpp"], "none"),
    (["export", "{d}/missing.json", "--cpp", "{d}/a.hpp"], "file not found"),
]


def _case_id(value) -> str:
    if not isinstance(value, list):
        return "-"
    text = " ".join(value).replace("{d}/", "").replace("--input x --output y --time t", "COLS")
    return text[:70]


@pytest.mark.parametrize(("args", "expected"), CASES, ids=_case_id)
def test_every_command_fails_on_bad_input_in_one_line(files, args, expected, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # a default output (model.json, pred.csv) lands here
    args = [a.replace("{d}", str(files)) for a in args]
    if args[0] in ("demo", "bench", "sweep") and "-o" not in args:
        args += ["-o", str(files / "out")]
    result = runner.invoke(app, args)
    assert result.exception is None or isinstance(result.exception, SystemExit), result.output
    assert "Traceback" not in result.output
    assert result.exit_code == 2, result.output
    lines = [ln for ln in result.output.splitlines() if ln.strip()]
    errors = [ln for ln in lines if ln.startswith("error:")]
    assert len(errors) == 1, result.output
    assert expected in errors[0], result.output


def test_an_unexpected_exception_is_one_line_said_to_be_a_bug(files, monkeypatch):
    """The last resort: no traceback, but the type and message, called a bug, exit 1."""

    def broken(*args, **kwargs):
        raise KeyError("limits")

    monkeypatch.setattr("tendonsheath.apps.export_cpp.cpp_header", broken)
    result = runner.invoke(
        app, ["export", str(files / "model.json"), "--cpp", str(files / "b.hpp")]
    )
    assert result.exit_code == 1 and "Traceback" not in result.output
    (line,) = [ln for ln in result.output.splitlines() if ln.strip()]
    assert line.startswith("error: KeyError: 'limits'") and "a bug" in line


def test_to_json_into_a_missing_folder_names_the_folder(tmp_path):
    ff = ts.compensate.InverseFeedforward(ts.models.Backlash(), 0.05, (-1.0, 1.0))
    with pytest.raises(FileNotFoundError) as err:
        ff.to_json(tmp_path / "nowhere" / "ff.json")
    assert str(tmp_path / "nowhere") in str(err.value) and ".tmp" not in str(err.value)


def test_suspicious_runs_get_a_note(files, tmp_path):
    """Validating on the training file, the same file twice: legal, and said; input and
    output one column: refused (a model would map the signal to itself)."""
    data = str(files / "data.csv")
    out = str(tmp_path / "m.json")
    args = ["identify", data, data, "-m", "Backlash", *COLS, "--validate", data]
    result = runner.invoke(app, [*args, "--maxiter", "2", "-o", out])
    assert result.exit_code == 0, result.output
    text = " ".join(result.output.split())
    assert "note: " + data + " is given twice" in text
    assert "note: validating on " + data + ", a training file" in text
    pred = ["predict", str(files / "model.json"), data, "--input", "x", "--output", "x"]
    result = runner.invoke(app, [*pred, "--time", "t", "-o", str(tmp_path / "p.csv")])
    assert result.exit_code != 0 and "Traceback" not in result.output
    said = " ".join(result.output.split())
    assert "column 'x' is named as both the input and the output" in said, said
