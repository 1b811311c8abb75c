"""No bound object outlives its Python owners: a whole workflow (simulate, identify, compare,
compensate, save and load, the bench) in a fresh interpreter with nanobind's leak check on
(TENDONSHEATH_LEAK_WARNINGS=1) exits without a leak report. (The check is off by default: at
exit nanobind also lists what a host such as pytest still holds, which is no leak.)"""

import os
import subprocess
import sys

WORKFLOW = """
import numpy as np
import tendonsheath as ts

t = np.arange(0.0, 4.0, 1e-2)
x = np.sin(2 * np.pi * 0.5 * t)
y = ts.models.BoucWenBacklash(B_r=0.1, B_l=0.08).simulate(t, x)
fit = ts.identify(ts.models.Backlash, t, x, y, maxiter=5, progress=False)
cmp = ts.compare_models([(t, x, y)], models=["backlash", "pi"], maxiter=5)
ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.03)
ff.to_json("ff.json")
loaded = ts.compensate.load_compensator("ff.json")
plant = ts.PullPullPlant(ts.Route.uniform(1.0, 1.5), pretension=20.0, elements=10)
result = ts.bench.run(plant, loaded, t, 0.5 * x)
print(round(float(result.metrics["rmse"]), 6))
"""


def test_a_workflow_leaks_no_bound_object(tmp_path):
    env = {**os.environ, "TENDONSHEATH_LEAK_WARNINGS": "1"}
    run = subprocess.run(
        [sys.executable, "-c", WORKFLOW], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert run.returncode == 0, run.stderr
    assert "leaked" not in run.stderr, run.stderr[-3000:]


def test_the_check_sees_a_leak_when_on_and_is_quiet_when_off(tmp_path):
    """A bound object whose reference count is raised by hand (a reference-counting bug) is
    reported with the variable set, and not without it."""
    leak = (
        "import ctypes, tendonsheath as ts\n"
        "m = ts.models.Backlash()\n"
        "ctypes.pythonapi.Py_IncRef(ctypes.py_object(m))\n"
    )
    for on in (True, False):
        env = {k: v for k, v in os.environ.items() if k != "TENDONSHEATH_LEAK_WARNINGS"}
        if on:
            env["TENDONSHEATH_LEAK_WARNINGS"] = "1"
        run = subprocess.run(
            [sys.executable, "-c", leak], cwd=tmp_path, env=env, capture_output=True, text=True
        )
        assert run.returncode == 0, run.stderr
        assert ("leaked" in run.stderr) == on, (on, run.stderr[-2000:])
