"""Step 22 (part B): whole classes of silent answers, each with its rule.

- options that do not apply to what was asked: refused by a one-line error naming the option
  (the command-line rows are in test_cli_bad_inputs.py);
- messages that mislead: a parameter set on a model, a fixed value outside its range, a
  composite model name, rows logged twice: each names what is really wrong;
- the API reads as the docs: ``ts.identify`` is the package and is callable;
- command-line warnings: one line, their category named, no file and line of the package.
"""

from __future__ import annotations

import inspect
import re

import numpy as np
import pytest
from typer.testing import CliRunner

import tendonsheath as ts
from tendonsheath.apps.cli import app
from tendonsheath.apps.compare import parse_model

m = ts.models
T = np.linspace(0, 4, 400)
X = 0.5 * np.sin(2 * np.pi * 0.5 * T)
Y = m.Backlash(B_r=0.1, B_l=0.1).simulate(T, X).output


def _error(call) -> str:
    with pytest.raises((ValueError, TypeError, AttributeError)) as info:
        call()
    text = str(info.value)
    assert "\n" not in text, text
    return text


# -- options that do not apply -------------------------------------------------------------------
OPTIONS = [
    (
        "bootstrap with linearised errors",
        lambda: ts.identify(m.Backlash, T, X, Y, bootstrap=50, progress=False),
        "bootstrap=50 applies to standard_errors='bootstrap'",
    ),
    (
        "bootstrap_block with linearised errors",
        lambda: ts.identify(m.Backlash, T, X, Y, bootstrap_block=10, progress=False),
        "bootstrap_block=10 applies to",
    ),
    (
        "a curve angle to a model that takes none",
        lambda: ts.identify(m.Backlash, T, X, Y, curve_angle=2.0, progress=False),
        "Backlash does not",
    ),
    (
        "a load to a model that takes none",
        lambda: ts.identify(m.Backlash, T, X, Y, load=np.zeros_like(T), progress=False),
        "a measured load is taken by a Loaded model",
    ),
]


@pytest.mark.parametrize(("case", "call", "says"), OPTIONS, ids=[c[0] for c in OPTIONS])
def test_an_option_that_does_not_apply_is_refused(case, call, says):
    assert says in _error(call)


def test_the_options_that_do_apply_still_work():
    fit = ts.identify(
        m.CurveAngleModel, T, X, Y, curve_angle=2.0, maxiter=2, progress=False, polish=False
    )
    assert np.isfinite(fit.rmse)
    boot = ts.identify(
        m.Backlash, T, X, Y, standard_errors="bootstrap", bootstrap=5, maxiter=2, progress=False
    )
    assert boot.uncertainty["samples"].shape[0] <= 5


# -- messages that mislead -----------------------------------------------------------------------
MESSAGES = [
    (
        "a parameter set on a model",
        lambda: setattr(m.Backlash(), "B_r", 0.2),
        "Backlash: parameter 'B_r' cannot be set on the object (it is read as "
        ".params['B_r']); with_params(B_r=...) makes a copy with the new value",
    ),
    (
        "a fixed value below its range",
        lambda: ts.identify(m.Backlash, T, X, Y, fixed={"B_r": -1.0}, progress=False),
        "fixed B_r = -1 is outside Backlash's valid range of B_r, [0, inf)",
    ),
    (
        "a fixed slope of zero",
        lambda: ts.identify(m.Backlash, T, X, Y, fixed={"c_r": 0.0}, progress=False),
        "fixed c_r = 0 is outside Backlash's valid range of c_r, (0, inf)",
    ),
    (
        "a fixed value that is not finite",
        lambda: ts.identify(m.BoucWen, T, X, Y, fixed={"n": float("nan")}, progress=False),
        "fixed n = nan is not a finite number",
    ),
    ("two lags", lambda: parse_model("lag1+lag1"), "a lag chained with a lag is linear"),
    ("a lag alone", lambda: parse_model("lag2"), "a lag alone is linear"),
    ("three parts", lambda: parse_model("bwb+poly3+lag1"), "3 parts; at most two"),
    ("an empty part", lambda: parse_model("+bwb"), "an empty part around '+'"),
]


