"""The report's executive summary: what a reader must know before the tables, in a few lines.

It says how many of the papers' claims were met, names each one that was not with its
measured figure, and names every loop that oscillated on its own or saturated its command,
in a scenario's runs or in the robustness study, so that no table further down flatters.
"""

from __future__ import annotations

import html as _html

from ..bench.limit_cycle import describe


def _missed(results: list) -> list[str]:
    out = []
    for r in results:
        for x in r.targets:
            if not x["met"]:
                measured = f"{x['measured']:.3g} {x['unit']}".strip()
                seen = f"; {x['seen']}" if x.get("seen") else ""
                out.append(f"{r.name}: {x['claim']}: {measured} (target {x['target']}){seen}")
    return out


def _runs_flagged(results: list) -> list[str]:
    """Each shown run that had a limit cycle or a saturated command."""
    out = []
    for r in results:
        for name, run in r.runs.items():
            cycle = run.metrics.get("limit_cycle", {})
            saturated = run.metrics.get("status", {}).get("saturated", 0)
            parts = [describe(cycle)] if cycle.get("detected") else []
            if saturated:
                parts.append(f"command saturated on {saturated} cycles")
            if parts:
                out.append(f"{r.name}, {name}: {'; '.join(parts)}")
    return out


def _robustness_flagged(sections: list[tuple[str, str, str, dict]]) -> list[str]:
    out = []
    for anchor, _heading, _body, data in sections:
        for name, numbers in (data.get("compensators") or {}).items():
            share = numbers.get("limit_cycle_share") if isinstance(numbers, dict) else None
            if share:
                runs = data.get("runs")
                of = f" of {runs} perturbed plants" if runs else ""
                out.append(f"{anchor}, {name}: a limit cycle in {100 * share:.3g} %{of}")
    return out


def executive_summary(
    results: list, extra_sections: list[tuple[str, str, str, dict]] | None = None
) -> str:
    """The summary's HTML ("" when there is nothing to summarise).

    Parameters
    ----------
    results : list of ScenarioResult
        The scenarios' results.
    extra_sections : list of (anchor, heading, html, data), optional
        Sections after the scenarios; a robustness study's share of runs with a limit cycle
        (``data["compensators"][name]["limit_cycle_share"]``) is named.

    Returns
    -------
    str
        HTML: the claims met, each claim missed, each loop that oscillated or saturated.
    """
    claims = [x for r in results for x in r.targets]
    if not claims and not results:
        return ""
    missed = _missed(results)
    flagged = _runs_flagged(results) + _robustness_flagged(extra_sections or [])
    items: list[str] = []
    if claims:
        items.append(f"{len(claims) - len(missed)} of {len(claims)} paper claims met.")
    items += [f"Not met: {m}." for m in missed]
    items += [f"Look before trusting its figure: {f}." for f in flagged]
    if not flagged:
        items.append("No shown run had a limit cycle or a saturated command.")
    body = "".join(f"<li>{_html.escape(i)}</li>" for i in items)
    return f'<div class="summary"><h2>Summary</h2><ul>{body}</ul></div>'


__all__ = ["executive_summary"]
