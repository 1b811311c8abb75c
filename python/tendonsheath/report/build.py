"""Turn scenario results into report.html, metrics.json and figure files.

metrics.json (schema "tendonsheath.metrics", version 2):

    {"schema": "tendonsheath.metrics", "version": 2, "generated": ISO time,
     "scenarios": {scenario: {compensator: {metric: value}}},      # the headline runs
     "paper": {scenario: {...the paper's numbers...}},
     "details": {scenario: {...per-condition metrics, frequency responses, calibration...}},
     "honesty": {scenario: {compensator: {told, at_bounds, model_class, in_class_rmse,
                                          in_class_nrmse, output_range}}},
     "robustness": {...},     # the demo's Monte Carlo study: per compensator, quantiles
     "models": {model: {...}}}                                       # hysteresis model demo

Metrics per compensator: mse (rad^2), rmse, max_abs (rad), percent_error and
max_percent_error (% of the reference's range), loop_width (rad), slack_samples; all after
the warm-up (the reference's first period); status: cycles flagged with each Status flag
(held_nonfinite_input, input_clamped, not_converged, slack, fallback, saturated; whole run).
"""

from __future__ import annotations

import math
from datetime import UTC, datetime
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.atomic import write_bytes, write_json, write_text
from .._util.extras import require_plotly
from ..bench.limit_cycle import describe as describe_limit_cycle
from . import figures, html, interactive
from .summary import executive_summary
from .units import check_angle_unit, convert, rows_in_unit, unit_after

if TYPE_CHECKING:
    from ..bench.scenarios.common import ScenarioResult

SCHEMA = "tendonsheath.metrics"
# 2: parameter keys renamed; 3: the scenarios' details per servo (docs/metrics-json.md)
SCHEMA_VERSION = 3


def _status_table(runs) -> str:
    """Cycles flagged with each status, per compensator (the loop's controller, motor, plant
    and sensor together; metrics.json: scenarios.<scenario>.<compensator>.status)."""
    rows = [
        {
            "compensator": name,
            **r.metrics["status"],
            "limit cycle": describe_limit_cycle(r.metrics.get("limit_cycle", {})) or "none",
        }
        for name, r in runs.items()
        if isinstance(r.metrics.get("status"), dict)
    ]
    if not rows:
        return ""
    return (
        '<h3>Status per cycle</h3><p class="note">Control cycles in which the real-time loop '
        "flagged each status (whole run): a held non-finite input, a clamped input, a solve "
        "that did not converge, a slack tendon, a controller fallback (no measurement), a "
        "saturated command (controller limits, motor torque or speed limit); and whether the "
        "tip oscillated on its own (a limit cycle: many more tip reversals than the "
        "reference's).</p>" + html.table(rows)
    )


def _jsonable(value: Any):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, np.generic):
        return _jsonable(value.item())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


class _Section:
    """The HTML parts of one scenario's section, and the PNG files written beside the
    report (named after the scenario)."""

    def __init__(self, out: Path, scenario: str) -> None:
        self.out, self.scenario = out, scenario
        self.parts: list[str] = []
        self.written: list[Path] = []

    def figure(self, fig, name: str, caption: str, interactive_div=None) -> None:
        """The PNG beside the report; in the page, the interactive figure where there is one."""
        data = figures.png(fig)
        path = self.out / f"{self.scenario}_{name}.png"
        write_bytes(path, data)
        self.written.append(path)
        if interactive_div is None:
            self.parts.append(html.figure(data, caption))
        else:
            self.parts.append(html.interactive_figure(interactive_div, path.name))


# the figures over time of every scenario: (file name, PNG, interactive, title, caption)
_TIME_FIGURES = (
    (
        "tracking",
        figures.tracking,
        interactive.tracking,
        "tracking",
        "Reference (dashed) and distal output of each compensator, last 12 s.",
    ),
    (
        "error",
        figures.errors,
        interactive.errors,
        "tracking error",
        "Tracking error over the whole run; metrics exclude the warm-up (dotted line).",
    ),
    (
        "loops",
        figures.loops,
        interactive.loops,
        "output vs reference",
        "Hysteresis left by each compensator (output against reference).",
    ),
)


