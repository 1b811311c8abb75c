"""The inverse of every model saved, loaded and run elsewhere (issue 23 item 5): the C++ loader's
commands equal Python's to 1e-12 for every model class, the compensator JSON round-trips bit
for bit with its new settings (files without them still load), identify records the range of
its training inputs, and the inverse runs in bench.run (following the sensed route) and as a
python-control system. On the shared tool-5 recordings, the identified PI's inverse stays in the
identified range and flags what it cannot reach there."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_cpp_example_12 import example  # noqa: E402,F401  (the fixture: the built example)
from test_inverse_every_model import T, _every_class, _reference_input  # noqa: E402

import tendonsheath as ts  # noqa: E402
from tendonsheath import Status  # noqa: E402
from tendonsheath.compensate import InverseFeedforward, load_compensator  # noqa: E402
from tendonsheath.models import AngleDependent, Backlash, HysteresisModel, load_model  # noqa: E402

DATA = Path(__file__).resolve().parents[2] / "shared" / "data" / "davinci_tool5"
TOOL5 = ("f0.10Hz_load010.csv", "f0.30Hz_load050.csv", "f0.50Hz_load100.csv")


def _curve(model, n):
    """One curve angle per sample for a route-following model (a slow change), else None."""
    if not getattr(model, "uses_curve_angle", False):
        return None
    return 1.0 + 0.5 * np.sin(2 * np.pi * 0.2 * T[:n])


def _trajectory(path: Path, y_d, theta) -> None:
    cols = [T.tolist(), y_d.tolist()] + ([] if theta is None else [theta.tolist()])
    rows = zip(*cols, strict=True)
    path.write_text("".join(",".join(repr(v) for v in row) + "\n" for row in rows))


def test_cpp_loader_commands_equal_python_for_every_class(example, tmp_path):  # noqa: F811
    """Every model class, a range and the new settings: example 12 (tendonsheath/io/json.hpp)
    gives Python's commands to 1e-12 (route-following ones with a changing curve angle)."""
    rng = np.random.default_rng(8)
    for name, model in _every_class(rng).items():
        x = _reference_input(rng, amplitude=0.5)
        ff = InverseFeedforward(
            model, smoothing=0.03, limits={"max_rate": 40.0}, input_range=(x.min(), x.max()),
            range_margin=0.05, filter_hz=25.0,
        )  # fmt: skip
        y_d = 1.2 * np.asarray(ff.model.simulate(T, x, **_kw(model)))  # partly out of reach
        theta = _curve(model, T.size)
        ff.to_json(tmp_path / "ff.json")
        _trajectory(tmp_path / "trajectory.csv", y_d, theta)
        out = tmp_path / "commands.csv"
        args = [example, tmp_path / "ff.json", tmp_path / "trajectory.csv", out]
        run = subprocess.run(args, capture_output=True, text=True)
        assert run.returncode == 0, f"{name}: {run.stderr}"
        python = ff.command(T, y_d, **({} if theta is None else {"curve_angle": theta}))
        np.testing.assert_allclose(np.loadtxt(out), python, rtol=0, atol=1e-12, err_msg=name)


def _kw(model):
    return {"curve_angle": 1.0} if getattr(model, "uses_curve_angle", False) else {}


def test_json_round_trip_is_bit_for_bit():
    """Every class: the file read back is the same file, and its commands the same bits."""
    rng = np.random.default_rng(9)
    y_d = 0.4 * np.sin(2 * np.pi * 0.7 * T)
    for name, model in _every_class(rng).items():
        ff = InverseFeedforward(model, input_range=(-0.3, 0.4), range_margin=0.2, filter_hz=12.5)
        back = load_compensator(ff.to_json())
        assert back.to_dict() == ff.to_dict(), name
        kw = _kw(model)
        np.testing.assert_array_equal(back.command(T, y_d, **kw), ff.command(T, y_d, **kw))


