"""Identify a backlash-like hysteresis model from a logged run and check it on another run.

Here the "log" is simulated (a BoucWenBacklash with sensor noise); with your robot's data use
``ts.io.read_log("run.csv", time="t", input="motor", output="tip")`` instead.
Runs in a few seconds: `python examples/03_identify_bouc_wen_backlash.py --out example-out`.
"""

import argparse
from pathlib import Path

import numpy as np

import tendonsheath as ts

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out", type=Path, default=Path("example-out"))
out = parser.parse_args().out
out.mkdir(parents=True, exist_ok=True)

rng = np.random.default_rng(0)
robot = ts.models.BoucWenBacklash(c_r=1.0, c_l=0.92, B_r=0.12, B_l=0.09, n=6.0)

# Calibration run: 10 s at 500 Hz, a sine with a decaying amplitude (nested loops).
t = np.arange(0.0, 10.0, 2e-3)
motor = np.sin(2 * np.pi * 0.3 * t) * (1.0 - 0.5 * t / t[-1])
tip = robot.simulate(t, motor) + 0.003 * rng.standard_normal(t.size)

fit = ts.identify(ts.models.BoucWenBacklash, t, motor, tip, warmup=100)
print(fit.summary())

# Validation run: another amplitude and frequency.
motor2 = 0.7 * np.sin(2 * np.pi * 0.8 * t)
tip2 = robot.simulate(t, motor2) + 0.003 * rng.standard_normal(t.size)
print("validation:", {k: round(v, 5) for k, v in fit.validate(t, motor2, tip2).items()})

fit.model.to_json(out / "bouc_wen_backlash.json")  # reload with ts.load_model(...)
print("wrote", out / "bouc_wen_backlash.json")
print("figure:", fit.report(out / "identify_report.png"))
