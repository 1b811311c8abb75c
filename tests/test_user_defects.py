"""Issue 17: the defects a new user hits, replayed through the real command line (typer's
CliRunner runs the same app as the `tendonsheath` script) and the Python API. Each bad input
must end in a one-line error that names the problem (exit code != 0, no traceback), or in the
correct result. docs/user-errors.md lists the cases and their messages."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app
from tendonsheath.bench.frequency import frequency_response
from tendonsheath.compensate import (
    ContinuumFeedforward,
    CurveAngleFeedforward,
    InverseFeedforward,
)

ROOT = Path(__file__).resolve().parent.parent
SCENARIO = ROOT / "examples" / "scenarios" / "changing_route.toml"
SWEEP = ROOT / "examples" / "sweep.toml"
# a folder nobody may write in, root included (sysfs refuses new files)
READ_ONLY = Path("/sys/fs")

runner = CliRunner()


def one_line_error(args, *needles, cwd=None):
    """Run the command; it must fail with exit code 2 and one 'error:' line naming the problem."""
    result = runner.invoke(app, [str(a) for a in args])
    out = result.output
    assert result.exit_code == 2, out
    assert isinstance(result.exception, SystemExit), result.exception
    assert "Traceback" not in out
    errors = [line for line in out.splitlines() if line.startswith("error:")]
    assert len(errors) == 1, out
    for needle in needles:
        assert needle in errors[0], (needle, errors[0])
    return errors[0]


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    """run1.csv (a backlash loop), the same scaled by 1e-300 and 1e300, and a constant output."""
    folder = tmp_path_factory.mktemp("data")
    t = np.arange(0.0, 4.0, 0.01)
    x = np.sin(2 * np.pi * 0.5 * t)
    y = ts.models.Backlash(B_r=0.1, B_l=0.1).simulate(t, x)
    files = {
        "run1": (x, y),
        "tiny": (x * 1e-300, y * 1e-300),
        "huge": (x * 1e300, y * 1e300),
        "const": (x, np.ones_like(y)),
    }
    for name, (xi, yi) in files.items():
        ts.io.write_csv(folder / f"{name}.csv", {"time": t, "motor": xi, "tip": yi})
    return folder


@pytest.fixture(scope="module")
def model_file(data):
    path = data / "model.json"
    result = runner.invoke(
        app,
        ["identify", str(data / "run1.csv"), "-m", "backlash", "--input", "motor", "--output",
         "tip", "--time", "time", "--maxiter", "5", "-o", str(path)],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    return path


IDENTIFY = ["--input", "motor", "--output", "tip", "--time", "time", "--maxiter", "3"]


# -- 1. limits that are not CommandLimits -------------------------------------------------------


def _feedforwards(limits):
    return [
        InverseFeedforward(ts.models.BoucWenBacklash(), limits=limits),
        CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, limits=limits),
        ContinuumFeedforward(limits=limits, mode="published"),
    ]


def test_limits_as_tuple_or_dict_saturate_every_feedforward(rng):
    t = np.arange(0.0, 4.0, 1e-3)
    for _ in range(10):
        low, high = -rng.uniform(0.05, 0.3), rng.uniform(0.05, 0.3)
        y_d = rng.uniform(0.5, 1.5) * np.sin(2 * np.pi * rng.uniform(0.2, 1.0) * t)
        for limits in ((low, high), [low, high, 1e3], {"min": low, "max": high}):
            for ff in _feedforwards(limits):
                u = ff.command(t, y_d)
                assert u.min() >= low - 1e-12 and u.max() <= high + 1e-12, (ff, limits)
                assert u.max() > high - 1e-9  # the reference asks for more: it saturates


@pytest.mark.parametrize("limits", ["0.2", (0.2,), {"mn": 1.0}, (None, 1.0), (True, 1.0), 0.2])
def test_limits_of_any_other_form_are_a_type_error(limits):
    for make in (
        lambda: InverseFeedforward(ts.models.BoucWenBacklash(), limits=limits),
        lambda: CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0, limits=limits),
        lambda: ContinuumFeedforward(limits=limits),
    ):
        with pytest.raises(TypeError, match="limits"):
            make()


# -- 2. model JSON --------------------------------------------------------------------------------


def _corrupt(model_file, tmp_path, change):
    record = json.loads(model_file.read_text())
    change(record)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(record))
    return path


@pytest.mark.parametrize(
    "change, needle",
    [
        (lambda r: r.pop("params"), "'params' is missing"),
        (lambda r: r["params"].pop("B_r"), "['B_r'] missing"),
        (lambda r: r["params"].__setitem__("B_r", None), "'B_r' is null"),
        (lambda r: r["params"].__setitem__("B_r", True), "'B_r' must be a number"),
        (lambda r: r["params"].__setitem__("B_r", "wide"), "'B_r' must be a number"),
        (lambda r: r.__setitem__("params", [1, 2]), "'params' must be an object"),
        (lambda r: r.__setitem__("data", ["motor"]), "'data' must be an object"),
    ],
)
def test_corrupted_model_file_is_refused_naming_the_key(model_file, data, tmp_path, change, needle):
    bad = _corrupt(model_file, tmp_path, change)
    one_line_error(["predict", bad, data / "run1.csv", "-o", tmp_path / "p.csv"], needle)
    assert not (tmp_path / "p.csv").exists()


def test_every_model_class_round_trips_through_the_strict_loader():
    gpi = ts.models.GeneralizedPrandtlIshlinskii()
    chain = ts.models.Chain(ts.models.BoucWenBacklash(), ts.models.Polynomial(3))
    models = (ts.models.Backlash(), ts.models.BoucWen(), ts.models.CurveAngleModel(), gpi,
              ts.models.HystereticOscillator(), ts.models.PrandtlIshlinskii(), chain)  # fmt: skip
    for model in models:
        assert ts.load_model(model.to_json()) == model


# -- 3. a local sweep in a script without the __main__ guard -------------------------------------


def test_unguarded_local_sweep_script_says_so_in_one_line(tmp_path):
    script = tmp_path / "my_sweep.py"
    script.write_text(
        "import tendonsheath as ts\n"
        "from reference.stand_in_study import tracking_mse\n"
        "res = ts.sweep(tracking_mse, {'friction': ts.sweep.Relative(0.1, 0.3)}, n=2,"
        " engine='local', workers=2, progress=False)\n"
    )
    env = {**os.environ, "PYTHONPATH": str(ROOT / "tests")}  # the stand-in study
    done = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                          timeout=120, cwd=tmp_path, env=env)  # fmt: skip
    assert done.returncode != 0
    last = done.stderr.strip().splitlines()[-1]
    assert 'if __name__ == "__main__":' in last and "my_sweep.py" in last, done.stderr
    # the script's own short traceback, not one per worker process (it was ~190 lines)
    assert done.stderr.count("Traceback") == 1, done.stderr


# -- 5. output paths checked before the work -----------------------------------------------------


def test_output_path_errors_come_first_and_in_one_line(data, model_file, tmp_path):
    run1 = data / "run1.csv"
    a_file = tmp_path / "a_file.txt"
    a_file.write_text("x")
    cases = [
        (["identify", run1, "-m", "bwb", *IDENTIFY, "-o", READ_ONLY / "m.json"], "cannot write"),
        (["identify", run1, "-m", "bwb", *IDENTIFY, "-o", tmp_path], "is a folder"),
        (["identify", run1, "-m", "bwb", *IDENTIFY, "--report", tmp_path / "f.xyz"], "'.xyz'"),
        (["predict", model_file, run1, "-o", READ_ONLY / "p.csv"], "cannot write"),
        (["predict", model_file, run1, "-o", tmp_path], "is a folder"),
        (["compare", run1, "--input", "motor", "--output", "tip", "--report", a_file], "a file"),
        (["demo", "-o", READ_ONLY / "demo"], "cannot write"),
        (["demo", "-o", a_file], "is a file, not a folder"),
        (["bench", SCENARIO, "-o", READ_ONLY / "bench"], "cannot write"),
        (["bench", SCENARIO, "-o", a_file / "sub"], "is a file, not a folder"),
        (["sweep", SWEEP, "-o", a_file], "is a file, not a folder"),
        (["sweep", SWEEP, "-o", READ_ONLY / "sweep"], "cannot write"),
    ]
    for args, needle in cases:
        one_line_error(args, needle)
    assert not (tmp_path / "model.json").exists()


# -- 6. non-finite metrics are errors -------------------------------------------------------------


def test_data_at_absurd_scales_or_constant_is_refused(data, model_file, tmp_path):
    out = tmp_path / "m.json"
    for name, needle in (("tiny", "rescale"), ("huge", "rescale"), ("const", "constant")):
        one_line_error(["identify", data / f"{name}.csv", "-m", "Backlash", *IDENTIFY, "-o", out],
                       needle)  # fmt: skip
        assert not out.exists()
    one_line_error(["predict", model_file, data / "const.csv", "-o", tmp_path / "p.csv"],
                   "nrmse = nan is not finite")  # fmt: skip
    one_line_error(["predict", model_file, data / "huge.csv", "-o", tmp_path / "p.csv"],
                   "is not finite")  # fmt: skip
    one_line_error(["compare", data / "huge.csv", "--input", "motor", "--output", "tip",
                    "--models", "backlash"], "rescale")  # fmt: skip
    one_line_error(["compare", data / "const.csv", "--input", "motor", "--output", "tip",
                    "--models", "backlash"], "the output tip is constant")  # fmt: skip


@pytest.mark.parametrize("angle, needle", [("1e300", "<= 628.3 rad"), ("-1", ">= 0")])
def test_curve_angles_out_of_range_are_refused(data, tmp_path, angle, needle):
    args = ["identify", data / "run1.csv", "-m", "CurveAngleModel", *IDENTIFY]
    one_line_error([*args, "--curve-angle", angle, "-o", tmp_path / "m.json"], needle)


def _scenario(tmp_path, text):
    path = tmp_path / "s.toml"
    path.write_text(text)
    return path


def test_bench_scenarios_that_cannot_mean_anything(tmp_path):
    huge = _scenario(tmp_path, "[plant]\npretension = 1e300\n")
    one_line_error(["bench", huge, "-o", tmp_path / "o"], "pretension / EA must be < 0.05")
    empty = _scenario(tmp_path, "[compare]\ncompensators = []\n")
    one_line_error(["bench", empty, "-o", tmp_path / "o"], "'compensators' is empty")


# -- 7. units -------------------------------------------------------------------------------------


def test_report_tables_name_their_unit_in_the_chosen_angle_unit():
    from tendonsheath.report.units import rows_in_unit

    rows = [{"compensator": "a", "mse": 1e-4, "rmse": 0.01, "percent_error": 3.0}]
    deg = rows_in_unit(rows, "deg")[0]
    assert deg["mse [deg^2]"] == pytest.approx(1e-4 * (180 / math.pi) ** 2)
    assert deg["rmse [deg]"] == pytest.approx(math.degrees(0.01))
    assert deg["percent error [%]"] == 3.0
    rad = rows_in_unit(rows, "rad")[0]
    assert rad["mse [rad^2]"] == 1e-4 and rad["rmse [rad]"] == 0.01
    sun = rows_in_unit([{"condition": "c", "none": 0.1}], "deg", {"none": "rad"})[0]
    assert sun["none [deg]"] == pytest.approx(math.degrees(0.1))


def test_scenario_summaries_are_whole_sentences_and_sun_names_its_metric():
    from tendonsheath.bench.scenarios.common import first_paragraph
    from tendonsheath.bench.scenarios.do import do2015

    summary = first_paragraph(do2015.__doc__)
    assert summary.endswith("behind a PID servo and a yielding PD servo.")
    source = (ROOT / "python" / "tendonsheath" / "bench" / "scenarios" / "sun.py").read_text()
    assert 'table_title="RMSE of the distal angle per condition' in source


def test_cli_tables_carry_units_and_one_angle_unit(data, model_file, tmp_path):
    result = runner.invoke(
        app, ["predict", str(model_file), str(data / "run1.csv"), "-o", str(tmp_path / "p.csv")]
    )
    assert result.exit_code == 0, result.output
    assert "rmse" in result.output and "(tip units)" in result.output
    one_line_error(["demo", "--angle-unit", "grad", "-o", tmp_path / "d"], "deg or rad")


# -- 8. invalid options ---------------------------------------------------------------------------


def test_invalid_cli_options(data, model_file, tmp_path):
    run1 = data / "run1.csv"
    one_line_error(["identify", run1, "-m", "bwb", *IDENTIFY[:-1], "-1", "-o", tmp_path / "m"],
                   "maxiter must be an integer >= 0")  # fmt: skip
    one_line_error(["predict", model_file, run1, "--warmup", "-3", "-o", tmp_path / "p.csv"],
                   "--warmup must be >= 0")  # fmt: skip
    one_line_error(["predict", model_file, run1, "--warmup", "100000", "-o", tmp_path / "p.csv"],
                   "leaves none of the 400 samples")  # fmt: skip
    one_line_error(["sweep", SWEEP, "--bound", "-1", "-o", tmp_path / "s"], "--bound must be")
    bad_file = tmp_path / "sweep.toml"
    bad_file.write_text(SWEEP.read_text().replace("bound = { mse = 1e-4 }", "bound = -1.0"))
    one_line_error(["sweep", bad_file, "-o", tmp_path / "s"], "[report]", "bound must be > 0")
    from tendonsheath.sweep.result import check_bound

    with pytest.raises(ValueError, match="bound on mse must be finite"):
        check_bound({"mse": math.inf})


def _log():
    t = np.linspace(0.0, 2.0, 400)
    x = np.sin(2 * np.pi * t)
    return t, x, ts.models.Backlash().simulate(t, x)


@pytest.mark.parametrize(
    "options, needle",
    [
        ({"maxiter": -5}, "maxiter must be"),
        ({"popsize": 0}, "popsize must be"),
        ({"workers": 0}, "workers must be"),
        ({"tol": -1}, "tol must be"),
        ({"bounds": {"unknown": (0, 1)}}, "unknown parameter(s) ['unknown']"),
        ({"fixed": {"c_r": 1.0, "c_l": 1.0, "B_r": 0.1, "B_l": 0.1}}, "every parameter"),
    ],
)
def test_invalid_identify_options(options, needle):
    with pytest.raises(ValueError) as err:
        ts.identify(ts.models.Backlash, *_log(), progress=False, **options)
    assert needle in str(err.value)


def test_identify_with_a_model_instance_names_the_mistake():
    with pytest.raises(ValueError, match="takes a model class"):
        ts.identify(ts.models.Backlash(), *_log(), progress=False)


def _plant():
    return ts.PullPullPlant(route=ts.Route.uniform(1.2, math.pi), elements=20)


def test_bench_run_and_frequency_response_check_their_options():
    t = np.arange(0.0, 2.0, 1e-3)
    ref = 0.3 * np.sin(2 * np.pi * t)
    for warmup, needle in ((-1.0, "warmup must be in"), (math.nan, "warmup"), (5.0, "warmup")):
        with pytest.raises(ValueError, match=needle):
            ts.bench.run(_plant(), None, t, ref, warmup=warmup)
    with pytest.raises(ValueError, match="at least 2 samples"):
        ts.bench.run(_plant(), None, t[:1], ref[:1])
    with pytest.raises(ValueError, match="rate must be"):
        frequency_response(_plant(), None, [1.0], rate=0)
    with pytest.raises(ValueError, match="Nyquist"):
        frequency_response(_plant(), None, [1e6], rate=1000.0)
    # a valid warm-up still gives the metrics after it
    assert ts.bench.run(_plant(), None, t, ref, warmup=0.5).metrics["rmse"] > 0


def test_streaming_dt_is_checked_in_python_and_held_in_the_core():
    model = ts.models.BoucWenBacklash()
    ff = InverseFeedforward(model)
    motor = ts.Motor.position(bandwidth_hz=20.0)
    for dt in (-1e-3, math.nan, math.inf):
        for step in (model.step, ff.step, _plant().step, motor.step):
            with pytest.raises(ValueError, match="dt must be"):
                step(0.1, dt)
        assert math.isfinite(ts._core.ModelInverse.step(ff, 0.1, dt))  # real time: holds


def test_read_log_refuses_an_upsampling_typo(data):
    with pytest.raises(ValueError, match="would make .* samples from 400"):
        ts.io.read_log(data / "run1.csv", time="time", input="motor", output="tip", resample=1e7)
    ok = ts.io.read_log(data / "run1.csv", time="time", input="motor", output="tip", resample=200)
    assert ok.x.size == 799


# -- 9. demo --no-robustness ----------------------------------------------------------------------


def test_demo_no_robustness_skips_the_study(tmp_path, monkeypatch, scenario_results):
    import tendonsheath.apps.demo as demo

    def forbidden(*args, **kwargs):
        raise AssertionError("the robustness study ran")

    monkeypatch.setattr(demo, "robustness_section", forbidden)
    monkeypatch.setattr(demo, "rate_section", lambda out, **_: ("", {}, out / "rate.png"))
    monkeypatch.setattr(demo, "model_section", lambda out: ("", {}, []))
    from tendonsheath.bench import scenarios

    # the session's lau2015 result (tests/test_scenarios.py judges the scenario itself)
    monkeypatch.setitem(
        scenarios.SCENARIOS, "lau2015", lambda scale, seed, progress: scenario_results["lau2015"]
    )
    out = tmp_path / "demo"
    result = runner.invoke(
        app,
        # one worker: the sections patched above run in this process (a worker imports its own)
        ["demo", "-s", "lau2015", "--no-robustness", "--angle-unit", "rad", "--workers", "1",
         "-o", str(out)],
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    assert "robustness:" not in result.output  # the study's table
    assert "mse (rad^2)" in result.output and "rmse (rad)" in result.output
    report = (out / "report.html").read_text()
    assert "rmse [rad]" in report and "[deg" not in report


# -- smaller ones -------------------------------------------------------------------------------


def test_smaller_ones():
    with pytest.raises(ValueError, match="rising must be the 4 envelope coefficients"):
        ts.models.GeneralizedPrandtlIshlinskii(rising=(1.0,))
    ff = CurveAngleFeedforward(0.1, 1 / 5e-5, 1.0, 10.0)
    with pytest.raises(TypeError, match="set_route needs a Route"):
        ff.set_route(None)
    with pytest.raises(TypeError, match="needs a CurveAngleModel"):
        CurveAngleFeedforward.from_model(None)


# -- also -----------------------------------------------------------------------------------------


def test_identify_takes_compare_names(data, tmp_path):
    out = tmp_path / "m.json"
    result = runner.invoke(
        app, ["identify", str(data / "run1.csv"), "-m", "bwb", *IDENTIFY, "-o", str(out)]
    )
    assert result.exit_code == 0, result.output
    assert json.loads(out.read_text())["model"] in ("BoucWenBacklash", "Scaled")
    assert "Excel" in runner.invoke(app, ["identify", "--help"]).output


def test_help_shows_no_bool_type():
    for command in ([], ["demo"], ["sweep"], ["identify"], ["compare"]):
        text = runner.invoke(app, [*command, "--help"]).output
        assert "<bool>" not in text and "--help" in text


def test_command_descriptions_are_one_paragraph():
    """A docstring's source line break split sentences in --help ("compare the compensators,
    and" / "write report.html, ..."): each command's help is now one paragraph."""
    import typer.main

    group = typer.main.get_command(app)
    for name, command in group.commands.items():
        assert "\n" not in (command.help or ""), name


