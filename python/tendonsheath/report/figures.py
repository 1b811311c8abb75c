"""Figures of the report (matplotlib, Agg): tracking, error, loops, routes, Bode."""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from ..plant.route import Route  # noqa: E402

COLORS = {"none": "#7f7f7f"}
PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"]


def _color(name: str, i: int) -> str:
    return COLORS.get(name, PALETTE[i % len(PALETTE)])


def png(fig) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=100)
    plt.close(fig)
    return buf.getvalue()


def _angle(values, unit: str):
    """Radians to the report's angle unit."""
    return np.degrees(values) if unit == "deg" else np.asarray(values)


def _labelled(fig, ax, xlabel: str, ylabel: str, title: str, loc="upper right", fontsize=8):
    """Labels, title, grid and legend, laid out: how the tracking, error and loop figures end."""
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(loc=loc, fontsize=fontsize)
    fig.tight_layout()
    return fig


def tracking(runs: dict, title: str, last_seconds: float | None = 12.0, unit: str = "deg"):
    """Reference and outputs over time (the last `last_seconds`), in `unit` (deg or rad)."""
    fig, ax = plt.subplots(figsize=(9, 3.4))
    first = next(iter(runs.values()))
    t = first.t
    keep = t >= t[-1] - last_seconds if last_seconds else np.ones_like(t, bool)
    ax.plot(t[keep], _angle(first.reference[keep], unit), "k--", lw=1.2, label="reference")
    for i, (name, r) in enumerate(runs.items()):
        ax.plot(t[keep], _angle(r.output[keep], unit), lw=1.0, color=_color(name, i), label=name)
    return _labelled(fig, ax, "time [s]", f"distal angle [{unit}]", title)


def errors(runs: dict, title: str, unit: str = "deg"):
    fig, ax = plt.subplots(figsize=(9, 3.0))
    for i, (name, r) in enumerate(runs.items()):
        ax.plot(r.t, _angle(r.error, unit), lw=0.8, color=_color(name, i), label=name)
    ax.axvline(
        next(iter(runs.values())).t[0] + next(iter(runs.values())).warmup,
        color="k",
        lw=0.8,
        ls=":",
        label="end of warm-up",
    )
    return _labelled(fig, ax, "time [s]", f"tracking error [{unit}]", title)


def loops(runs: dict, title: str, unit: str = "deg"):
    """Output against reference after the warm-up: the hysteresis each compensator leaves."""
    fig, ax = plt.subplots(figsize=(4.8, 4.2))
    for i, (name, r) in enumerate(runs.items()):
        keep = r.scored
        ax.plot(
            _angle(r.reference[keep], unit),
            _angle(r.output[keep], unit),
            lw=0.8,
            color=_color(name, i),
            label=name,
        )
    lim = _angle(np.max(np.abs(next(iter(runs.values())).reference)), unit)
    ax.plot([-lim, lim], [-lim, lim], "k:", lw=0.8)
    return _labelled(
        fig, ax, f"reference [{unit}]", f"output [{unit}]", title, loc="best", fontsize=7
    )


def planar_centreline(route: Route, samples: int = 400):
    """A drawing of the route as a planar curve bending one way (x' = cos theta, y' = sin theta)."""
    s = np.linspace(0.0, route.length, samples)
    theta = np.asarray(route.angle_at(s))
    ds = np.diff(s)
    mid = 0.5 * (theta[1:] + theta[:-1])
    x = np.r_[0.0, np.cumsum(ds * np.cos(mid))]
    y = np.r_[0.0, np.cumsum(ds * np.sin(mid))]
    return x, y


def routes(shapes: dict, title: str):
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.4))
    for i, (name, route) in enumerate(shapes.items()):
        s = np.linspace(0.0, route.length, 400)
        color = PALETTE[i % len(PALETTE)]
        ax1.plot(s, route.angle_at(s) / np.pi, color=color, lw=1.2, label=name)
        x, y = planar_centreline(route)
        ax2.plot(x, y, color=color, lw=1.2)
    ax1.set_xlabel("arc length s [m]")
    ax1.set_ylabel("accumulated curve angle [pi rad]")
    ax1.grid(alpha=0.3)
    ax1.legend(fontsize=7)
    ax2.set_xlabel("x [m]")
    ax2.set_ylabel("y [m]")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.grid(alpha=0.3)
    ax2.set_title("drawn as a planar sheath")
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def bode(responses: dict, title: str, paper_bandwidth: float | None = None):
    fig, (ax1, ax2, ax3) = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
    for i, (name, fr) in enumerate(responses.items()):
        color = _color(name, i)
        ax1.semilogx(fr.frequencies, fr.gain_db, "o-", color=color, label=name)
        ax2.semilogx(fr.frequencies, fr.phase_deg, "o-", color=color)
        ax3.semilogx(fr.frequencies, 100 * fr.error_magnitude, "o-", color=color)
    ax1.axhline(-3.0, color="k", lw=0.8, ls=":")
    if paper_bandwidth:
        for ax in (ax1, ax3):
            ax.axvline(
                paper_bandwidth,
                color="#8c564b",
                lw=1.0,
                ls="--",
                label=f"paper: {paper_bandwidth} Hz" if ax is ax1 else None,
            )
    ax1.set_ylabel("gain [dB]")
    ax2.set_ylabel("phase [deg]")
    ax3.set_ylabel("|E| / |Y_d| [%]")
    ax3.set_xlabel("frequency [Hz]")
    for ax in (ax1, ax2, ax3):
        ax.grid(alpha=0.3, which="both")
    ax1.legend(fontsize=8)
    ax1.set_title(title)
    fig.tight_layout()
    return fig


def bars(values: dict, title: str, ylabel: str, paper: dict | None = None, log: bool = True):
    fig, ax = plt.subplots(figsize=(6, 3.4))
    names = list(values)
    x = np.arange(len(names))
    ax.bar(
        x - 0.2,
        [values[n] for n in names],
        0.4,
        label="this simulation",
        color=[_color(n, i) for i, n in enumerate(names)],
    )
    if paper:
        ax.bar(
            x + 0.2,
            [paper.get(n, np.nan) for n in names],
            0.4,
            label="paper",
            color="none",
            edgecolor="k",
            hatch="//",
        )
    ax.set_xticks(x, names, fontsize=8)
    if log:
        ax.set_yscale("log")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


__all__ = [
    "COLORS",
    "PALETTE",
    "bars",
    "bode",
    "errors",
    "loops",
    "planar_centreline",
    "png",
    "routes",
    "tracking",
]
