"""A single self-contained HTML report: figures embedded as base64 PNG or as Plotly divs with
plotly.js inlined once, no network."""

from __future__ import annotations

import base64
import html
import math
from datetime import UTC, datetime
from typing import Any

STYLE = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:0;
background:#fafafa;color:#222;line-height:1.45}
main{max-width:1100px;margin:0 auto;padding:1.5rem 1.2rem 4rem}
h1{font-size:1.7rem;margin:.2rem 0 .4rem}h2{font-size:1.3rem;margin-top:2.4rem;
border-bottom:2px solid #ddd;padding-bottom:.2rem}h3{font-size:1.05rem;margin-top:1.4rem}
table{border-collapse:collapse;margin:.6rem 0 1rem;font-size:.9rem;background:#fff}
th,td{border:1px solid #ccc;padding:.25rem .55rem;text-align:right}
th{background:#eef2f7}td:first-child,th:first-child{text-align:left}
figure{margin:.8rem 0;background:#fff;border:1px solid #e3e3e3;padding:.4rem;display:inline-block;
max-width:100%}figure img{max-width:100%;height:auto;display:block}
figure.interactive{display:block}
figcaption{font-size:.82rem;color:#555;margin-top:.25rem}
.conditions td{text-align:left}.note{color:#555;font-size:.9rem}
nav a{margin-right:1rem}
"""

CHECK_SCRIPT = """
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  document.body.setAttribute('data-figures', imgs.length);
  document.body.setAttribute('data-figures-loaded', ok);
});
"""


def fmt(value: Any) -> str:
    if value is None:
        return "&ndash;"
    if isinstance(value, float):
        if math.isnan(value):
            return "&ndash;"
        if value != 0 and (abs(value) < 1e-3 or abs(value) >= 1e5):
            return f"{value:.3e}"
        return f"{value:.4g}"
    return html.escape(str(value))


def table(rows: list[dict[str, Any]], headers: dict[str, str] | None = None) -> str:
    if not rows:
        return ""
    keys = list(rows[0])
    head = "".join(f"<th>{html.escape((headers or {}).get(k, k))}</th>" for k in keys)
    body = "".join(
        "<tr>" + "".join(f"<td>{fmt(r.get(k))}</td>" for k in keys) + "</tr>" for r in rows
    )
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def conditions(items: dict[str, str]) -> str:
    body = "".join(
        f"<tr><th>{html.escape(k)}</th><td>{html.escape(v)}</td></tr>" for k, v in items.items()
    )
    return f'<table class="conditions"><tbody>{body}</tbody></table>'


def figure(png: bytes, caption: str, alt: str | None = None) -> str:
    data = base64.b64encode(png).decode("ascii")
    return (
        f'<figure><img src="data:image/png;base64,{data}" alt="{html.escape(alt or caption)}">'
        f"<figcaption>{html.escape(caption)}</figcaption></figure>"
    )


def interactive_figure(div: str, png_name: str) -> str:
    """A Plotly figure (``div`` from report.interactive) and a link to its PNG for papers."""
    link = (
        f'<p class="note">Static figure for papers: <a href="{html.escape(png_name)}">'
        f"{html.escape(png_name)}</a></p>"
    )
    return div + link


def _plotly_script(body: str) -> str:
    """plotly.js, inlined once, when the page has a Plotly figure."""
    from .interactive import MARKER, plotly_js

    return f"<script>{plotly_js()}</script>" if MARKER in body else ""


def page(title: str, intro: str, sections: list[tuple[str, str, str]]) -> str:
    """sections: (anchor, heading, html body)."""
    nav = "".join(f'<a href="#{a}">{html.escape(h)}</a>' for a, h, _ in sections)
    body = "".join(
        f'<section id="{a}"><h2>{html.escape(h)}</h2>{b}</section>' for a, h, b in sections
    )
    stamp = datetime.now(UTC).strftime("%Y-%m-%d %H:%M UTC")
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{html.escape(title)}</title><style>{STYLE}</style>{_plotly_script(body)}</head>
<body><main><h1>{html.escape(title)}</h1><p class="note">Generated {stamp} by tendonsheath.</p>
{intro}<nav>{nav}</nav>{body}</main><script>{CHECK_SCRIPT}</script></body></html>
"""


__all__ = [
    "CHECK_SCRIPT",
    "STYLE",
    "conditions",
    "figure",
    "fmt",
    "interactive_figure",
    "page",
    "table",
]
