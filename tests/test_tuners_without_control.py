"""The tuners on a bare install: python-control (the ``control`` extra) blocked, the encoder-
and tip-loop designs are made all the same, with the gains and margins they have when it is
installed; and the margins agree with python-control's own stability_margins."""

import json
import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import tendonsheath
from tendonsheath.compensate.tuning import controller_polynomials, frequency_margins, loop_plant

PACKAGE_PARENT = Path(tendonsheath.__file__).resolve().parents[1]

# The designs, as a script run with and without python-control: an encoder loop around a PD
# and a PID servo, with and without a derivative; a tip loop over two shapes (one
# without a resonance in its band) through TipLoop.from_calibration.
DESIGNS = r"""
import dataclasses, json, math, sys
if BLOCK:
    sys.modules["control"] = None  # `import control` now raises ImportError
    try:
        import control  # noqa: F401
    except ImportError:
        pass
    else:
        raise SystemExit("python-control could not be blocked")
import tendonsheath as ts
from tendonsheath.compensate import EncoderLoop, TipLoop
from tendonsheath.identify import LoopDynamics, ServoFit

def servo(f, z, d, ti):
    return ServoFit(f, z, 1.0, 0.0, d, 1e-3, 0.0, 0.0, {}, ti)

ff = ts.compensate.InverseFeedforward(ts.models.Backlash(B_r=0.0, B_l=0.0))
out = {}
for name, sv, kw in (("pd", servo(60.0, 0.8, 0, 0.0), {}),
                     ("pd derivative", servo(25.0, 0.3, 2, 0.0), {"derivative": True}),
                     ("pid", servo(69.0, 1.1, 0, 0.0135), {})):
    d = EncoderLoop.from_calibration(ff, sv, **kw).design
    out[name] = [d.kp, d.ki, d.kd, d.sensitivity_peak, d.gain_margin_db, d.phase_margin_deg,
                 d.crossover_hz]
shape = LoopDynamics(servo(60.0, 0.9, 0, 0.05), 42.0, 0.3, 1.0, 1, 1e-3, 40.0, 0.0, 0.0)
bare = dataclasses.replace(shape, resonance_hz=math.inf, damping=math.nan, band_hz=(5.0, 120.0))
model = ts.models.BoucWenBacklash(c_r=1.0, c_l=1.0, B_r=0.05, B_l=0.05)
d = TipLoop.from_calibration(model, [shape, bare], curve_angles=[1.0, 2.0]).design
out["tip"] = [d.kp, d.ki, d.kd, *d.sensitivity_peaks, *d.gain_margins_db, *d.phase_margins_deg,
              *d.crossovers_hz]
print(json.dumps(out))
"""


def _designs(block: bool) -> dict:
    """The designs computed in a fresh interpreter (python-control blocked or not) that imports
    the same tendonsheath as this one."""
    path = os.pathsep.join([str(PACKAGE_PARENT), os.environ.get("PYTHONPATH", "")])
    env = {**os.environ, "PYTHONPATH": path}
    done = subprocess.run(
        [sys.executable, "-c", f"BLOCK = {block}\n{DESIGNS}"],
        capture_output=True,
        text=True,
        timeout=600,
        env=env,
    )
    assert done.returncode == 0, done.stderr[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_the_tuners_design_without_python_control_as_with_it():
    bare = _designs(block=True)
    assert set(bare) == {"pd", "pd derivative", "pid", "tip"}
    for values in bare.values():
        assert values[1] > 0  # a design with integral action, not a refusal
    pytest.importorskip("control")
    full = _designs(block=False)
    for name, values in full.items():
        # the same code runs either way: equal to rounding (NaN crossovers compare as equal)
        np.testing.assert_allclose(bare[name], values, rtol=1e-12, err_msg=name)


def _random_loops(n=25):
    """Loops C P of random servos under random PI(D) gains (stable or not: margins exist)."""
    from tendonsheath.identify import ServoFit

    rng = np.random.default_rng(11)
    for _ in range(n):
        sv = ServoFit(rng.uniform(5, 150), rng.uniform(0.3, 2.5), rng.uniform(0.7, 1.3), 0.0,
                      int(rng.integers(0, 5)), 1e-3, 0.0, 0.0, {},
                      float(rng.choice([0.0, 0.0135, 0.05])))  # fmt: skip
        c_num, c_den = controller_polynomials(rng.uniform(0, 2), rng.uniform(5, 400),
                                              rng.uniform(0, 2e-3), 100.0, 1e-3)  # fmt: skip
        p_num, p_den = loop_plant(sv, 1e-3)
        yield np.convolve(c_num, p_num), np.convolve(c_den, p_den)


def test_the_margins_are_python_controls():
    """frequency_margins against python-control's stability_margins (method "frd"): both solve
    the crossings of the same response, python-control on its interpolated frequency data:
    1e-4 relative leaves room for that interpolation (they agree to 1e-6 on the designs)."""
    ct = pytest.importorskip("control")
    for num, den in _random_loops():
        n = max(num.size, den.size)
        L = ct.tf(np.pad(num, (0, n - num.size)), np.pad(den, (0, n - den.size)), 1e-3)
        gm, pm, _, _, wc, _ = ct.stability_margins(L, method="frd")
        gm_db = 20 * math.log10(gm) if gm and math.isfinite(gm) else math.inf
        assert math.isfinite(gm_db) and math.isfinite(pm)  # every case has both crossings
        ours = frequency_margins(num, den, 1e-3)
        assert ours == pytest.approx((gm_db, pm, wc / (2 * math.pi)), rel=1e-4)
