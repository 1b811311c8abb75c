"""Figures of a sweep: metric histograms, metric against each parameter, sensitivity."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .._util.atomic import save_figure


def _log_scale(x: np.ndarray) -> bool:
    x = x[np.isfinite(x)]
    return x.size > 1 and bool(np.all(x > 0)) and x.max() / x.min() > 30


def plot_all(result, out: Path, sensitivity=None) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")

    out.mkdir(parents=True, exist_ok=True)
    groups = list(result._groups())
    written = [_histogram(result, m, groups, out) for m in result.metrics]
    # seeds have no meaningful order: no scatter against them (text choices are kept)
    params = [
        p
        for p in result.parameters
        if not (p in result.unranked and result.table[p].dtype != object)
    ]
    if params:
        written += [_against_parameters(result, m, params, groups, out) for m in result.metrics]
    if sensitivity is not None and len(sensitivity):
        written.append(_sensitivity_bars(result, sensitivity, groups, out))
    return written


def _saved(fig, path: Path) -> Path:
    import matplotlib.pyplot as plt

    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


def _histogram(result, m: str, groups, out: Path) -> Path:
    """Histogram of metric ``m`` over the runs, one colour per compensator."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    allx = result.table[m].to_numpy(dtype=np.float64)
    log = _log_scale(allx)
    finite = allx[np.isfinite(allx)]
    if finite.size:
        if log:
            bins = np.geomspace(finite.min(), finite.max(), 30)
        else:
            bins = np.linspace(finite.min(), finite.max() + 1e-300, 30)
        for comp, g in groups:
            x = g[m].to_numpy(dtype=np.float64)
            ax.hist(x[np.isfinite(x)], bins=bins.tolist(), alpha=0.55, label=comp)
    if log:
        ax.set_xscale("log")
    ax.set_xlabel(m)
    ax.set_ylabel("runs")
    ax.set_title(f"{m} over {result.n_runs} runs")
    if len(groups) > 1:
        ax.legend(fontsize="small")
    ax.grid(True, alpha=0.3)
    return _saved(fig, out / f"hist_{m}.png")


def _against_parameters(result, m: str, params: list[str], groups, out: Path) -> Path:
    """Metric ``m`` of every run against each parameter, one panel per parameter."""
    import matplotlib.pyplot as plt

    cols = min(3, len(params))
    rows = -(-len(params) // cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.3 * rows), squeeze=False)
    log = _log_scale(result.table[m].to_numpy(dtype=np.float64))
    for ax, p in zip(axes.flat, params, strict=False):
        for comp, g in groups:
            ax.plot(
                g[p].astype(str) if g[p].dtype == object else g[p],
                g[m],
                ".",
                ms=3,
                alpha=0.6,
                label=comp,
            )
        if log:
            ax.set_yscale("log")
        ax.set_xlabel(p)
        ax.set_ylabel(m)
        ax.grid(True, alpha=0.3)
    for ax in list(axes.flat)[len(params) :]:
        ax.set_visible(False)
    if len(groups) > 1:
        axes.flat[0].legend(fontsize="small")
    fig.suptitle(f"{m} against each parameter")
    return _saved(fig, out / f"{m}_vs_parameters.png")


def _sensitivity_bars(result, sensitivity, groups, out: Path) -> Path:
    """The sensitivity of the primary metric to each parameter, one bar per compensator."""
    import matplotlib.pyplot as plt

    m = result.primary_metric()
    sens = sensitivity[sensitivity["metric"] == m]
    value = "ST" if "ST" in sens else "coefficient"
    names = list(dict.fromkeys(sens["parameter"]))
    fig, ax = plt.subplots(figsize=(6.5, 0.5 + 0.45 * len(names) * max(1, len(groups))))
    height = 0.8 / max(1, len(groups))
    for k, (comp, _) in enumerate(groups):
        s = sens[sens["compensator"] == comp].set_index("parameter").reindex(names)
        y = np.arange(len(names)) + k * height
        ax.barh(y, s[value].to_numpy(dtype=np.float64), height=height, label=comp)
    ax.set_yticks(np.arange(len(names)) + 0.4 - height / 2, names)
    ax.axvline(0, color="k", lw=0.8)
    label = "total Sobol index ST" if value == "ST" else "standardized regression coefficient"
    ax.set_xlabel(f"{label} of {m}")
    ax.set_title("which parameter matters most")
    if len(groups) > 1:
        ax.legend(fontsize="small")
    ax.grid(True, axis="x", alpha=0.3)
    return _saved(fig, out / "sensitivity.png")


__all__ = ["plot_all"]
