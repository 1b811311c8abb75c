"""``import tendonsheath`` loads no heavy module: scipy's submodules, matplotlib and pandas are
imported where a feature uses them (issue 37, item 5). The time itself is measured in
benchmarks/import_time.py, never asserted here; which modules the import loads is behaviour."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

# scipy.signal alone was 0.5 s of a 0.8 s import; scipy's top level (~1 ms) is not listed
HEAVY = ("scipy.", "matplotlib", "pandas", "importlib.metadata")

_LOADED = """
import sys
import tendonsheath
print("\\n".join(sorted(sys.modules)))
"""


def _loaded_by(code: str) -> list[str]:
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_the_import_loads_no_heavy_module():
    loaded = _loaded_by(_LOADED)
    assert "tendonsheath.bench" in loaded  # the package itself was imported
    assert [m for m in loaded if m.startswith(HEAVY)] == []


def test_a_feature_still_finds_its_scipy_import():
    # the imports moved into the functions that use them: a linear block's filter and a
    # bounded least squares run, and load scipy.signal / scipy.optimize only then
    import tendonsheath as ts
    from tendonsheath.identify.problem import bounded_lsq

    tau = 0.05
    t = np.arange(0.0, 1.0, 1e-3)
    y = ts.models.FirstOrderLag(time_constant=tau).simulate(t, t).output
    # a ramp from rest: y = t - tau (1 - exp(-t / tau)), exact under the first-order hold
    np.testing.assert_allclose(y, t - tau * (1.0 - np.exp(-t / tau)), atol=1e-12)
    a = np.eye(2)
    x = bounded_lsq(a, np.array([-1.0, 2.0]), np.zeros(2), np.full(2, np.inf))
    np.testing.assert_allclose(x, [0.0, 2.0], atol=1e-12)  # the bound holds the first at 0
    assert "scipy.signal" in sys.modules and "scipy.optimize" in sys.modules
