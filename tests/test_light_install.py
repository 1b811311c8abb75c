"""A light core install (issue 26, item 8): plotly, h5py and openpyxl are extras.

Without them ``import tendonsheath`` works, and so do simulating, identifying and
compensating; the HTML report, an HDF5 log and an Excel log each raise one line that names
the extra (a MissingExtraError, an ImportError), and the commands print it as ``error: ...``
with exit code 2. "Without them" is made here by blocking their import (``sys.modules[name] =
None``: ``import name`` then raises ImportError), in a fresh interpreter for the import and in
this one for the commands. tests/wheel_smoke.sh checks a real install of the wheel pulls none
of them."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import openpyxl
import pytest
from typer.testing import CliRunner

from tendonsheath.apps.cli import app

OPTIONAL = ("plotly", "h5py", "openpyxl")
REPORT = "the HTML report needs plotly: pip install 'tendonsheath[report]'"
HDF5 = "reading HDF5 files needs h5py: pip install 'tendonsheath[hdf5]'"
EXCEL = "reading Excel files needs openpyxl: pip install 'tendonsheath[excel]'"

# run in a fresh interpreter: the package and its commands import none of the optional
# packages; with them blocked the core workflow runs and each feature names its extra
_WITHOUT_EXTRAS = """
import sys
from pathlib import Path

import numpy as np

import tendonsheath as ts
import tendonsheath.apps.cli, tendonsheath.apps.demo
import tendonsheath.report.build, tendonsheath.report.html

OPTIONAL = {optional!r}
loaded = sorted(m for m in sys.modules if m.split(".")[0] in OPTIONAL)
assert not loaded, f"imported by the package: {{loaded}}"
for name in OPTIONAL:
    sys.modules[name] = None  # import name: ImportError from here on

t = np.arange(0.0, 4.0, 1e-3)
x = np.sin(2 * np.pi * 0.5 * t)
truth = ts.models.Backlash(c_r=1.2, c_l=1.1, B_r=0.1, B_l=0.08)
y = truth.simulate(t, x)
fit = ts.identify(ts.models.Backlash, t, x, y)
assert abs(fit.model.params["B_r"] - 0.1) < 1e-3, fit.model.params
# the identified inverse drives the truth onto a reference it never saw: its rms error is
# about 1e-3 of the uncompensated one's (1e-4 against 0.10 rad), 1e-2 leaves a 10x margin
yd = 0.8 * x
ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.03)
u = np.array([ff.step(v, 1e-3) for v in yd])
late = t >= 1.0
rms = lambda e: np.sqrt(np.mean(e[late] ** 2))
assert rms(truth.simulate(t, u) - yd) < 1e-2 * rms(truth.simulate(t, yd) - yd)

errors = []
for path in (Path(sys.argv[1]), Path(sys.argv[2])):
    try:
        ts.io.read_log(path, time="t", input="x", output="y")
    except ts.MissingExtraError as exc:
        errors.append(str(exc))
for call in (
    lambda: ts.report.build.write(Path(sys.argv[3]), []),
    lambda: ts.report.html.page("title", "", [("a", "A", '<div class="plotly-graph-div">')]),
):
    try:
        call()
    except ImportError as exc:
        errors.append(f"{{type(exc).__name__}}: {{exc}}")
print("\\n".join(errors))
"""


@pytest.fixture(scope="module")
def logs(tmp_path_factory) -> dict[str, Path]:
    """A good HDF5 log and a good Excel log (t, x, y), written while their packages work."""
    d = tmp_path_factory.mktemp("logs")
    t = np.arange(50) * 0.01
    columns = {"t": t, "x": np.sin(t), "y": 0.9 * np.sin(t)}
    with h5py.File(d / "log.h5", "w") as f:
        for name, values in columns.items():
            f[name] = values
    book = openpyxl.Workbook()
    sheet = book.active
    sheet.append(list(columns))
    for row in zip(*columns.values(), strict=True):
        sheet.append([float(v) for v in row])
    book.save(d / "log.xlsx")
    return {"h5": d / "log.h5", "xlsx": d / "log.xlsx"}


def test_the_core_works_without_the_extras_and_each_feature_names_its_own(logs, tmp_path):
    code = _WITHOUT_EXTRAS.format(optional=OPTIONAL)
    args = [str(logs["h5"]), str(logs["xlsx"]), str(tmp_path / "report")]
    run = subprocess.run(
        [sys.executable, "-c", code, *args], capture_output=True, text=True, timeout=120
    )
    assert run.returncode == 0, run.stderr
    assert run.stdout.splitlines() == [
        f"{logs['h5']}: {HDF5}",
        f"{logs['xlsx']}: {EXCEL}",
        f"MissingExtraError: {REPORT}",
        f"MissingExtraError: {REPORT}",
    ]
    assert not (tmp_path / "report").exists(), "the report folder was made before the check"


def _block(monkeypatch, *names):
    """``import name`` (and of its loaded submodules) raises ImportError until the test ends."""
    for key in [k for k in sys.modules if k.split(".")[0] in names] + list(names):
        monkeypatch.setitem(sys.modules, key, None)


COLS = ["--input", "x", "--output", "y", "--time", "t"]


@pytest.mark.parametrize(
    ("blocked", "command", "message"),
    [
        ("plotly", ["demo", "--out", "{d}/out", "--scale", "0.01"], REPORT),
        ("plotly", ["bench", "{d}/scenario.toml", "--out", "{d}/out"], REPORT),
        ("h5py", ["identify", "{h5}", "-m", "Backlash", *COLS], f"{{h5}}: {HDF5}"),
        ("openpyxl", ["identify", "{xlsx}", "-m", "Backlash", *COLS], f"{{xlsx}}: {EXCEL}"),
        ("openpyxl", ["predict", "{d}/model.json", "{xlsx}", *COLS], f"{{xlsx}}: {EXCEL}"),
    ],
)
def test_a_command_without_its_extra_is_one_line_and_exit_2(
    monkeypatch, logs, tmp_path, blocked, command, message
):
    (tmp_path / "scenario.toml").write_text("")
    from tendonsheath.models import Backlash

    Backlash().to_json(tmp_path / "model.json")
    names = {"d": tmp_path, "h5": logs["h5"], "xlsx": logs["xlsx"]}
    _block(monkeypatch, blocked)
    result = CliRunner().invoke(app, [arg.format(**names) for arg in command])
    assert result.exit_code == 2, result.output
    assert result.output.strip() == "error: " + message.format(**names)
    assert not (tmp_path / "out").exists(), "an output was written before the check"
