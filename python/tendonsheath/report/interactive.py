"""Interactive figures of the HTML report (Plotly): tracking, error and loops per scenario.

Each figure is a div and a call of Plotly.newPlot; plotly.js itself is inlined once per report
by :func:`html.page`, so the file stays self-contained and works offline. The traces are
thinned to at most ``POINTS`` samples (the minimum and maximum of each stretch, so no peak of
the error is lost) and stored as float32, to keep the report small. Plotly is the ``report``
extra: imported where a figure is drawn, never at ``import tendonsheath``."""

from __future__ import annotations

import html as _html

import numpy as np

from .._util.extras import require_plotly
from .figures import _angle, _color

POINTS = 2000  # per trace: a few pixels' worth across a report-wide figure
MARKER = 'class="plotly-graph-div"'  # what Plotly's div carries: the page inlines plotly.js


def thinned(y, points: int = POINTS) -> np.ndarray:
    """Indices of at most ``points`` samples of ``y``: each stretch's first minimum and
    maximum, in time order (the envelope survives; a stride could skip the peaks)."""
    n = len(y)
    if n <= points:
        return np.arange(n)
    stretches = np.array_split(np.arange(n), points // 2)
    picks = [(s[np.argmin(y[s])], s[np.argmax(y[s])]) for s in stretches]
    return np.unique(np.asarray(picks).ravel())


def _line(go, x, y, name, color, dash=None):
    keep = thinned(y)
    return go.Scatter(
        x=np.asarray(x)[keep].astype(np.float32),
        y=np.asarray(y)[keep].astype(np.float32),
        mode="lines",
        name=name,
        line={"color": color, "width": 1.2, "dash": dash},
    )


def _div(fig, title: str, xlabel: str, ylabel: str, height: int, caption: str) -> str:
    fig.update_layout(
        template="none",
        title={"text": title, "font": {"size": 14}},
        xaxis_title=xlabel,
        yaxis_title=ylabel,
        height=height,
        margin={"l": 60, "r": 20, "t": 40, "b": 45},
        legend={"font": {"size": 10}},
    )
    div = fig.to_html(
        full_html=False,
        include_plotlyjs=False,
        config={"displaylogo": False, "responsive": True},
    )
    return (
        f'<figure class="interactive">{div}<figcaption>{_html.escape(caption)}</figcaption>'
        "</figure>"
    )


def tracking(runs: dict, title: str, caption: str, last_seconds=12.0, unit="deg") -> str:
    go = require_plotly("plotly.graph_objects")

    first = next(iter(runs.values()))
    keep = first.t >= first.t[-1] - last_seconds
    t = first.t[keep]
    traces = [_line(go, t, _angle(first.reference[keep], unit), "reference", "#000", "dash")]
    for i, (name, r) in enumerate(runs.items()):
        traces.append(_line(go, t, _angle(r.output[keep], unit), name, _color(name, i)))
    fig = go.Figure(traces)
    return _div(fig, title, "time [s]", f"distal angle [{unit}]", 360, caption)


def errors(runs: dict, title: str, caption: str, unit="deg") -> str:
    go = require_plotly("plotly.graph_objects")

    traces = [
        _line(go, r.t, _angle(r.error, unit), name, _color(name, i))
        for i, (name, r) in enumerate(runs.items())
    ]
    fig = go.Figure(traces)
    first = next(iter(runs.values()))
    fig.add_vline(x=first.t[0] + first.warmup, line={"dash": "dot", "width": 1})
    return _div(fig, title, "time [s]", f"tracking error [{unit}]", 330, caption)


def loops(runs: dict, title: str, caption: str, unit="deg") -> str:
    go = require_plotly("plotly.graph_objects")

    traces = []
    for i, (name, r) in enumerate(runs.items()):
        x, y = _angle(r.reference[r.scored], unit), _angle(r.output[r.scored], unit)
        keep = thinned(y)
        traces.append(
            go.Scatter(
                x=x[keep].astype(np.float32),
                y=y[keep].astype(np.float32),
                mode="lines",
                name=name,
                line={"color": _color(name, i), "width": 1.0},
            )
        )
    fig = go.Figure(traces)
    fig.update_yaxes(scaleanchor="x", scaleratio=1)
    return _div(fig, title, f"reference [{unit}]", f"output [{unit}]", 480, caption)


def plotly_js() -> str:
    """The plotly.js bundle shipped with the plotly package (no network)."""
    return require_plotly("plotly.offline").get_plotlyjs()


__all__ = ["MARKER", "POINTS", "errors", "loops", "plotly_js", "thinned", "tracking"]