def test_the_new_settings_are_saved_and_old_files_still_load():
    ff = InverseFeedforward(Backlash(), input_range=(-1.0, 2.0), range_margin=0.25)
    data = json.loads(ff.to_json())
    assert data["input_range"] == [-1.0, 2.0] and data["range_margin"] == 0.25
    assert data["filter_hz"] is None
    assert ff.command_range == (-1.75, 2.75)
    old = {k: v for k, v in data.items() if k not in ("input_range", "range_margin", "filter_hz")}
    legacy = load_compensator(old)  # before the settings: the model's range (none), margin 0.1
    assert legacy.input_range is None and legacy.range_margin == 0.1 and legacy.filter_hz is None
    model = Backlash()
    model.input_range = (0.0, 1.0)
    old["model"] = model.to_dict()
    assert load_compensator(old).command_range == pytest.approx((-0.1, 1.1))
    data["input_range"] = "wide"
    with pytest.raises(ValueError, match="'input_range' must be"):
        load_compensator(data)


def test_bad_settings_are_named():
    with pytest.raises(ValueError, match="range_margin"):
        InverseFeedforward(Backlash(), range_margin=-0.1)
    with pytest.raises(ValueError, match="input_range"):
        InverseFeedforward(Backlash(), input_range=(1.0, 0.0))
    with pytest.raises(ValueError, match="input_range"):
        InverseFeedforward(Backlash(), input_range="training")
    with pytest.raises(ValueError, match="filter_hz"):
        InverseFeedforward(Backlash(), filter_hz=0.0)
    with pytest.raises(TypeError, match="unexpected keyword"):
        InverseFeedforward(Backlash(), margin=0.1)


def test_identify_records_the_training_input_range():
    """The range of every recording's inputs, on the Fit and the model, saved with the model
    (and absent from older files: None); the inverse takes it by default."""
    rng = np.random.default_rng(10)
    recs = []
    for _ in range(3):
        x = rng.uniform(0.2, 1.0) * np.sin(2 * np.pi * 0.5 * T[:600]) + rng.uniform(-0.3, 0.3)
        recs.append((T[:600], x, np.asarray(Backlash(B_r=0.05, B_l=0.05).simulate(None, x))))
    fit = ts.identify(Backlash, recordings=recs, progress=False, maxiter=5)
    lo = min(float(r[1].min()) for r in recs)
    hi = max(float(r[1].max()) for r in recs)
    assert fit.input_range == (lo, hi) and fit.model.input_range == (lo, hi)
    assert fit.to_dict()["input_range"] == [lo, hi]
    saved = fit.model.to_dict()
    assert saved["input_range"] == [lo, hi]
    assert load_model(saved).input_range == (lo, hi)
    del saved["input_range"]
    assert load_model(saved).input_range is None
    saved["input_range"] = [1.0, -1.0]
    with pytest.raises(ValueError, match="'input_range' must be"):
        HysteresisModel.from_dict(saved)
    span = hi - lo
    assert InverseFeedforward(fit.model).command_range == pytest.approx(
        (lo - 0.1 * span, hi + 0.1 * span)
    )


def test_bench_run_gives_a_route_following_inverse_the_route():
    """bench.run tells an inverse of an AngleDependent model the route (its shape at every
    change, or the sensed one with shape_sensing): the same run as streaming it by hand."""
    model = AngleDependent(
        "Backlash",
        coefficients={"c_r": [1.0], "c_l": [1.0], "B_r": [0.0, 0.08], "B_l": [0.0, 0.08]},
        laws={"B_r": "tanh", "B_l": "tanh"}, angle_friction=0.15,
    )  # fmt: skip
    ff = InverseFeedforward(model, smoothing=0.05)
    route_a, route_b = ts.Route.uniform(1.2, np.pi / 2), ts.Route.uniform(1.2, 2 * np.pi)
    plant = ts.PullPullPlant(route=route_a, friction=0.15, elements=20)
    t = np.arange(0.0, 2.0, 1e-3)
    y_d = 0.3 * np.sin(2 * np.pi * 1.0 * t)

    def routes(tk):
        return route_a if tk < 1.0 else route_b

    result = ts.bench.run(plant, ff, t, y_d, routes=routes)
    ff.reset()
    by_hand = []
    for k, tk in enumerate(t):
        if k in (0, 1000):
            ff.set_route(routes(tk))
        by_hand.append(ff.step(y_d[k], t[k] - t[k - 1] if k else 0.0))
    np.testing.assert_allclose(result.command, by_hand, rtol=0, atol=1e-15)
    sensed = ts.bench.run(plant, ff, t, y_d, routes=routes,
                          shape_sensing=ts.bench.ShapeSensing(noise_std=0.0))  # fmt: skip
    assert np.all(np.isfinite(sensed.command))
    unaware = ts.bench.run(plant, InverseFeedforward(model.at(np.pi / 2)), t, y_d, routes=routes)
    late = t >= 1.2
    assert np.abs(result.error[late]).max() < np.abs(unaware.error[late]).max()


