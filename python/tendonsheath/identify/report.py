"""Figure of a fit: measured vs predicted over time, input-output loop, residual."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .._util.atomic import save_figure


def draw_report(fit, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = Path(path)
    if path.suffix == "":
        path = path.with_suffix(".png")
    path.parent.mkdir(parents=True, exist_ok=True)
    fig, axes = plt.subplots(3, 1, figsize=(9, 10))
    ax_t, ax_loop, ax_res = axes
    offset = 0.0
    for i, (rec, y_hat) in enumerate(zip(fit.recordings, fit.predictions, strict=True)):
        t = rec.t if rec.t is not None else np.arange(rec.n, dtype=float)
        t = t - t[0] + offset
        offset = t[-1] + (t[-1] - t[0]) / max(rec.n - 1, 1)
        label = "" if len(fit.recordings) == 1 else f" #{i}"
        ax_t.plot(t, rec.y, lw=1.0, color="C0", label=("measured" if i == 0 else None))
        ax_t.plot(t, y_hat, lw=1.0, ls="--", color="C1", label=("predicted" if i == 0 else None))
        ax_loop.plot(rec.x, rec.y, lw=0.8, color="C0", alpha=0.8)
        ax_loop.plot(rec.x, y_hat, lw=0.8, ls="--", color="C1", alpha=0.8)
        ax_res.plot(t, rec.y - y_hat, lw=0.8, label=f"residual{label}")
        if fit.warmup:
            ax_res.axvspan(t[0], t[min(fit.warmup, rec.n - 1)], color="0.9")
    ax_t.set_xlabel("time (s)" if fit.recordings[0].t is not None else "sample")
    ax_t.set_ylabel("output")
    ax_t.legend(loc="upper right")
    ax_t.set_title(
        f"{type(fit.model).__name__}: rmse {fit.rmse:.3g}, nrmse {100 * fit.nrmse:.2f} %, "
        f"fit {fit.fit_percent:.1f} %"
    )
    ax_loop.set_xlabel("input")
    ax_loop.set_ylabel("output")
    ax_loop.set_title("input-output loop (solid: measured, dashed: predicted)")
    ax_res.set_xlabel(ax_t.get_xlabel())
    ax_res.set_ylabel("measured - predicted")
    ax_res.set_title("residual (shaded: warm-up, not fitted)")
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    plt.close(fig)
    return path


__all__ = ["draw_report"]
