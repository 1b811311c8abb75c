"""01: simulate the hysteresis models on one input and compare their loops.

python examples/01_hysteresis_models.py --out example-out
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import tendonsheath as ts


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("example-out"))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    t = np.linspace(0.0, 10.0, 10_001)  # 10 s at 1 kHz
    x = 0.6 * np.sin(2 * np.pi * 0.3 * t)  # motor angle, rad

    backlash = ts.models.Backlash(c_r=1.0, c_l=0.95, B_r=0.12, B_l=0.10)
    smooth = ts.models.BoucWenBacklash(c_r=1.0, c_l=0.95, B_r=0.12, B_l=0.10, n=8)
    pi = ts.models.PrandtlIshlinskii.uniform(max_threshold=0.3, count=6)

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for model in (backlash, smooth, pi):
        y = model.simulate(t, x)
        ax.plot(x, y, label=type(model).__name__)
        print(f"{type(model).__name__:18s} output range {y.min():+.3f} .. {y.max():+.3f} rad")

    # the exact inverse of a Prandtl-Ishlinskii operator undoes it
    x_back = pi.inverse().simulate(t, pi.simulate(t, x))
    print(f"PI inverse round trip: max error {np.max(np.abs(x_back - x)):.1e} rad")

    # streaming, as in a control loop: same answer as simulate()
    smooth.reset()
    streamed = [smooth.step(xk, 1e-3) for xk in x[:5]]
    print("first streamed outputs:", np.round(streamed, 5))

    ax.set_xlabel("motor angle x [rad]")
    ax.set_ylabel("distal angle y [rad]")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.out / "01_loops.png")
    smooth.to_json(args.out / "bouc_wen_backlash.json")
    print(f"wrote {args.out / '01_loops.png'} and {args.out / 'bouc_wen_backlash.json'}")


if __name__ == "__main__":
    main()
