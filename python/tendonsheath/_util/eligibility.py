"""Which candidates of :func:`~tendonsheath.compare_models` may win: a model choice that
never misleads, judged on errors where they are known.

A candidate can win on the pooled held-out error and still be worse than the affine map
y = a x + b on one held-out run (a run with a longer stroke, another load): the pooled figure
hides it, and on the robot that run is the one that matters. A candidate is therefore *not
eligible* (it stays in the table, marked, with the reason) when its held-out error on any
held-out part (a held-out recording, or a held-out block of one recording) exceeds the affine
map's on that part: the forward error, and under ``objective="compensation"`` the offline
inverse error as well (a model that predicts a run worse than the affine map gives no ground to
trust its inverse there), or it has no inverse error at all under that objective.

Every held-out part compare_models scores has its output recorded, so the error there decides.
A prediction that leaves the outputs' range on a part is *flagged*, not excluded
(``range_flag``): the range is the one the part's training outputs reached, widened to the affine
map's own prediction on the part (the baseline's extrapolation) and, where the logs carry a
measured load, to the affine map in the input and the load (a load beyond the training loads
moves the whole loop); the flag is raised past ``range_margin`` times that range's span. Where
nothing is recorded (on the robot), the guard is the inverse's: InverseFeedforward holds its
commands to the identified input range (widened by its own ``range_margin``) and flags the
cycles it held. (Before issue 35 the range excess excluded a candidate even where its held-out
error on that very part was lower than the affine map's.)

The affine map is always eligible: the winner is never worse than it on any held-out part.
"""

from __future__ import annotations

from typing import Any

import numpy as np

AFFINE = "affine"
OBJECTIVES = ("prediction", "compensation")
#: the default allowance past the outputs' range, as a share of its span
RANGE_MARGIN = 0.1


def check_objective(objective: Any) -> str:
    """``objective``: "prediction" or "compensation" (ValueError otherwise)."""
    if objective not in OBJECTIVES:
        raise ValueError(f"objective must be 'prediction' or 'compensation' (got {objective!r})")
    return str(objective)


def check_range_margin(range_margin: Any) -> float:
    """``range_margin``: a finite number >= 0, or None (no range check; ValueError otherwise)."""
    if range_margin is None:
        return float("inf")
    ok = isinstance(range_margin, int | float) and not isinstance(range_margin, bool)
    if not (ok and np.isfinite(range_margin) and range_margin >= 0):
        raise ValueError(
            f"range_margin must be a number >= 0 (a share of the outputs' span) or None "
            f"(got {range_margin!r})"
        )
    return float(range_margin)


def part_rmse(validation: list[dict], name: str) -> list[float]:
    """The forward held-out rmse of ``name`` on each held-out part (NaN where it has none)."""
    out = []
    for slot in validation:
        pred = slot["predictions"].get(name)
        if pred is None or len(pred) == 0:
            out.append(float("nan"))
            continue
        e = np.asarray(slot["y"], dtype=float) - np.asarray(pred, dtype=float)
        out.append(float(np.sqrt(np.mean(e * e))))
    return out


def _range_excess(slot: dict, name: str) -> float:
    """How far (a share of the allowed range's span) ``name``'s prediction on the part leaves
    the training outputs' range widened to the affine map's prediction (and, where the logs
    carry a load, to the affine map in the input and the load: ``load_affine``); 0 inside it."""
    lo, hi = slot["train_range"]
    for baseline in (slot["predictions"].get(AFFINE), slot.get("load_affine")):
        if baseline is not None and len(baseline):
            lo, hi = min(lo, float(np.min(baseline))), max(hi, float(np.max(baseline)))
    span = hi - lo
    pred = np.asarray(slot["predictions"].get(name, ()), dtype=float)
    if pred.size == 0:
        return 0.0
    if not np.all(np.isfinite(pred)):
        return float("inf")
    past = max(lo - float(np.min(pred)), float(np.max(pred)) - hi, 0.0)
    if past == 0.0:
        return 0.0
    return past / span if span > 0 else float("inf")


