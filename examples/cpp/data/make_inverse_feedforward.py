"""Writes inverse_feedforward.json, the compensator C++ example 12 loads.

A Backlash model is identified from a synthetic log of a BoucWenBacklash drive (outside the
identified class, with sensor noise), and its InverseFeedforward is saved with to_json.
Run from the repository root: .venv/bin/python examples/cpp/data/make_inverse_feedforward.py
"""

from pathlib import Path

import numpy as np

import tendonsheath as ts

OUT = Path(__file__).with_name("inverse_feedforward.json")


def main() -> None:
    rng = np.random.default_rng(3)
    t = np.arange(0.0, 20.0, 1e-2)
    x = 1.2 * np.sin(2 * np.pi * 0.25 * t) * (0.6 + 0.4 * np.sin(2 * np.pi * 0.03 * t))
    drive = ts.models.BoucWenBacklash(c_r=0.95, c_l=0.9, B_r=0.12, B_l=0.08, rho=20.0)
    y = drive.simulate(t, x) + 0.002 * rng.standard_normal(t.size)
    fit = ts.identify(ts.models.Backlash, t, x, y, progress=False)
    ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.05, limits=(-3.0, 3.0, 50.0))
    ff.to_json(OUT)
    print(f"{OUT}: InverseFeedforward over {fit.model!r}")


if __name__ == "__main__":
    main()