def test_python_control_runs_the_new_inverses():
    """to_control (python-control) of an inverse: a Hammerstein chain, a route-following one
    (its curve angle an input) and a plant's give the commands of streaming it."""
    import control

    rng = np.random.default_rng(11)
    models = _every_class(rng)
    t = T[:300]
    y_d = 0.3 * np.sin(2 * np.pi * 1.0 * t)
    for name in ("BoucWenBacklash+lag2", "AngleDependent(Backlash)", "PlantModel"):
        ff = InverseFeedforward(models[name])
        sys_ = ff.to_control(1e-3)
        theta = np.full(t.size, 1.3)
        u = y_d if not ff.follows_route else np.vstack([y_d, theta])
        out = control.input_output_response(sys_, t, u, 0).outputs
        kw = {"curve_angle": 1.3} if ff.follows_route else {}
        streamed = [ff.step(y, 1e-3 if k else 0.0, **kw) for k, y in enumerate(y_d)]
        np.testing.assert_array_equal(np.ravel(out), streamed)


def _tool5_logs():
    if not DATA.is_dir():
        pytest.fail(f"the shared tool-5 recordings are not at {DATA} (../shared/data)")
    return [ts.io.read_log(DATA / f, time="t", input="motor", output="jaw") for f in TOOL5]


def test_tool5_pi_inverse_stays_in_the_identified_range():
    """The shared tool-5 case: identify returns a Scaled PI whose weights' sum is about 1e-9
    (a negative weight): its unbounded inverse commanded about 1e8 rad for a 1 rad jaw
    trajectory with every flag 0. With the identified range it stays within 10 % of the span
    beyond the training inputs and flags every cycle it could not reach."""
    logs = _tool5_logs()
    fit = ts.identify(ts.models.PrandtlIshlinskii, recordings=[(g.t, g.x, g.y) for g in logs],
                      seed=0, progress=False)  # fmt: skip
    lo, hi = fit.input_range
    assert (lo, hi) == (min(g.x.min() for g in logs), max(g.x.max() for g in logs))
    ff = InverseFeedforward(fit.model)
    c_lo, c_hi = ff.command_range
    for g in logs:
        u = ff.command(g.t, g.y)
        flags = u.status
        assert np.all((u >= c_lo) & (u <= c_hi))
        held = (flags & Status.OUT_OF_RANGE) != 0
        reached = np.abs(np.asarray(fit.model.simulate(g.t, u)) - g.y) < 1e-9
        assert np.all(held | reached)  # every cycle reached its target or says it did not
        assert held.any()
    u_free = InverseFeedforward(fit.model, input_range=None).command(logs[0].t, logs[0].y)
    flags_free = u_free.status
    assert np.max(np.abs(u_free)) > 1e6 and not np.any(flags_free)  # the case it fixes


def test_export_cpp_refuses_the_new_inverses_in_one_line(tmp_path):
    """export --cpp writes the D.2 and exact PI inverses (with their range as two constants);
    any other inverse is refused with a one-line reason pointing at the JSON loader."""
    from typer.testing import CliRunner

    from tendonsheath.apps.cli import app

    gpi = ts.models.GeneralizedPrandtlIshlinskii()
    InverseFeedforward(gpi).to_json(tmp_path / "gpi.json")
    result = CliRunner().invoke(app, ["export", str(tmp_path / "gpi.json"), "--cpp", "x.hpp"])
    assert result.exit_code != 0
    assert "GeneralizedPrandtlIshlinskii" in result.output and "io/json.hpp" in result.output
    model = Backlash()
    model.input_range = (-1.0, 1.0)
    InverseFeedforward(model, range_margin=0.5).to_json(tmp_path / "b.json")
    out = tmp_path / "b.hpp"
    result = CliRunner().invoke(app, ["export", str(tmp_path / "b.json"), "--cpp", str(out)])
    assert result.exit_code == 0, result.output
    text = out.read_text()
    assert "input_min = -2.0;" in text and "input_max = 2.0;" in text