def scenario_section(
    result: ScenarioResult, out: Path, angle_unit: str = "deg"
) -> tuple[str, list[Path]]:
    """HTML for one scenario, and the PNG files written beside the report; every angle in the
    tables in ``angle_unit`` ("deg" or "rad").

    Parameters
    ----------
    result : ScenarioResult
        One scenario's result.
    out : Path
        The report's folder.
    angle_unit : {"deg", "rad"}, default "deg"
        Unit of the angles in the tables.

    Returns
    -------
    html : str
        The section's HTML.
    written : list of Path
        The PNG files written.
    """
    section = _Section(out, result.name)
    parts = section.parts
    parts.append(f"<p>{html.fmt(result.summary)}</p>")
    parts.append("<h3>What was simulated</h3>" + html.conditions(result.conditions))
    parts.append(_targets_table(result.targets))
    parts.append(
        f"<h3>{html.fmt(result.table_title)}</h3>"
        + html.table(rows_in_unit(result.table, angle_unit, result.table_units))
    )
    parts.append(_status_table(result.runs))
    parts.append(_tip_sensor_table(result.extra.get("tip_sensor")))
    parts.append(_learning_table(result.extra.get("ilc")))
    if result.paper.get("note"):
        parts.append(f'<p class="note">{html.fmt(result.paper["note"])}</p>')
    if result.name == "do2015":
        section.figure(
            _mse_bars(result, angle_unit),
            "mse",
            "Mean squared error of the headline runs (the route changing at random; "
            "log scale) beside the paper's.",
        )
    for name, static, live, title, caption in _TIME_FIGURES:
        title = f"{result.name}: {title}"
        live_caption = caption + " Zoom, pan, hide a trace in the legend."
        section.figure(
            static(result.runs, title, unit=angle_unit),
            name,
            caption,
            live(result.runs, title, live_caption, unit=angle_unit),
        )
    if result.routes:
        section.figure(
            figures.routes(result.routes, f"{result.name}: route shapes"),
            "routes",
            "Accumulated curve angle along the sheath, and the same route drawn flat.",
        )
    if result.frequency:
        section.figure(
            figures.bode(
                result.frequency,
                f"{result.name}: frequency response",
                result.paper.get("bandwidth_hz"),
            ),
            "bode",
            "Gain, phase and error magnitude of the fundamental, with the paper's bandwidth.",
        )
        parts.append(_bandwidth_table(result))
    parts.append(_calibration_tables(result, angle_unit))
    if result.honesty:
        parts.append(honesty_section(result.honesty, angle_unit))
    return "".join(parts), section.written


def _tip_sensor_table(tip: dict | None) -> str:
    """Each tip-feedback controller at each latency: its figures, saturation, and the
    identified resonance and delay it was designed from ("" without a tip-sensor study)."""
    if not tip:
        return ""
    rows = []
    for latency, controllers in tip.items():
        for name, d in controllers.items():
            design = d["design"]
            rows.append(
                {
                    "latency": latency,
                    "controller": name,
                    "improvement, fixed route": d["factor_fixed"],
                    "improvement, random routes (median)": d["factor_random"]["median"],
                    "improvement, random routes (min)": d["factor_random"]["min"],
                    "saturated cycles": d["saturated_cycles"],
                    "resonance Hz (per shape)": ", ".join(
                        f"{f:.3g}" for f in design["resonances_hz"]
                    ),
                    "delay ms (per shape)": ", ".join(f"{1e3 * x:.3g}" for x in design["delays_s"]),
                    "design": d["designed_from"],
                }
            )
    return (
        '<h3>With a tip sensor: designed from calibration logs</h3><p class="note">Each '
        "controller designed, at each latency of the tip sensor, from the loop dynamics "
        "identified on the calibration shapes (a chirp on a fast ramp through the sensor) and "
        "trial runs on those shapes; judged on the fixed route and 5 route seeds. A controller "
        "that saturated is shown with its saturated cycles, whatever its MSE.</p>"
        + html.table(rows)
    )


def _learning_table(ilc: dict | None) -> str:
    """Iterative learning: the factor after each trial, the learned table without the sensor
    and on a shifted route, and what the law was designed from ("" without one)."""
    if not ilc:
        return ""
    row = {
        "trials": ilc["trials"],
        "improvement by trial": ", ".join(f"{f:.3g}" for f in ilc["factor_by_trial"]),
        "learned table, no sensor": ilc["factor_learned_no_sensor"],
        "shifted route: learned / feedforward alone": (
            f"{ilc['shifted_route_factor']['learned']:.3g} / "
            f"{ilc['shifted_route_factor']['InverseFeedforward']:.3g}"
        ),
        "resonance Hz": ilc["resonance_hz"],
        "delay ms": 1e3 * ilc["delay_s"],
        "design": ilc["designed_from"],
    }
    return (
        '<h3>Repeated motion: iterative learning</h3><p class="note">MSE reduction over the '
        f"uncompensated run, trial after trial (tip sensor {ilc['latency_ms']:g} ms, new noise "
        "each trial), then the learned table run without the sensor.</p>" + html.table([row])
    )