@pytest.mark.parametrize(("case", "call", "says"), MESSAGES, ids=[c[0] for c in MESSAGES])
def test_a_message_names_what_is_wrong(case, call, says):
    assert says in _error(call)


def test_an_unknown_attribute_still_lists_the_parameters():
    text = _error(lambda: setattr(m.Backlash(), "b_r", 0.2))
    assert "no attribute 'b_r' to set; its parameters are ['c_r', 'c_l', 'B_r', 'B_l']" in text


def test_the_composite_names_that_work_still_parse():
    for name in ("lag1+bwb", "bwb+lag2", "bwb+poly3", "pi+odd3", "gpi", "bwb+load"):
        parse_model(name)


def test_rows_logged_twice_are_dropped_not_blamed_on_rounding(tmp_path):
    """Every row written twice, stamps at the sampling's resolution: the copies are dropped
    with a note; different values at a repeated stamp coarser than the sampling still are
    rounding (an error saying so)."""
    t = np.round(np.arange(0, 2, 0.01), 2)
    x = np.sin(t)
    twice = np.repeat(np.c_[t, x, 0.9 * x], 2, axis=0)
    path = tmp_path / "twice.csv"
    np.savetxt(path, twice, delimiter=",", header="t,x,y", comments="", fmt="%.2f,%.6f,%.6f")
    log = ts.io.read_log(path, time="t", input="x", output="y")
    assert log.x.size == t.size
    assert "repeat the one before (time and values) dropped" in log.notes[-1]
    np.testing.assert_array_equal(log.x, np.round(x, 6))
    fine = np.arange(0, 2, 0.001)
    rounded = np.c_[np.round(fine, 2), np.sin(fine), np.cos(fine)]
    path = tmp_path / "rounded.csv"
    np.savetxt(path, rounded, delimiter=",", header="t,x,y", comments="", fmt="%.2f,%.6f,%.6f")
    assert "rounding made them equal" in _error(
        lambda: ts.io.read_log(path, time="t", input="x", output="y")
    )


# -- the API reads as the docs -------------------------------------------------------------------
def test_ts_identify_is_the_package_and_is_callable():
    import tendonsheath.identify as package

    assert ts.identify is package
    for name in package.__all__:
        assert getattr(ts.identify, name) is getattr(package, name)
    assert ts.identify.identify_loop_dynamics.__module__.endswith("loop_dynamics")
    first = next(iter(inspect.signature(ts.identify).parameters))
    assert first == "model_class"
    fit = ts.identify(m.Backlash, T, X, Y, maxiter=2, progress=False)
    assert isinstance(fit, ts.Fit)


# -- command-line warnings -----------------------------------------------------------------------
def test_a_command_line_warning_is_one_line_with_its_category(tmp_path):
    data = tmp_path / "run.csv"
    ts.io.write_csv(data, {"t": T, "x": X, "y": Y})
    args = ["identify", str(data), "-m", "curve", "--input", "x", "--output", "y", "--time"]
    result = CliRunner().invoke(
        app, [*args, "t", "--curve-angle", "180", "--maxiter", "1", "-o", str(tmp_path / "m.json")]
    )
    assert result.exit_code == 0, result.output
    lines = [ln for ln in result.output.splitlines() if "UnitWarning" in ln]
    assert lines and lines[0].startswith("Warning (UnitWarning): read_log(run.csv): curve_angle")
    assert not re.search(r"\.py:\d+", result.output), result.output
    assert "warnings.warn" not in result.output


def test_a_linear_block_that_cannot_run_says_so_in_one_line():
    """The abstract base is refused, and a lag too slow or too fast for the sample time to
    discretise is named (it was a singular matrix or an overflow from inside SciPy)."""
    assert "use FirstOrderLag or SecondOrderLag" in _error(lambda: m.LinearBlock())
    t = np.arange(100) * 0.01
    with pytest.warns(ts.UnitWarning):
        slow = m.FirstOrderLag(time_constant=1e300)
    fast = m.SecondOrderLag(frequency=1e300)
    for block in (slow, fast):
        assert "cannot be discretised at a sample time of 0.01 s" in _error(
            lambda block=block: block.simulate(t, np.sin(t))
        )
