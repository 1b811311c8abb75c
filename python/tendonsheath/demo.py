"""The main job: `tendonsheath demo --out DIR`.

At this stage it simulates each hysteresis model of the library on a standard
input (a sine whose amplitude decays, so that nested minor loops appear) and
writes DIR/metrics.json and one PNG of each model's input-output loop.
"""

from __future__ import annotations

import json
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from . import models

DEMO_SCHEMA_VERSION = 1


def standard_input(duration: float = 20.0, rate: float = 1000.0, amplitude: float = 1.0):
    """0.25 Hz sine whose amplitude decays from `amplitude` to a third: nested loops."""
    t = np.arange(0.0, duration, 1.0 / rate)
    envelope = amplitude * (1.0 - (2.0 / 3.0) * t / duration)
    return t, envelope * np.sin(2 * np.pi * 0.25 * t)


def demo_models() -> dict[str, models.HysteresisModel]:
    return {
        "Backlash": models.Backlash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.10),
        "BoucWenBacklash": models.BoucWenBacklash(c_r=1.0, c_l=0.9, B_r=0.12, B_l=0.10, n=8),
        "BoucWen": models.BoucWen(A=1.0, beta=2.0, gamma=1.0, n=1.5, a=0.3, k=1.0),
        "PrandtlIshlinskii": models.PrandtlIshlinskii.uniform(0.4, 8),
        "HystereticOscillator": models.HystereticOscillator(
            m=1.0, c=0.5, k=2.0, alpha=3.0, beta=2.0, gamma=0.6, delta=0.4, nu=1.0
        ),
    }


def loop_width(x: np.ndarray, y: np.ndarray) -> float:
    """Largest vertical gap between the rising and falling branches at the same input."""
    dx = np.gradient(x)
    up, down = dx > 0, dx < 0
    if up.sum() < 2 or down.sum() < 2:
        return 0.0
    grid = np.linspace(max(x[up].min(), x[down].min()), min(x[up].max(), x[down].max()), 200)
    order_u, order_d = np.argsort(x[up]), np.argsort(x[down])
    yu = np.interp(grid, x[up][order_u], y[up][order_u])
    yd = np.interp(grid, x[down][order_d], y[down][order_d])
    return float(np.max(np.abs(yd - yu)))


def run_demo(out: Path, progress: Callable[[str], None] | None = None) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    t, x = standard_input()
    metrics: dict = {"schema_version": DEMO_SCHEMA_VERSION, "models": {}}
    written = []
    for name, model in demo_models().items():
        if progress:
            progress(name)
        start = time.perf_counter()
        y = model.simulate(t, x)
        elapsed = time.perf_counter() - start
        last = t >= t[-1] - 4.0  # the last input period
        metrics["models"][name] = {
            "params": model.params,
            "samples": int(x.size),
            "output_min": float(y.min()),
            "output_max": float(y.max()),
            "loop_width_last_cycle": loop_width(x[last], y[last]),
            "simulate_seconds": elapsed,
        }
        fig, ax = plt.subplots(figsize=(5, 4), dpi=110)
        ax.plot(x, y, lw=1.0)
        xlabel = "input force u" if name == "HystereticOscillator" else "input x"
        ax.set_xlabel(xlabel)
        ax.set_ylabel("output y")
        ax.set_title(f"{name}: input-output loop")
        ax.grid(alpha=0.3)
        fig.tight_layout()
        png = out / f"loop_{name}.png"
        fig.savefig(png)
        plt.close(fig)
        written.append(png)
    metrics_path = out / "metrics.json"
    metrics_path.write_text(json.dumps(metrics, indent=2) + "\n")
    written.append(metrics_path)
    metrics["written"] = [str(p) for p in written]
    return metrics
