"""11: coupled joints: a wrist whose joint-1 cables run over joint 0's pulley.

    python examples/11_coupled_joints.py [--out example-out] [--scale 1.0]

A single-input model cannot represent this: joint 1 turns when joint 0 does, whatever joint
1's motor does. Two realistic pull-pull drives (outside every model class) are coupled by an
idler on joint 0's axis (0.25 rad of joint 1 per rad of joint 0); both joints have noisy
encoders. From one calibration log of both joints, excited independently:

1. identify_coupled fits each joint's BoucWenBacklash and the coupling matrix by joint least
   squares, with Newey-West standard errors (the residuals are autocorrelated);
2. CoupledFeedforward inverts the coupled model each cycle, x_i = H_i^-1(y_d,i - sum_j C_ij
   y_d,j), and is compared on a new route with an InverseFeedforward per joint (each joint's
   own model, coupling ignored) and with no compensation.
"""

from __future__ import annotations

import argparse
import math
import warnings
from pathlib import Path

import numpy as np

import tendonsheath as ts


def wrist(seed: int) -> ts.CoupledPlant:
    """The two drives, the idler coupling C[1,0] = 0.25 and the encoders."""
    rig = dict(pretension=20.0, proximal_radius=15e-3, distal_radius=15e-3, elements=40)
    routes = (
        ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2)]),
        ts.Route.arcs([(0.4, 0.0), (0.6, 3 * math.pi / 4)]),
    )
    drives = [
        ts.PullPullPlant(r, **rig, **ts.presets.realistic_plant(friction=0.1, stiffness=5e3))
        for r in routes
    ]
    sensors = [ts.Sensor(resolution=1e-4, noise_std=2e-4, seed=seed + k) for k in range(2)]
    return ts.CoupledPlant(drives, [[0.0, 0.0], [0.25, 0.0]], sensors=sensors)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("example-out"))
    ap.add_argument("--scale", type=float, default=1.0, help="run length (1: 20 s calibration)")
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    # 1. calibration: both joints at once, at unrelated frequencies
    duration = max(6.0, 20.0 * args.scale)
    t = np.arange(0.0, duration, 1e-3)
    env = np.pi * t / duration
    x = np.column_stack(
        [
            1.1 * np.sin(2 * np.pi * 0.35 * t) * (1 - 0.5 * np.sin(env)),
            0.9 * np.sin(2 * np.pi * 0.61 * t + 1.0) * (1 - 0.4 * np.cos(env)),
        ]
    )
    log = wrist(seed=1).simulate(t, x)
    with warnings.catch_warnings():  # the realistic drives put Bouc-Wen's n at its bound
        warnings.simplefilter("ignore", ts.IdentifiabilityWarning)
        fit = ts.identify_coupled(
            ts.models.BoucWenBacklash, t, log.command, log.measured, warmup=1000
        )
    print(fit.report())
    print(
        f"true coupling C[1,0] = 0.25: identified {fit.coupling[1, 0]:.5f} +/- "
        f"{fit.coupling_se[1, 0]:.5f}"
    )

    # 2. a new route, three compensations, the same plant
    t = np.arange(0.0, 10.0, 1e-3)
    y_d = np.column_stack(
        [
            0.7 * np.sin(2 * np.pi * 0.4 * t) + 0.1 * np.sin(2 * np.pi * 1.1 * t),
            0.6 * np.sin(0.5) - 0.6 * np.sin(2 * np.pi * 0.3 * t + 0.5),
        ]
    )
    independent = [ts.compensate.InverseFeedforward(m, smoothing=0.03) for m in fit.model.models]
    commands = {
        "none": y_d,
        "independent": np.column_stack(
            [ff.command(t, y_d[:, i]) for i, ff in enumerate(independent)]
        ),
        "coupled": ts.compensate.CoupledFeedforward(fit.model, smoothing=0.03).command(t, y_d),
    }
    plant = wrist(seed=7)
    outputs = {name: plant.simulate(t, u).q_out for name, u in commands.items()}
    for name, y in outputs.items():
        rms = np.sqrt(np.mean((y - y_d)[1000:] ** 2, axis=0))
        print(f"{name:>12}: RMS error joint 0 {rms[0]:.2e} rad, joint 1 {rms[1]:.2e} rad")

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 3.5))
    for name, y in outputs.items():
        ax.plot(t, np.degrees(y[:, 1] - y_d[:, 1]), label=name, lw=1)
    ax.set(xlabel="t (s)", ylabel="joint 1 error (deg)", title="coupled joints: joint 1")
    ax.legend()
    fig.tight_layout()
    path = args.out / "coupled_joints.png"
    fig.savefig(path, dpi=100)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
