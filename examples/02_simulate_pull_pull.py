"""Simulate a sine through a pull-pull tendon-sheath pair at two routes and plot the loops.

.venv/bin/python examples/02_simulate_pull_pull.py --out example-out
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tendonsheath as ts  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("example-out"))
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    t = np.arange(0, 10.0, 1e-3)
    q_in = 0.5 * np.sin(2 * np.pi * 0.3 * t)  # proximal pulley angle (rad)
    routes = {
        "straight-ish (Theta = pi/2)": ts.Route.uniform(1.2, np.pi / 2),
        "one coil (Theta = 2 pi)": ts.Route.uniform(1.2, 2 * np.pi),
    }
    fig, (ax_loop, ax_t) = plt.subplots(1, 2, figsize=(10, 4))
    for name, route in routes.items():
        plant = ts.PullPullPlant(
            route=route,
            friction=0.1,
            stiffness=2.4e4,
            pretension=10.0,
            proximal_radius=5e-3,
            distal_radius=5e-3,
            elements=100,
            load=ts.loads.ConstantTorque(5.0 * 5e-3),
        )
        q_out = plant.simulate(t, q_in)
        cf = plant.closed_form()
        print(
            f"{name}: dead zone {cf['dead_zone'] / 5e-3:.4f} rad (closed form), "
            f"max |q_in - q_out| {np.abs(q_in - q_out).max():.4f} rad"
        )
        ax_loop.plot(q_in, q_out, label=name)
        ax_t.plot(t, q_in - q_out, label=name)
    ax_loop.set_xlabel("input angle (rad)")
    ax_loop.set_ylabel("output angle (rad)")
    ax_loop.set_title("hysteresis loop")
    ax_t.set_xlabel("time (s)")
    ax_t.set_ylabel("q_in - q_out (rad)")
    ax_t.set_title("transmission error")
    for ax in (ax_loop, ax_t):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize="small")
    fig.tight_layout()
    path = args.out / "02_pull_pull_loops.png"
    fig.savefig(path, dpi=120)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