def _describe_part(slot: dict, k: int) -> str:
    return slot.get("label") or f"held-out part {k + 1}"


def judge(rows: list[dict], validation: list[dict], objective: str, range_margin: float) -> None:
    """Mark each row: ``eligible``, ``excluded`` (the reason, or None), ``worst_part_ratio``
    (its largest held-out error on one part over the affine map's there, by the objective's
    error), ``range_excess`` (its prediction's largest excursion past the allowed output
    range, as a share of that range's span) and ``range_flag`` (in words where the excursion
    passes ``range_margin``, else None: a flag, never an exclusion, since the part's output is
    recorded and its error judges the candidate there). Rows that failed are left as they
    are."""
    base_row = next(r for r in rows if r["model"] == AFFINE)
    # compensation: the inverse error, and the forward one too (a model that predicts a run
    # worse than the affine map is no ground for trusting its inverse there)
    keys = ["val_rmse_parts"] + (["inv_rmse_parts"] if objective == "compensation" else [])
    for r in rows:
        if r.get("error"):
            r["eligible"] = False
            continue
        reasons: list[str] = []
        for key in keys:  # the last one is the objective's error
            r["worst_part_ratio"] = _worse_than_affine(r, base_row, key, validation, reasons)
        excess = [_range_excess(slot, r["model"]) for slot in validation]
        r["range_excess"] = float(max(excess)) if excess else 0.0
        r["range_flag"] = None
        if r["model"] != AFFINE and r["range_excess"] > range_margin:
            k = int(np.argmax(excess))
            r["range_flag"] = (
                f"prediction leaves the outputs' range by {_share(r['range_excess'])} of its "
                f"span on {_describe_part(validation[k], k)} (margin {_share(range_margin)}; "
                "recorded there: its error decides)"
            )
            if not np.isfinite(r["range_excess"]):  # a prediction that is not finite
                reasons.append("prediction not finite on " + _describe_part(validation[k], k))
        r["eligible"] = not reasons
        r["excluded"] = "; ".join(reasons) if reasons else None


def _worse_than_affine(r: dict, base_row: dict, key: str, validation, reasons: list) -> float:
    """Append to ``reasons`` where row ``r``'s error ``key`` (per held-out part) exceeds the
    affine map's; returns its largest ratio to the affine map's (NaN without one)."""
    if r["model"] == AFFINE:
        return 1.0
    base = base_row.get(key) or []
    parts = r.get(key) or []
    if len(parts) != len(base):  # no error of this kind (a failed inverse)
        parts = [float("nan")] * len(base)
    ratios = [
        c / b if b > 0 else (np.inf if c > b else 1.0) for c, b in zip(parts, base, strict=True)
    ]
    what = "inverse error" if key == "inv_rmse_parts" else "held-out error"
    if any(not np.isfinite(c) for c in parts) and key == "inv_rmse_parts":
        reasons.append(f"no {what} ({r.get('inv_error', 'the inverse failed')})")
    worse = [(k, q) for k, q in enumerate(ratios) if np.isfinite(parts[k]) and q > 1.0]
    if worse:
        k, q = max(worse, key=lambda kq: kq[1])
        where = _describe_part(validation[k], k) if k < len(validation) else f"part {k + 1}"
        more = f" (and {len(worse) - 1} more)" if len(worse) > 1 else ""
        reasons.append(f"{what} {q:.2f}x the affine map's on {where}{more}")
    finite = [q for q in ratios if np.isfinite(q)]
    return float(max(finite)) if finite else float("nan")


def _share(v: float) -> str:
    return "inf" if not np.isfinite(v) else f"{100 * v:.0f} %"


def sort_key(objective: str):
    """Rows: eligible ones first, then the excluded ones, then failures; each by the
    objective's normalised error."""
    metric = "inv_nrmse" if objective == "compensation" else "val_nrmse"

    def key(r: dict):
        v = r.get(metric, np.inf)
        v = v if v is not None and np.isfinite(v) else np.inf
        return (bool(r.get("error")), not r.get("eligible", False), v)

    return key