def _targets_table(targets: list[dict]) -> str:
    """The paper's headline claims, measured here, met or not ("" without any)."""
    if not targets:
        return ""
    rows = [
        {
            "paper's claim": x["claim"],
            "target": x["target"],
            "measured": f"{x['measured']:.3g} {x['unit']}".strip(),
            "verdict": "met" if x["met"] else "NOT met",
            "also seen": x.get("seen") or "-",
        }
        for x in targets
    ]
    return (
        '<h3>Paper targets</h3><p class="note">Each paper\'s headline, measured here on the '
        "realistic plant with compensators calibrated from logs alone. A miss is a "
        "measured figure, not a failure to hide. A loop with a limit cycle in any of its runs "
        "meets no claim; its limit cycles and saturated cycles are named beside the "
        "verdict.</p>" + html.table(rows)
    )


def _mse_bars(result, angle_unit: str):
    """The headline runs' MSE beside the paper's (do2015)."""
    return figures.bars(
        {k: convert(r.metrics["mse"], "rad^2", angle_unit) for k, r in result.runs.items()},
        "MSE under random route changes: this simulation and the paper",
        f"MSE [{unit_after('rad^2', angle_unit)}]",
        {k: convert(v, "rad^2", angle_unit) for k, v in result.paper["mse_rad2"].items()},
    )


def _bandwidth_table(result) -> str:
    """The -3 dB and error-rise bandwidths per compensator, beside the paper's."""
    rows = [
        {
            "compensator": k,
            "bandwidth_3db_hz": fr.bandwidth_3db,
            "bandwidth_error_rise_hz": fr.bandwidth_error,
            "paper_bandwidth_hz": result.paper.get("bandwidth_hz"),
        }
        for k, fr in result.frequency.items()
    ]
    return "<h3>Bandwidth</h3>" + html.table(rows)


def _calibration_tables(result, angle_unit: str = "deg") -> str:
    """The calibration's scalar figures (angles in the report's unit) and the identified
    parameters ("" without any)."""
    parts = []
    cal = {k: v for k, v in result.calibration.items() if not isinstance(v, dict | list | tuple)}
    if cal:
        parts.append(
            "<h3>Calibration (identified on the plant)</h3>"
            + html.table(rows_in_unit([cal], angle_unit))
        )
    if result.identified:
        parts.append(
            '<h3>Identified parameters</h3><p class="note">From the calibration logs alone '
            "(motor encoder, noisy distal sensor, sensed curve angle). Groups that cannot be "
            "separated are reported as groups; the rest is held at declared values.</p>"
            + html.table(result.identified)
        )
    return "".join(parts)


def honesty_section(panel: dict, angle_unit: str = "deg") -> str:
    """The honesty panel: what each compensator was told and where it came from, parameters
    at their search bounds, and the best in-class fit on its own test run.

    Parameters
    ----------
    panel : dict
        Compensator name -> its honesty entry (:func:`tendonsheath.bench.honesty_entry`).
    angle_unit : {"deg", "rad"}, default "deg"
        Unit of the angles in the tables.

    Returns
    -------
    str
        The panel's HTML.
    """
    summary = [
        {
            "compensator": name,
            "model class": e.get("model_class"),
            "best in-class fit rmse": e.get("in_class_rmse"),
            "output range": e.get("output_range"),
            "rmse / range": e.get("in_class_nrmse"),
            "parameters at search bounds": ", ".join(e.get("at_bounds") or []) or "none",
        }
        for name, e in panel.items()
    ]
    told = [
        {
            "compensator": name,
            "told": row["quantity"],
            "value": row["value"]
            if isinstance(row["value"], float | int | str)
            else str(row["value"]),
            "where it came from": row["source"],
        }
        for name, e in panel.items()
        for row in e.get("told", [])
    ]
    return (
        '<h3>Honesty panel</h3><p class="note">How far the plant lies from each '
        "compensator's model class: that class identified on the test run's own log (motor "
        "encoder in, distal sensor out), next to the output range.</p>"
        + html.table(
            rows_in_unit(summary, angle_unit, {"output range": "rad", "rmse / range": "-"})
        )
        + "<h3>What each compensator was told</h3>"
        + html.table(told)
    )


