"""A drive outside every model class: the realistic plant's loops at 0.1, 1 and 5 Hz, and creep.

The quasi-static capstan pair draws one loop at any rate (it is a classic backlash). The
realistic preset adds what a real rig has: a dynamic distal joint, viscous sheath friction,
tendon creep, an unequal pair, motor friction and gear backlash.

.venv/bin/python examples/07_realistic_plant.py --out example-out
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import numpy as np

import tendonsheath as ts
from tendonsheath.bench.rate_dependence import hysteresis_loops, loops_figure


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("example-out"))
    args = ap.parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)

    route = ts.Route.arcs([(0.5, 0.0), (0.5, math.pi / 2), (0.5, math.pi / 2)])
    rig = dict(pretension=20.0, proximal_radius=15e-3, distal_radius=15e-3, elements=40)
    plants = {
        "capstan only": ts.PullPullPlant(route, friction=0.1, stiffness=5e3, **rig),
        "realistic": ts.PullPullPlant(
            route,
            **rig,
            **ts.presets.realistic_plant(friction=0.1, stiffness=5e3),
            motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
        ),
    }
    for name, plant in plants.items():
        loops = hysteresis_loops(plant, frequencies=(0.1, 1.0, 5.0), amplitude=1.0)
        widths = ", ".join(f"{f:g} Hz {math.degrees(x.width):.2f} deg" for f, x in loops.items())
        print(f"{name:>13}: loop width {widths}")
        path = args.out / f"loops_{name.replace(' ', '_')}.png"
        loops_figure(loops, title=name).savefig(path, dpi=100)
        print(f"wrote {path}")

    # creep: against a spring load, ramp the motor to 1 rad, hold it, and watch the output move
    # (sheath friction locks most of the tendons' relaxation in place)
    sprung = ts.PullPullPlant(
        route,
        **rig,
        load=ts.loads.TorsionalSpring(0.2),
        **ts.presets.realistic_plant(friction=0.1, stiffness=5e3),
        motor=ts.presets.realistic_motor(bandwidth_hz=60.0, damping=0.8),
    )
    t = np.arange(0.0, 8.0, 1e-3)
    y = sprung.simulate(t, np.minimum(t, 1.0))
    creep = math.degrees(y[-1] - y[1500])
    print(f"creep while the motor holds 1 rad against a spring: {creep:+.4f} deg in 6.5 s")


if __name__ == "__main__":
    main()
