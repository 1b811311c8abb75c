"""The report: self-contained, and rendered by a real browser (headless Chromium)."""

import json
import re
import shutil
import subprocess
import tempfile

import matplotlib.image as mpimg
import numpy as np

from tendonsheath.report.build import SCHEMA, SCHEMA_VERSION, write
from tendonsheath.report.interactive import plotly_js
from tendonsheath.status import STATUS_FLAGS

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--enable-logging=stderr",
    "--v=0",
    "--virtual-time-budget=5000",
    "--host-resolver-rules=MAP * ~NOTFOUND",  # offline: a network load would fail loudly
]
LIVE = ("tracking", "error", "loops")  # the figures drawn with Plotly in the page


def _chromium(*args):
    assert CHROMIUM, "Chromium is needed: `make test` installs Debian's chromium package"
    with tempfile.TemporaryDirectory() as profile:
        return subprocess.run(
            [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", *args],
            capture_output=True,
            text=True,
            timeout=120,
        )


def test_report_is_self_contained_and_renders(scenario_results, tmp_path):
    written = write(tmp_path, list(scenario_results.values()), None)
    report = written["report"]
    text = report.read_text()
    bundle = plotly_js()
    assert text.count(bundle) == 1  # plotly.js inlined once, whatever the number of figures
    page = text.replace(bundle, "")
    assert "http://" not in page and "https://" not in page  # no network outside plotly.js
    assert "<script src" not in page
    assert text.count("<h3>Status per cycle</h3>") == len(scenario_results)
    n_live = len(LIVE) * len(scenario_results)
    assert page.count('class="plotly-graph-div"') == n_live
    assert text.count("<img") == len(written["figures"]) - n_live
    for name in scenario_results:  # every static PNG kept beside the report, linked
        for kind in LIVE:
            png = tmp_path / f"{name}_{kind}.png"
            assert png.read_bytes()[:4] == b"\x89PNG" and f'href="{png.name}"' in page
    assert len(text) < 8e6, len(text)  # about 5 MB: plotly.js 4.8 MB and thinned traces
    for name in ("do2015", "sun2015", "lau2015"):
        assert f'id="{name}"' in text

    dom = _chromium("--dump-dom", report.as_uri())
    assert dom.returncode == 0, dom.stderr[-2000:]
    figures = int(re.search(r'data-figures="(\d+)"', dom.stdout).group(1))
    loaded = int(re.search(r'data-figures-loaded="(\d+)"', dom.stdout).group(1))
    assert figures == len(written["figures"]) - n_live and loaded == figures
    # Plotly drew every interactive figure: its class and an SVG plot with a line per trace
    drawn = dom.stdout.replace(bundle, "")  # the elements, not plotly.js's own text
    plots = re.findall(r'class="[^"]*\bjs-plotly-plot\b[^"]*"', drawn)
    assert len(plots) == n_live, plots
    assert drawn.count('class="main-svg"') >= n_live
    traces = sum(len(r.runs) for r in scenario_results.values())  # 3 figures, + reference
    assert drawn.count('class="js-line"') >= 3 * traces + len(scenario_results)
    console = [line for line in dom.stderr.splitlines() if ":CONSOLE" in line]
    assert not console, console

    shot = tmp_path / "shot.png"
    result = _chromium(f"--screenshot={shot}", "--window-size=1280,1600", report.as_uri())
    assert result.returncode == 0 and shot.exists(), result.stderr[-2000:]
    pixels = mpimg.imread(shot)
    assert pixels.shape[0] >= 1000 and pixels.shape[1] >= 1200
    assert np.std(pixels[..., :3]) > 0.05  # not a blank page


def test_metrics_json_follows_its_schema(scenario_results, tmp_path):
    written = write(tmp_path, list(scenario_results.values()), None)
    data = json.loads(written["metrics"].read_text())
    assert data["schema"] == SCHEMA and data["version"] == SCHEMA_VERSION
    for scenario, comps in data["scenarios"].items():
        assert scenario in ("do2015", "sun2015", "lau2015")
        for comp, metrics in comps.items():
            for key in ("mse", "rmse", "max_abs", "percent_error", "loop_width"):
                assert isinstance(metrics[key], float), (scenario, comp, key)
            status = metrics["status"]  # cycles flagged with each status, per compensator
            assert set(status) == set(STATUS_FLAGS), (scenario, comp)
            assert all(isinstance(v, int) and v >= 0 for v in status.values()), (scenario, comp)
    assert data["paper"]["do2015"]["mse_rad2"]["none"] == 0.0158
    assert "frequency" in data["details"]["lau2015"]