def intro_for(results: list) -> str:
    """The report's introduction, from what each scenario actually did.

    Parameters
    ----------
    results : list of ScenarioResult
        The scenarios' results.

    Returns
    -------
    str
        The introduction's HTML.
    """
    lines = [
        f"<li>{html.fmt(r.protocol)}</li>"
        if r.protocol
        else f"<li>{html.fmt(r.name)}: no calibration protocol recorded.</li>"
        for r in results
    ]
    return (
        "<p>Each scenario ran on the N-element physics plant (spec A.5). How its compensators "
        "were calibrated and judged:</p><ul>" + "".join(lines) + "</ul><p>Metrics exclude the "
        "first period of the reference. Each section lists what every compensator was told "
        "and where it came from.</p>"
    )


def details(result: ScenarioResult) -> dict:
    """A scenario's details for metrics.json: calibration, table, identified values, route
    schedule, frequency responses and the scenario's extra data.

    Parameters
    ----------
    result : ScenarioResult
        One scenario's result.

    Returns
    -------
    dict
        The details (angles in radians).
    """
    d = {"calibration": result.calibration, "table": result.table}
    if result.identified:
        d["identified"] = result.identified
    if result.route_schedule:
        d["route_schedule"] = [{"t": t, "total_angle": a} for t, a in result.route_schedule]
    if result.frequency:
        d["frequency"] = {k: fr.as_dict() for k, fr in result.frequency.items()}
    d.update(result.extra)
    return d


def write(
    out: Path,
    scenario_results: list,
    extra_sections: list[tuple[str, str, str, dict]] | None = None,
    title: str = "tendonsheath virtual bench",
    angle_unit: str = "deg",
) -> dict:
    """Write report.html and metrics.json. ``extra_sections`` are (anchor, heading, html,
    data) after the scenarios; each one's data goes to metrics.json under its anchor (always
    in radians); the report's tables show angles in ``angle_unit``.

    Parameters
    ----------
    out : Path
        The folder (made as needed).
    scenario_results : list of ScenarioResult
        The scenarios' results.
    extra_sections : list of (str, str, str, dict), optional
        (anchor, heading, html, data) of each extra section.
    title : str, default "tendonsheath virtual bench"
        The page's title.
    angle_unit : {"deg", "rad"}, default "deg"
        Unit of the angles in the tables.

    Returns
    -------
    dict
        report and metrics (the paths written), figures (list of Path) and data (what
        metrics.json holds).

    Raises
    ------
    ValueError
        An angle_unit other than "deg" or "rad".
    MissingExtraError
        Plotly (the ``report`` extra) is not installed: checked before anything is written.
    """
    check_angle_unit(angle_unit)
    require_plotly()
    out.mkdir(parents=True, exist_ok=True)
    sections, written = [], []
    for result in scenario_results:
        body, files = scenario_section(result, out, angle_unit)
        sections.append((result.name, result.title, body))
        written += files
    metrics = {
        "schema": SCHEMA,
        "version": SCHEMA_VERSION,
        "generated": datetime.now(UTC).isoformat(timespec="seconds"),
        "scenarios": {r.name: r.metrics for r in scenario_results},
        "paper": {r.name: r.paper for r in scenario_results},
        "details": {r.name: details(r) for r in scenario_results},
        "honesty": {r.name: r.honesty for r in scenario_results if r.honesty},
        "targets": {r.name: r.targets for r in scenario_results if r.targets},
    }
    for anchor, heading, body, data in extra_sections or []:
        sections.append((anchor, heading, body))
        metrics[anchor] = data
    intro = executive_summary(scenario_results, extra_sections) + intro_for(scenario_results)
    report = out / "report.html"
    write_text(report, html.page(title, intro, sections))
    metrics_path = out / "metrics.json"
    write_json(metrics_path, _jsonable(metrics))
    return {
        "report": report,
        "metrics": metrics_path,
        "figures": written,
        "data": _jsonable(metrics),
    }


__all__ = [
    "SCHEMA",
    "SCHEMA_VERSION",
    "details",
    "honesty_section",
    "intro_for",
    "scenario_section",
    "write",
]
