"""08: models and compensators as python-control systems; the bench's sweep as an FRD.

    pip install 'tendonsheath[control]'
    python examples/08_python_control.py --out example-out

A BoucWenBacklash is identified from a calibration run of a plant model outside its class
(a smooth backlash followed by a first-order lag); its inverse feedforward and the plant
model become discrete-time ``control.NonlinearIOSystem`` objects, joined by
``control.interconnect`` on the signal name ``x`` (the motor command) and simulated by
``control.input_output_response``. The physics plant's frequency response from the bench
becomes a ``control.FrequencyResponseData`` for python-control's Bode plot.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import control as ct
import matplotlib.pyplot as plt
import numpy as np

import tendonsheath as ts

DT = 2e-3  # s, the control cycle


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=Path("example-out"))
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)

    # the plant model: smooth backlash, then a lag (rate-dependent: outside BoucWenBacklash)
    plant = ts.models.Chain(
        ts.models.BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.08, B_l=0.06, n=3),
        ts.models.FirstOrderLag(0.01),
    )
    t = np.arange(0.0, 8.0, DT)
    x_cal = 0.7 * np.sin(2 * np.pi * 0.25 * t) * (1 - 0.5 * np.sin(np.pi * t / 8.0))
    fit = ts.identify(ts.models.BoucWenBacklash, t, x_cal, plant.simulate(t, x_cal), progress=False)
    print(f"identified {fit.model} (rmse {fit.rmse:.2e})")

    # compensator in series with the plant model, joined on the signal "x"
    ff = ts.compensate.InverseFeedforward(fit.model, smoothing=0.03)
    series = ct.interconnect(
        [ff.to_control(DT, name="ff"), plant.to_control(DT, name="plant")],
        inplist=["y_d"],
        outlist=["y"],
    )
    t = np.arange(0.0, 3.0, DT)
    y_d = 0.5 * np.sin(2 * np.pi * 0.5 * t)
    y = ct.input_output_response(series, t, y_d).outputs
    same = np.max(np.abs(y - plant.simulate(t, ff.command(t, y_d))))
    print(f"interconnect == manual composition: max difference {same:.1e}")
    bare = np.sqrt(np.mean((plant.simulate(t, y_d) - y_d) ** 2))
    compensated = np.sqrt(np.mean((y - y_d) ** 2))
    print(f"tracking rmse: uncompensated {bare:.4f}, with feedforward {compensated:.4f}")

    # the physics plant's frequency response (bench sine sweep) as an FRD
    physics = ts.PullPullPlant(
        route=ts.Route.uniform(1.0, np.pi),
        friction=0.05,
        elements=10,
        motor=ts.Motor.position(bandwidth_hz=1.5, damping=0.5),
    )
    fr = ts.bench.frequency_response(physics, None, frequencies=[0.2, 0.5, 1.0, 2.0], cycles=2)
    frd = fr.to_control(name="bench")
    ct.bode_plot(frd, Hz=True)
    figure = args.out / "bode_bench.png"
    plt.savefig(figure, dpi=110)
    print(f"FRD at {np.round(frd.omega, 2)} rad/s, gain {np.round(fr.gain_db, 2)} dB")
    print(f"figure: {figure}")


if __name__ == "__main__":
    main()
