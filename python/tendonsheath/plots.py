"""Plot helpers for the physics plants (matplotlib is imported lazily)."""

from __future__ import annotations

import numpy as np


def plot_tension_profile(plant, ax=None):
    """Draw the tension of each tendon along its sheath (proximal s = 0 to distal s = L), with
    the stick/slip state of each interior node as markers. Returns the matplotlib Axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(figsize=(6, 3.5))
    T = np.atleast_2d(plant.tensions())
    S = np.atleast_2d(plant.slip_state())
    n = T.shape[1]
    colours = ("tab:blue", "tab:orange")
    for row in range(T.shape[0]):
        s = plant.element_positions(row + 1)
        L = s[-1] + s[0]
        label = f"tendon {row + 1}" if T.shape[0] > 1 else "tendon"
        ax.step(s, T[row], where="mid", color=colours[row], label=label)
        nodes = np.arange(1, n) * L / n
        tn = 0.5 * (T[row, :-1] + T[row, 1:])
        for state, marker, name in ((1, "^", "slip, pulled"), (-1, "v", "slip, released")):
            mask = S[row] == state
            if mask.any():
                ax.plot(
                    nodes[mask],
                    tn[mask],
                    marker,
                    ms=3,
                    color=colours[row],
                    alpha=0.6,
                    label=f"{label}: {name}",
                )
        stuck = S[row] == 0
        if stuck.any():
            ax.plot(nodes[stuck], tn[stuck], ".", ms=2, color="grey", alpha=0.6)
    ax.set_xlabel("arc length s from the proximal end (m)")
    ax.set_ylabel("tension (N)")
    ax.set_title("tension profile (grey dots: stuck nodes)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize="small")
    return ax


__all__ = ["plot_tension_profile"]