def test_streamed_plant_takes_its_first_command_as_rest_state(rng):
    """Documented in PullPullPlant.step and the README: the first step(q) is the rest state,
    so the output equals q; the dead zone shows only from the next move on."""
    for _ in range(10):
        plant = ts.PullPullPlant(
            route=ts.Route.uniform(1.2, rng.uniform(1.0, 6.0)),
            pretension=rng.uniform(5.0, 30.0),
            elements=20,
        )
        q = rng.uniform(-1.0, 1.0)
        assert plant.step(q) == pytest.approx(q, abs=1e-12)
        assert abs(plant.step(q + 0.05) - (q + 0.05)) > 1e-6  # now the slack takes its toll


def test_the_rate_table_follows_the_report_angle_unit(tmp_path):
    import math

    import tendonsheath.apps.demo as demo

    body_rad, numbers, _ = demo.rate_section(tmp_path, frequencies=(1.0,), angle_unit="rad")
    body_deg, _, _ = demo.rate_section(tmp_path, frequencies=(1.0,), angle_unit="deg")
    assert "[deg" not in body_rad and "width at 1 Hz [rad]" in body_rad
    assert "width at 1 Hz [deg]" in body_deg
    width = numbers["realistic"]["loop_width_rad"]["1"]
    assert f"{math.degrees(width):.3g}"[:3] in body_deg
