"""Rate dependence of a plant's hysteresis: input-output loops at several frequencies.

A quasi-static Coulomb plant draws the same loop at any rate; a drive with viscous sheath
friction, creep and a dynamic distal joint widens its loop as the rate rises, as measured
drives do. :func:`hysteresis_loops` measures that on any plant (through its motor, if any).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .metrics import loop_width


@dataclass
class Loop:
    """One steady loop: the motor angle (its encoder) and the distal output over one period."""

    frequency_hz: float
    motor: np.ndarray
    output: np.ndarray
    width: float  # largest vertical width of the loop (rad), bench.metrics.loop_width


def hysteresis_loops(
    plant,
    frequencies=(0.1, 1.0, 5.0),
    amplitude: float = 1.0,
    cycles: int = 3,
    rate: float = 1000.0,
) -> dict[float, Loop]:
    """Drive ``plant`` with ``amplitude * sin(2 pi f t)`` for ``cycles`` periods at each
    frequency (from rest) and keep the last period's loop (motor encoder in, output out)."""
    if cycles < 2:
        raise ValueError(f"hysteresis_loops: cycles must be >= 2 (got {cycles})")
    loops = {}
    for f in frequencies:
        f = float(f)
        if not f > 0:
            raise ValueError(f"hysteresis_loops: frequencies must be > 0 (got {f})")
        t = np.arange(0.0, cycles / f, 1.0 / rate)
        sim = plant.simulate(t, amplitude * np.sin(2 * np.pi * f * t))
        last = t >= t[-1] - 1.0 / f
        motor = sim.q_motor if sim.q_motor is not None else sim.q_in
        loops[f] = Loop(f, motor[last], sim.q_out[last], loop_width(motor[last], sim.q_out[last]))
    return loops


def loops_figure(loops: dict[float, Loop], title: str = "Rate dependence"):
    """The loops side by side on one axis (degrees), one colour per frequency."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.2, 4.2))
    for f, loop in loops.items():
        ax.plot(
            np.degrees(loop.motor),
            np.degrees(loop.output),
            lw=1.1,
            label=f"{f:g} Hz (width {np.degrees(loop.width):.2f} deg)",
        )
    ax.set_xlabel("motor angle (encoder) [deg]")
    ax.set_ylabel("distal angle [deg]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


__all__ = ["Loop", "hysteresis_loops", "loops_figure"]
