"""Choosing a model: fit candidates on training data, score them on held-out data.

``compare_models(logs, models=[...], validate=...)`` fits every candidate and scores it on
held-out data against the affine baseline y = a x + b:

- ``validate="cv"`` (default): cross-validation. With several recordings each is held out in
  turn (the models are fitted on the others and simulated over it from its start); with one
  recording, ``folds`` contiguous blocks are held out in turn (the model is fitted on the
  other blocks, then runs over the *whole* input, its state carrying over as on the robot,
  and only the block's samples are counted). Every sample is scored once; the ranking is by
  the pooled held-out error, and the winner is then fitted on all the data.
- ``validate`` a number in (0, 1): one split; the last fraction of every recording is held
  out (scored as a block above); the winner is refitted on the whole recordings.
- ``validate`` a list of logs (or one): held-out recordings, simulated from their start; the
  winner is the fit on the training logs (not refitted: it already saw all of them).

A candidate ``Loaded(cls)`` (or the name ``"bwb+load"``, ``"backlash+load"``, ...) takes
the measured load the logs carry (``read_log(..., load=COLUMN)``): its load terms are fitted
with it, its predictions and its inverse (``LoadCompensated``) are given each log's load.
When every log (the held-out ones too) carries a load, the default candidates include
``Loaded(Backlash)``, ``Loaded(BoucWenBacklash)`` and ``Loaded(PrandtlIshlinskii)``, as they
include CurveAngleModel when the logs carry a curve angle.

The winner is never worse than the affine map on any held-out part: a candidate that is (by
the forward error; with ``objective="compensation"``, by the offline inverse error too)
cannot win and is shown with the reason (``tendonsheath._util.eligibility``). Every held-out part
has its output recorded, so its error decides there: a prediction that leaves the outputs'
range by more than ``range_margin`` of its span is flagged (``row["range_flag"]``), not
excluded. With ``parsimony`` p > 0, a
candidate with more parameters wins only if its error is more than p below that of every
eligible candidate with fewer (``tendonsheath._util.parsimony``).

The result is a :class:`Comparison`: ``.table`` (the eligible rows first, sorted by the
objective's nrmse, the affine baseline included, with each candidate's seconds), ``.winner``
(the affine baseline is a ``Polynomial(1)``), ``.fits``, ``.parts()`` (each candidate's error per
held-out part, over the affine map's there) and ``.report(dir)`` (loops and residuals).
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from html import escape as html_escape
from pathlib import Path
from typing import Any

import numpy as np

from .._util import eligibility
from .._util import parsimony as parsimony_rule
from .._util.atomic import save_figure, write_json, write_text
from .._util.compare_progress import CompareProgress
from .._util.typing import RecordingLike
from ..identify.core import SEARCH_DEADLINE
from ..identify.cross_validation import estimator_split, evaluate_splits, recording_splits
from ..identify.data import make_recordings
from ..identify.dynamic import is_dynamic_chain
from ..identify.estimator import Identifier
from ..identify.generic import identifiable
from ..identify.refine import REFINE_LIMIT
from ..models import (
    Backlash,
    BoucWenBacklash,
    Chain,
    CurveAngleModel,
    FirstOrderLag,
    GeneralizedPrandtlIshlinskii,
    HysteresisModel,
    LinearBlock,
    Loaded,
    Polynomial,
    PrandtlIshlinskii,
    SecondOrderLag,
)
from ..models.base import _REGISTRY
from ..models.linear_block import sample_time

AFFINE = "affine"
#: the least-squares polish's evaluations in each cross-validation fold (the fits that rank
#: the candidates; the winner's final fit has the full polish): measured on three tool-5 runs,
#: GeneralizedPrandtlIshlinskii's folds 48.7 s -> 24.1 s, its held-out rmse 0.14403 -> 0.14398
#: (benchmarks/compare_candidates_time.py)
FOLD_REFINE_EVALUATIONS = 40
#: the training samples of a cross-validation fold's fit past FOLD_THIN_ABOVE, where the
#: winner is refitted on all the data (the folds' fits only rank): a rate-independent
#: candidate's records thinned to about this many (every turning point kept:
#: data.thin_for_search), a dynamic chain's decimated (at most 4x). Five tool-5 runs of 10^4
#: samples with every default: 95 s -> 31 s on 2 cores (benchmarks/compare_speed.py). Folds
#: up to FOLD_THIN_ABOVE samples are fitted on every sample: the ranking of close candidates
#: can turn on the thinning (on three tool-5 runs of 4000 samples, thinned folds ranked
#: Loaded(BoucWenBacklash) over Loaded(Backlash), whose inverse does better on unseen runs)
FOLD_SAMPLES = 4000
FOLD_THIN_ABOVE = 16000


#: the load-aware default candidates (logs that carry a measured load): Loaded(base) around
#: the cheap invertible bases. Each named in compare_models on the three tool-5 training runs
#: of benchmarks/tool5_default_path.py (3 folds; a shared 2-core machine): Loaded(Backlash)
#: 5.7 s, Loaded(BoucWenBacklash) 3.3 s, Loaded(PrandtlIshlinskii) 1.3 s, held-out rmse 0.168,
#: 0.173 and 0.174 of the affine map's; Loaded(GeneralizedPrandtlIshlinskii) took 48.9 s and
#: Loaded(BoucWenBacklash+poly3) and +lag2 16-17 s each, for no lower error (0.179, 0.178 and
#: 0.175): they are named by hand ("gpi+load", "bwb+poly3+load", ...).
LOADED_BASES = (Backlash, BoucWenBacklash, PrandtlIshlinskii)


def default_models(curve_angle: bool = False, load: bool = False) -> list:
    """The default candidates: the rate-independent operators, a BoucWenBacklash with a cubic
    output map, and a rate-dependent Hammerstein chain (BoucWenBacklash followed by a
    second-order lag; ``"lag1+bwb"`` names the Wiener one, ``"pi+lag1"`` a PI one); also
    CurveAngleModel when the logs have a curve angle, and ``Loaded(Backlash)``,
    ``Loaded(BoucWenBacklash)`` and ``Loaded(PrandtlIshlinskii)`` (:data:`LOADED_BASES`) when
    they carry a measured load. Chains with a linear block need a time column with a uniform
    step; they are left out of the defaults without one.

    Parameters
    ----------
    curve_angle : bool, default False
        Whether the logs have a curve angle (adds CurveAngleModel).
    load : bool, default False
        Whether the logs carry a measured load (adds the load-aware candidates).

    Returns
    -------
    list
        Model classes, Chain and Loaded instances.
    """
    models: list = [
        Backlash,
        BoucWenBacklash,
        PrandtlIshlinskii,
        GeneralizedPrandtlIshlinskii,
        Chain(BoucWenBacklash(), Polynomial(3)),
        Chain(BoucWenBacklash(), SecondOrderLag()),
    ]
    if curve_angle:
        models.append(CurveAngleModel)
    if load:
        models += [Loaded(base) for base in LOADED_BASES]
    return models


#: the model classes compare_models can fit (identify supports them)
CANDIDATES = (
    "Backlash",
    "BoucWenBacklash",
    "PrandtlIshlinskii",
    "GeneralizedPrandtlIshlinskii",
    "BoucWen",
    "HystereticOscillator",
    "CurveAngleModel",
    "PlantModel",
)

_ALIASES = {
    "bwb": "BoucWenBacklash",
    "pi": "PrandtlIshlinskii",
    "gpi": "GeneralizedPrandtlIshlinskii",
    "bw": "BoucWen",
    "curve": "CurveAngleModel",
    "plant": "PlantModel",
}
_BLOCKS = {"lag1": FirstOrderLag, "lag2": SecondOrderLag}


_FORMS = "MODEL, MODEL+polyN, MODEL+oddN, MODEL+lag1, MODEL+lag2, lag1+MODEL or lag2+MODEL"


def _check_composite_name(text: str) -> None:
    """A composite name's shape: one or two parts, not empty, one of them a hysteresis model
    (a lag alone, or two lags, is no candidate), else a ValueError that says so."""
    parts = [p.strip().lower() for p in text.split("+")]
    if any(not p for p in parts):
        raise ValueError(f"model {text!r}: an empty part around '+'; the forms are {_FORMS}")
    if len(parts) > 2:
        raise ValueError(f"model {text!r}: {len(parts)} parts; at most two: {_FORMS}")
    if all(p in _BLOCKS for p in parts):
        raise ValueError(
            f"model {text!r}: a lag {'alone' if len(parts) == 1 else 'chained with a lag'} is "
            f"linear, no hysteresis model; chain a lag with one (e.g. {parts[0]}+bwb): {_FORMS}"
        )


def parse_model(spec: type[HysteresisModel] | HysteresisModel | str) -> Any:
    """A candidate from a class, a Chain instance or a name: ``BoucWenBacklash``, ``gpi``,
    ``bwb+poly3`` (Chain with a cubic), ``bwb+odd3`` (odd cubic), ``bwb+lag2`` / ``pi+lag1``
    (Hammerstein: then a second- / first-order lag), ``lag1+bwb`` (Wiener), ``plant`` (the
    grey-box :class:`~tendonsheath.models.PlantModel`; not a default candidate).

    Parameters
    ----------
    spec : type, Chain or str
        The candidate.

    Returns
    -------
    type or Chain
        A model class or a Chain instance.

    Raises
    ------
    ValueError
        Not a class, a Chain or a known name.
    """
    if isinstance(spec, Chain | Loaded) or (
        isinstance(spec, type) and issubclass(spec, HysteresisModel)
    ):
        return spec
    if not isinstance(spec, str):
        raise ValueError(f"a model is a class, a Chain or a name (got {spec!r})")
    text = spec.strip()
    if text.lower().endswith("+load"):  # the measured load's terms around a model
        return Loaded(parse_model(text[: -len("+load")]))
    _check_composite_name(text)
    base, _, tail = text.partition("+")

    def cls_of(name):
        name = _ALIASES.get(name.lower(), name)
        lookup = {k.lower(): v for k, v in _REGISTRY.items()}
        found = lookup.get(name.lower())
        if found is None or (found.__name__ not in CANDIDATES and not identifiable(found)):
            raise ValueError(
                f"unknown model {name!r}; candidates: {', '.join(CANDIDATES)} (aliases "
                f"{', '.join(sorted(_ALIASES))}) or any other model identify takes, with "
                "+polyN / +oddN for a polynomial output map"
            )
        return lookup[name.lower()]

    if base.strip().lower() in _BLOCKS:  # Wiener: lagN+model
        block = _BLOCKS[base.strip().lower()]
        return Chain(block(), cls_of(tail.strip())())
    cls = cls_of(base)
    if not tail:
        return cls
    if tail.strip().lower() in _BLOCKS:  # Hammerstein: model+lagN
        return Chain(cls(), _BLOCKS[tail.strip().lower()]())
    m = re.fullmatch(r"(poly|odd)(\d+)", tail.strip().lower())
    if not m:
        raise ValueError(f"model {text!r}: the part after '+' must be polyN, oddN, lag1 or lag2")
    degree = int(m.group(2))
    if degree < 1:
        raise ValueError(f"model {text!r}: the degree must be >= 1")
    return Chain(cls(), Polynomial(degree, odd=m.group(1) == "odd"))


def model_name(candidate: type[HysteresisModel] | Chain) -> str:
    """BoucWenBacklash, BoucWenBacklash+poly3, BoucWenBacklash+lag2 (Hammerstein),
    lag1+BoucWenBacklash (Wiener).

    Parameters
    ----------
    candidate : type or Chain
        A model class or a Chain instance.

    Returns
    -------
    str
        Its name in the comparison table.
    """
    if isinstance(candidate, Loaded):
        base = candidate.base
        return f"Loaded({model_name(base if isinstance(base, Chain) else type(base))})"
    if isinstance(candidate, Chain):
        short = {FirstOrderLag: "lag1", SecondOrderLag: "lag2"}
        if isinstance(candidate.second, LinearBlock):
            return f"{type(candidate.first).__name__}+{short[type(candidate.second)]}"
        if isinstance(candidate.first, LinearBlock):
            return f"{short[type(candidate.first)]}+{type(candidate.second).__name__}"
        p = candidate.second
        assert isinstance(p, Polynomial)  # a static chain's second part
        kind = "odd" if getattr(p, "options", {}).get("odd") else "poly"
        return f"{type(candidate.first).__name__}+{kind}{p.degree}"
    return candidate.__name__


INVERSE_NOTE = (
    "inv: the held-out input the model's InverseFeedforward would have commanded for the "
    "recorded output (low-passed; tendonsheath.apps.inverse_error), against the input that "
    "produced it"
)


def _percent(value) -> str:
    return "-" if value is None or not np.isfinite(value) else f"{100 * value:.3f}%"


def _plain(value) -> str:
    return "-" if value is None or not np.isfinite(value) else f"{value:.3f}"


def _ratio_cell(ratio: float, worse: bool) -> str:
    """A ratio to the affine map's error in the per-part table: 3 decimals, 5 where 3 would
    round it to 1.000 (which side of 1 it is on decides eligibility), ``*`` where it is
    worse than the affine map's."""
    if ratio is None or not np.isfinite(ratio):
        return "-"
    close = ratio != 1.0 and abs(ratio - 1.0) < 5e-4
    return (f"{ratio:.5f}" if close else f"{ratio:.3f}") + ("*" if worse else "")


PARTS_CAPTION = (
    "Held-out rmse of each candidate on each held-out part, over the affine map's on that "
    "part. A part is one held-out recording, or one held-out block of a recording: {names}. "
    "*: worse than the affine map on that part (the candidate cannot win)."
)


def _parts_html(parts: dict[str, Any]) -> str:
    """The per-part table of report.html (Comparison.parts() as the CLI prints it: the ratios
    to the affine map's rmse, ``*`` where worse); empty with fewer than two parts (the main
    table's ratio is then the part's)."""
    labels = parts["labels"]
    if len(labels) < 2:
        return ""
    names = ", ".join(f"{j + 1} = {html_escape(n)}" for j, n in enumerate(labels))
    head = "<th>model</th>" + "".join(
        f"<th title='{html_escape(n, quote=True)}'>part {j + 1}</th>" for j, n in enumerate(labels)
    )
    body = "".join(
        f"<tr><td>{html_escape(name)}</td>"
        + "".join(f"<td>{_ratio_cell(q, w)}</td>" for q, w in zip(ratios, worse, strict=True))
        + "</tr>"
        for name, ratios, worse in zip(
            parts["models"], parts["ratio_to_affine"], parts["worse_than_affine"], strict=True
        )
    )
    return (
        "<h2>Held-out rmse on each held-out part / the affine map's there</h2>"
        # a figure's caption, not the table's: that one would be as narrow as the table
        f"<figure><table class='parts' border='1' cellpadding='4'><tr>{head}</tr>{body}</table>"
        f"<figcaption>{PARTS_CAPTION.format(names=names)}</figcaption></figure>"
    )


def _parts_json(parts: dict[str, Any]) -> dict[str, Any]:
    """Comparison.parts() for comparison.json: lists, a missing figure as null (JSON has no
    NaN)."""

    def plain(a: np.ndarray) -> list:
        return [[float(v) if np.isfinite(v) else None for v in row] for row in a]

    return {
        "labels": parts["labels"],
        "models": parts["models"],
        "rmse": plain(parts["rmse"]),
        "ratio_to_affine": plain(parts["ratio_to_affine"]),
        "worse_than_affine": parts["worse_than_affine"].tolist(),
        "inv_rmse": plain(parts["inv_rmse"]),
        "inv_ratio_to_affine": plain(parts["inv_ratio_to_affine"]),
    }


@dataclass
class Comparison:
    """Result of :func:`compare_models`. ``table`` rows: model, n_params, train_rmse,
    train_nrmse, val_rmse, val_nrmse, val_fit_percent, val_max_abs, ratio_to_affine, the
    offline inverse error inv_rmse, inv_nrmse (over the held-out inputs' range),
    inv_ratio_to_affine and inv_out_of_range (the share of held-out cycles whose command the
    identified input range held; :mod:`tendonsheath.apps.inverse_error`), seconds
    and cpu_seconds (fitting and scoring over all folds), error (if the fit failed) and
    status ("out of time" past the time budget); per held-out part (a held-out recording or
    block) val_rmse_parts and inv_rmse_parts; eligible, excluded (why a candidate cannot win,
    or None), worst_part_ratio, range_excess and range_flag (``_util.eligibility``). Sorted
    with the eligible rows first, each group by the objective's error (val_nrmse, or
    inv_nrmse for "compensation"); failures last.
    ``fits``: each candidate's Fit (a list of one per fold under cross-validation);
    ``winner_fit``: the Fit of ``winner`` (None for the affine map).

    Parameters
    ----------
    table : list of dict
        One row per candidate (see above).
    winner : HysteresisModel
        The best model, fitted on all the data.
    winner_name : str
        Its name.
    fits : dict, optional
        Each candidate's Fit (a list per fold under cross-validation).
    validation : list of dict, optional
        The held-out data and each model's predictions (for the report's figures).
    mode : str, default ""
        How the models were validated.
    winner_fit : Fit, optional
        The winner's Fit.
    objective : str, default "prediction"
        What ranked the candidates: "prediction" (the held-out forward error) or
        "compensation" (the offline inverse error).
    rule : str, default ""
        The ranking and who could not win, in words.
    parsimony : float, default 0.0
        The parsimony rule's margin (``tendonsheath._util.parsimony``): a candidate with more
        parameters won only if its error was more than this share below every smaller
        eligible candidate's.
    choice : str, default ""
        Why the winner won where the parsimony rule chose it over a lower error, or which
        smaller candidate came close ("" otherwise).
    """

    table: list[dict[str, Any]]
    winner: HysteresisModel
    winner_name: str
    fits: dict[str, Any] = field(default_factory=dict, repr=False)
    validation: list[dict[str, Any]] = field(default_factory=list, repr=False)
    mode: str = ""
    winner_fit: Any = field(default=None, repr=False)
    objective: str = "prediction"
    rule: str = ""
    parsimony: float = 0.0
    choice: str = ""

    def row(self, name: str) -> dict[str, Any]:
        """The table's row of one candidate.

        Parameters
        ----------
        name : str
            The candidate's name (:func:`model_name`).

        Returns
        -------
        dict
            Its row.

        Raises
        ------
        KeyError
            No candidate of that name.
        """
        for r in self.table:
            if r["model"] == name:
                return r
        raise KeyError(name)

    def text(self) -> str:
        """The table as text, one line per candidate, and the winner.

        Returns
        -------
        str
            Several lines (also ``str(comparison)``).
        """
        w = max([34, *(len(r["model"]) for r in self.table)])
        spread = self.fold_spread()
        lines = [
            f"{'model':<{w}} {'train rmse':>11} {'val rmse':>11} {'val nrmse':>10} {'/affine':>8}"
            f" {'per part':>11} {'inv nrmse':>10} {'/affine':>8}"
        ]
        excluded, flagged = [], []
        for r in self.table:
            if r.get("error"):
                lines.append(f"{r['model']:<{w}} {r.get('status', 'failed')}: {r['error']}")
                continue
            mark = ""
            if r.get("excluded"):
                excluded.append(r)
                mark = f" [x{len(excluded)}]"
            if r.get("range_flag"):
                flagged.append(r)
                mark += f" [!{len(flagged)}]"
            lines.append(
                f"{r['model']:<{w}} {r['train_rmse']:>11.4g} {r['val_rmse']:>11.4g} "
                f"{100 * r['val_nrmse']:>9.3f}% {r['ratio_to_affine']:>8.3f} "
                f"{spread.get(r['model'], ''):>11} "
                f"{_percent(r.get('inv_nrmse')):>10} {_plain(r.get('inv_ratio_to_affine')):>8}"
                + mark
            )
        for k, r in enumerate(excluded, start=1):
            lines.append(f"[x{k}] {r['model']} cannot win: {r['excluded']}")
        for k, r in enumerate(flagged, start=1):
            lines.append(f"[!{k}] {r['model']}: {r['range_flag']}")
        lines.append(f"winner: {self.winner_name} ({self.mode})")
        if self.choice:
            lines.append(self.choice)
        if self.rule:
            lines.append(f"choice: {self.rule}")
        lines.append(f"inverse: {INVERSE_NOTE}")
        return "\n".join(lines + self.parts_text())

    def fold_spread(self) -> dict[str, str]:
        """Each candidate's held-out error over the affine map's, from its best held-out part
        to its worst ("0.31-0.56"; the spread over the folds), where there are two parts or
        more.

        Returns
        -------
        dict of str to str
            Model name -> the range, as the table shows it.
        """
        p = self.parts()
        if len(p["labels"]) < 2:
            return {}
        out = {}
        for name, ratios in zip(p["models"], p["ratio_to_affine"], strict=True):
            q = ratios[np.isfinite(ratios)]
            if q.size:
                out[name] = f"{np.min(q):.2f}-{np.max(q):.2f}"
        return out

    def parts(self) -> dict[str, Any]:
        """Each candidate's held-out error on each held-out part (a held-out recording, or a
        held-out block of one), against the affine map's there: the figures behind the
        eligibility rule, as plain NumPy arrays.

        Returns
        -------
        dict
            ``labels``: a name per held-out part (k of them); ``models``: the candidates in
            the table's order, the failed ones left out (m of them); ``rmse``: (m, k) array
            of the held-out rmse (output units); ``ratio_to_affine``: (m, k) array, each over
            the affine map's rmse on that part; ``worse_than_affine``: (m, k) bool array,
            True where the ratio exceeds 1 (a part that keeps the candidate from winning);
            ``inv_rmse`` and ``inv_ratio_to_affine``: the same for the offline inverse error
            (NaN where a candidate has none).
        """
        rows = [r for r in self.table if not r.get("error")]
        base = next((r for r in rows if r["model"] == AFFINE), None)
        k = len(base["val_rmse_parts"]) if base and base.get("val_rmse_parts") else 0
        labels = [v.get("label", "") for v in self.validation] if self.validation else []
        if len(labels) != k:
            labels = [f"part {j + 1}" for j in range(k)]

        def matrix(key: str) -> tuple[np.ndarray, np.ndarray]:
            out = np.full((len(rows), k), np.nan)
            for i, r in enumerate(rows):
                values = r.get(key) or []
                if len(values) == k:
                    out[i] = values
            ref = out[rows.index(base)] if base is not None else np.full(k, np.nan)
            with np.errstate(divide="ignore", invalid="ignore"):
                return out, out / ref

        rmse, ratio = matrix("val_rmse_parts")
        inv, inv_ratio = matrix("inv_rmse_parts")
        return {
            "labels": labels,
            "models": [r["model"] for r in rows],
            "rmse": rmse,
            "ratio_to_affine": ratio,
            "worse_than_affine": np.nan_to_num(ratio, nan=0.0) > 1.0,
            "inv_rmse": inv,
            "inv_ratio_to_affine": inv_ratio,
        }

    def parts_text(self) -> list[str]:
        """The held-out error per held-out part over the affine map's, one line per candidate
        (a ``*`` where it exceeds 1: that part keeps the candidate from winning); no lines
        with fewer than two parts (the table's ratio is then the part's).

        Returns
        -------
        list of str
            The lines.
        """
        p = self.parts()
        k = len(p["labels"])
        if k < 2:
            return []
        width = max([34, *(len(n) + 1 for n in p["models"])])
        head = f"{'held-out rmse / affine':<{width}}" + "".join(f" {j + 1:>8}" for j in range(k))
        lines = [head]
        for name, ratios, worse in zip(
            p["models"], p["ratio_to_affine"], p["worse_than_affine"], strict=True
        ):
            cells = "".join(f" {_ratio_cell(q, w):>8}" for q, w in zip(ratios, worse, strict=True))
            lines.append(f"{name:<{width}}{cells}")
        lines.append("parts: " + ", ".join(f"{j + 1} = {n}" for j, n in enumerate(p["labels"])))
        lines.append("*: worse than the affine map on that part (the candidate cannot win)")
        return lines

    def excluded(self) -> dict[str, str]:
        """The candidates that could not win, with the reason.

        Returns
        -------
        dict of str to str
            Model name -> why it was excluded (see ``tendonsheath._util.eligibility``).
        """
        return {r["model"]: r["excluded"] for r in self.table if r.get("excluded")}

    def __str__(self) -> str:
        return self.text()

    def to_dict(self) -> dict[str, Any]:
        """The comparison as a JSON-ready dict: mode, table, winner and the winner's model.

        Returns
        -------
        dict
            What comparison.json holds.
        """
        return {
            "mode": self.mode,
            "objective": self.objective,
            "rule": self.rule,
            "parsimony": self.parsimony,
            "choice": self.choice,
            "part_labels": self.parts()["labels"],
            "parts": _parts_json(self.parts()),
            "table": self.table,
            "winner": self.winner_name,
            "winner_model": self.winner.to_dict(),
        }

    def report(self, path: str | Path) -> Path:
        """Write DIR/comparison.json, DIR/winner.json (the winner's model file, which
        ``load_model`` and ``tendonsheath predict`` read), DIR/loops.png, DIR/residuals.png
        and DIR/report.html (validation loops and residuals of every model); returns the HTML
        path.

        Parameters
        ----------
        path : str or Path
            The folder (made as needed).

        Returns
        -------
        Path
            DIR/report.html.
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        out = Path(path)
        out.mkdir(parents=True, exist_ok=True)
        write_json(out / "comparison.json", self.to_dict())
        self.winner.to_json(out / "winner.json")
        names = [r["model"] for r in self.table if not r.get("error")]
        cols = min(3, len(names))
        rows = int(np.ceil(len(names) / cols))
        figs = {}
        for kind in ("loops", "residuals"):
            fig, axes = plt.subplots(rows, cols, figsize=(4.2 * cols, 3.4 * rows), squeeze=False)
            for ax, name in zip(axes.flat, names, strict=False):
                for v in self.validation:
                    pred = v["predictions"].get(name)
                    if pred is None:
                        continue
                    if kind == "loops":
                        ax.plot(v["x"], v["y"], color="0.6", lw=1.0, label="measured")
                        ax.plot(v["x"], pred, lw=1.0, label="model")
                        ax.set_xlabel("input")
                        ax.set_ylabel("output")
                    else:
                        ax.plot(v["s"], v["y"] - pred, lw=0.8)
                        ax.set_xlabel("time" if v["has_t"] else "sample")
                        ax.set_ylabel("measured - model")
                r = self.row(name)
                ax.set_title(f"{name}\nval rmse {r['val_rmse']:.3g} (output units)", fontsize=9)
                if kind == "loops":  # one entry each, however many validation files
                    handles = dict(zip(*reversed(ax.get_legend_handles_labels()), strict=True))
                    ax.legend(handles.values(), handles.keys(), fontsize=7)
            for ax in list(axes.flat)[len(names) :]:
                ax.axis("off")
            fig.tight_layout()
            figs[kind] = out / f"{kind}.png"
            save_figure(fig, figs[kind], dpi=110)
            plt.close(fig)
        head = "".join(
            f"<th>{h}</th>"
            for h in (
                "model",
                "train rmse [output units]",
                "val rmse [output units]",
                "val nrmse [%]",
                "val rmse / affine's",
                "inverse nrmse [%]",
                "cannot win because",
            )
        )
        body = "".join(
            f"<tr><td>{r['model']}</td><td>{r['train_rmse']:.4g}</td><td>{r['val_rmse']:.4g}"
            f"</td><td>{100 * r['val_nrmse']:.3f}</td><td>{r['ratio_to_affine']:.3f}</td>"
            f"<td>{_percent(r.get('inv_nrmse')).rstrip('%')}</td>"
            f"<td>{html_escape(r.get('excluded') or '')}</td></tr>"
            for r in self.table
            if not r.get("error")
        )
        html = (
            "<!doctype html><html><head><meta charset='utf-8'><title>model comparison</title>"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>"
            "<style>img{max-width:100%;height:auto}figure{margin:1em 0}</style>"  # 1280 px
            "</head><body><h1>Model comparison</h1>"
            f"<p>{html_escape(self.mode)}; winner: <b>{self.winner_name}</b></p>"
            f"<p>{html_escape(self.rule)}</p>"
            f"<table border='1' cellpadding='4'><tr>{head}</tr>{body}</table>"
            + _parts_html(self.parts())
            + "<h2>Validation loops</h2><img src='loops.png'>"
            "<h2>Validation residuals</h2><img src='residuals.png'></body></html>"
        )
        page = out / "report.html"
        write_text(page, html)
        return page


def _as_items(logs) -> list:
    """The recordings given: one (a Log, a tuple) or a sequence of them, as a list."""
    if logs is None:
        return []
    if isinstance(logs, tuple) and len(logs) in (3, 4) and not hasattr(logs[0], "x"):
        logs = [logs]
    if hasattr(logs, "x") and hasattr(logs, "y"):
        logs = [logs]
    return list(logs)


def _as_recs(logs) -> list:
    items = _as_items(logs)
    return make_recordings(recordings=items) if items else []


def _uniform(recs) -> bool:
    """Every recording has a time column with a uniform step (linear blocks need one)."""
    try:
        for r in recs:
            sample_time(r.t)
    except ValueError:
        return False
    return True


def _affine(recs) -> np.ndarray:
    x = np.concatenate([r.x for r in recs])
    y = np.concatenate([r.y for r in recs])
    A = np.column_stack([np.ones_like(x), x])
    return np.linalg.lstsq(A, y, rcond=None)[0]  # [b, a]


def _piece(r, a: int, b: int):
    return r.take(slice(a, b))


MIN_PIECE = 20  # samples of a training piece in blocked folds (shorter ones are dropped)


def _folds(recs, folds: int | None) -> tuple[list[tuple[list, list]], str]:
    """Cross-validation folds: (training recordings, [(recording, first, end) scored]).

    Several recordings: leave one recording out (at most 10 folds; more recordings are
    grouped round-robin into ``folds`` or 5 groups). One recording: ``folds`` (default 3)
    contiguous blocks; each block is scored with the model run over the whole recording
    (its state carries over, as on the robot) and the model is fitted on the other blocks:
    the part before the block, and the part after it simulated from the block's start
    (its input is known) but counted only after the block's end.
    """
    if len(recs) >= 2:
        return recording_splits(recs, folds)
    (r,) = recs
    k = 3 if folds is None else int(folds)
    if k < 2:
        raise ValueError(f"folds: at least 2 are needed (got {folds})")
    edges = np.linspace(0, r.n, k + 1).astype(int)
    if np.min(np.diff(edges)) < MIN_PIECE:
        raise ValueError(
            f"{r.n} samples are too few for {k} folds of at least {MIN_PIECE} samples each"
        )
    out = []
    for j in range(k):
        a, b = int(edges[j]), int(edges[j + 1])
        train = [_piece(r, 0, a)] if a >= MIN_PIECE else []
        if r.n - b >= MIN_PIECE:
            # after the held-out block: run from its start (the input is known), count
            # only from its end, so the state there is the one the data built up. The
            # block's outputs are not passed on at all: they are replaced by the affine
            # map of the training samples (never counted; only data scales see them).
            after = _piece(r, a, r.n)
            after.skip = b - a
            mask = np.ones(r.n, dtype=bool)
            mask[a:b] = False
            A = np.column_stack([np.ones(int(mask.sum())), r.x[mask]])
            c0, c1 = np.linalg.lstsq(A, r.y[mask], rcond=None)[0]
            after.y = after.y.copy()
            after.y[: b - a] = c0 + c1 * after.x[: b - a]
            train.append(after)
        out.append((train, [(r, a, b)]))
    return out, f"cross-validation: {k} contiguous blocks of the recording"


SETTLE_FRACTION = 0.05  # of the input's range: a reversal counts once the input moves back this far
SETTLE_NOTE = "each run's start until the input's first reversal is neither fitted nor scored"


def _settle(x: np.ndarray) -> int:
    """Samples before the input's first reversal (by more than SETTLE_FRACTION of its
    range), at most a quarter of them: until then a hysteresis model's output depends on
    its unknown initial state (a run's start is at rest, a piece's start mid-record is
    not), afterwards on the input history it has seen."""
    tol = SETTLE_FRACTION * float(np.ptp(x))
    cap = x.size // 4
    moved = np.flatnonzero(np.abs(x - x[0]) > tol)
    if tol <= 0.0 or moved.size == 0:
        return 0
    if x[moved[0]] > x[0]:  # rising first: the first drop from the running maximum
        back = np.flatnonzero(np.maximum.accumulate(x) - x > tol)
    else:
        back = np.flatnonzero(x - np.minimum.accumulate(x) > tol)
    return int(min(back[0] if back.size else cap, cap))


def _without_initial_transients(splits):
    """Every simulated run starts from the model's rest state, not the robot's state: the
    samples before the input's first reversal are neither fitted (a training piece's skip)
    nor scored (a held-out block's first sample), for every candidate and the affine map."""
    out = []
    for train, evals in splits:
        train = [replace(r, skip=max(r.skip, _settle(r.x))) for r in train]
        train = [r for r in train if r.n - r.skip >= MIN_PIECE]
        kept = [(r, max(a, _settle(r.x)), b) for r, a, b in evals]
        out.append((train, [(r, a, b) for r, a, b in kept if b - a >= 1]))
    return out


def compare_models(
    logs: Sequence[RecordingLike],
    models: Sequence | None = None,
    validate: float | str | Sequence | Any = "cv",
    *,
    folds: int | None = None,
    curve_angle: float | None = None,
    seed: int | None = 0,
    maxiter: int = 100,
    popsize: int = 15,
    workers: int | None = None,
    progress: bool = False,
    refit: bool = True,
    on_fit: Callable[[str, float], object] | None = None,
    time_budget: float | None = None,
    objective: str = "prediction",
    range_margin: float | None = eligibility.RANGE_MARGIN,
    parsimony: float = 0.0,
) -> Comparison:
    """Fit each candidate on training data and rank them on held-out data.

    ``logs``: :class:`~tendonsheath.io.Log` objects or (t, x, y[, curve_angle]) tuples (a
    tuple's curve angle may be a :class:`~tendonsheath.Route`, e.g. a sensed shape: the
    models that take the curve angle then use its distribution of curvature).
    ``models``: classes, Chain instances or names (see :func:`parse_model`); default
    :func:`default_models`. ``validate``:

    - ``"cv"`` (default): cross-validation, every sample held out once. Several recordings:
      leave one recording out; one recording: ``folds`` (default 3) contiguous blocks, each
      scored with the model fitted on the others. The winner is then fitted on all the data.
    - a fraction: the last part of every recording is held out (one split);
    - held-out logs: fitted on ``logs``, scored on these (the winner is that fit).

    ``curve_angle`` (a number) applies to recordings without one. ``on_fit(name, seconds)``
    is called after each candidate. ``progress``: a bar over the fits (candidate, fold,
    elapsed time and ETA) on a terminal. Each row's ``seconds`` (wall) and ``cpu_seconds``
    are the candidate's fitting and scoring time over all folds.

    A model choice that never misleads: a candidate whose held-out error (and, for
    "compensation", its inverse error) on any held-out part (a held-out recording or block)
    exceeds the affine map's cannot win; it stays in the table, marked with the reason
    (``row["excluded"]``, :meth:`Comparison.excluded`). Among the others the pooled held-out
    error ranks; the table shows each candidate's spread over the parts
    (:meth:`Comparison.fold_spread`). The gate is a worst-part rule against the affine map;
    ranking by the worst part or by a one-standard-error rule on top of it picked worse
    winners on runs no rule saw (``benchmarks/choice_few_runs.py``: two training runs of real
    drives, the winner judged on every other run). The held-out outputs are recorded, so
    their error decides: a prediction that leaves the outputs' range by more than
    ``range_margin`` is flagged (``row["range_flag"]``), not excluded. With logs that carry a
    measured load (all of them, the held-out ones too), the default candidates include the
    load-aware ones (:func:`default_models`).
    ``objective="compensation"`` ranks by the offline inverse error instead of the forward
    one (:mod:`tendonsheath.apps.inverse_error`).

    ``time_budget`` (seconds of wall clock for the candidates' cross-validation): a global
    search running at the deadline stops after its generation; a candidate whose folds end
    past it, or that was not started, gets a row with ``status`` "out of time" and an
    ``error`` saying so (never ranked, never dropped). The winner's final fit on all the
    data comes after the budget (about one fold's time). Where the winner is refitted on all
    the data, the folds' fits only rank the candidates: their least-squares polish stops
    after :data:`FOLD_REFINE_EVALUATIONS` evaluations (the final fit has the full polish).

    Parameters
    ----------
    logs : list of Log or tuple
        The recordings.
    models : sequence, optional
        The candidates (default :func:`default_models`).
    validate : "cv", float or sequence of Log, default "cv"
        Cross-validation, a held-out fraction, or held-out logs.
    folds : int, optional
        Blocks of a single recording's cross-validation (default 3).
    curve_angle : float, optional
        The curve angle (rad) of recordings without one.
    seed : int or None, default 0
        Seed of every identification.
    maxiter : int, default 100
        Generations of each search.
    popsize : int, default 15
        Population per parameter of each search.
    workers : int, optional
        Threads of the batched simulations (default all cores).
    progress : bool, default False
        Show a progress bar.
    refit : bool, default True
        With a held-out fraction, fit the winner on all the data (False: keep its fit on the
        training part); cross-validation always does.
    on_fit : callable, optional
        Called as on_fit(name, seconds) after each candidate.
    time_budget : float, optional
        Seconds of wall clock for the candidates' cross-validation.
    objective : {"prediction", "compensation"}, default "prediction"
        What ranks the candidates: the held-out forward error (val_nrmse), or the offline
        inverse error (inv_nrmse: how well the model's inverse would compensate).
    range_margin : float or None, default 0.1
        How far (a share of the outputs' span) a candidate's held-out prediction may leave
        the range the training outputs (or the affine map's prediction) reached before it is
        flagged (``range_flag``; a flag, not an exclusion); None: no range flag.
    parsimony : float, default 0.0
        A candidate with more parameters wins only by this margin: the winner is the eligible
        candidate with the fewest parameters whose error is within (1 + parsimony) of the
        best one's (``tendonsheath._util.parsimony``; 0: the lowest error wins).

    Returns
    -------
    Comparison
        The table, the winner and the fits.

    Raises
    ------
    ValueError
        Bad logs, models, validation, time budget or parsimony.
    """
    _check_time_budget(time_budget)
    margin_of_parsimony = parsimony_rule.check_parsimony(parsimony)
    objective = eligibility.check_objective(objective)
    margin = eligibility.check_range_margin(range_margin)
    recs = make_recordings(recordings=list(_as_recs(logs)), curve_angle=curve_angle)
    has_angle = all(r.curve_angle is not None for r in recs)
    splits, mode = _splits(recs, validate, folds, curve_angle)
    # a load every recording carries, the held-out ones too: the load-aware defaults
    scored = [r for _, evals in splits for r, _, _ in evals]
    has_load = all(getattr(r, "load", None) is not None for r in [*recs, *scored])
    candidates, names = _candidates(models, recs, has_angle, has_load)
    # one estimator per candidate, cloned per fold; one bar for the comparison
    settings: dict[str, Any] = dict(
        seed=seed, maxiter=maxiter, popsize=popsize, workers=workers, progress=False
    )
    estimators = [Identifier(c, **settings) for c in candidates]
    cv = isinstance(validate, str)
    whole_runs = (cv and len(recs) >= 2) or not isinstance(validate, str | int | float)
    splits = _without_initial_transients(splits)
    labels = _part_labels(splits, recs, logs, validate, whole_runs)
    mode += "; " + SETTLE_NOTE
    validation = _validation_slots(splits, labels)

    b, a = _affine(recs if not isinstance(validate, int | float) or refit else splits[0][0])
    final = cv or (refit and isinstance(validate, int | float))
    run = _Run(splits, validation, time_budget, progress, len(candidates), final)
    token = SEARCH_DEADLINE.set(run.deadline)
    # folds whose fits only rank (the winner is refitted on all the data): a shorter polish
    capped = REFINE_LIMIT.set(FOLD_REFINE_EVALUATIONS if final else None)
    try:
        rows, fits = run.all_candidates(estimators, names, has_angle, on_fit)
        fits[AFFINE] = Polynomial(coefficients=[b, a])
    finally:
        REFINE_LIMIT.reset(capped)
        SEARCH_DEADLINE.reset(token)
    try:
        eligibility_note = _judge(rows, validation, objective, margin)
        winner, winner_fit, best, choice = _winner(
            rows, fits, (estimators, names, recs), run, objective, margin_of_parsimony
        )
    finally:
        run.view.close()
    found = Comparison(rows, winner, best, fits, validation, mode, winner_fit, objective)
    return replace(found, rule=eligibility_note, parsimony=margin_of_parsimony, choice=choice)


def _judge(rows, validation, objective: str, margin: float) -> str:
    """Each row's held-out error per part and its eligibility (see tendonsheath._util.eligibility);
    the rule in words."""
    for r in rows:
        if not r.get("error"):
            r["val_rmse_parts"] = eligibility.part_rmse(validation, r["model"])
    eligibility.judge(rows, validation, objective, margin)
    what = "held-out or inverse error" if objective == "compensation" else "held-out error"
    rule = (
        f"ranked by {objective}: a candidate whose {what} exceeds the affine map's on any "
        "held-out part cannot win"
    )
    if np.isfinite(margin):
        rule += (
            f"; a prediction that leaves the outputs' range by more than {100 * margin:g} % of "
            "its span is flagged, not excluded (the held-out outputs are recorded: their "
            "error decides)"
        )
    return rule


def _check_time_budget(time_budget) -> None:
    if time_budget is not None and not (
        isinstance(time_budget, int | float) and time_budget > 0 and np.isfinite(time_budget)
    ):
        raise ValueError(f"time_budget must be a number of seconds > 0 (got {time_budget!r})")


def _candidates(models, recs, has_angle: bool, has_load: bool) -> tuple[list, list[str]]:
    """The candidates (given, or the defaults that the recordings support: the curve-angle
    one with a curve angle, the load-aware ones with a measured load) and their names."""
    if models:
        candidates = [parse_model(m) for m in models]
    else:
        candidates = default_models(has_angle, has_load)
        if not _uniform(recs):
            candidates = [c for c in candidates if not is_dynamic_chain(c)]
    names = [model_name(c) for c in candidates]
    if len(set(names)) != len(names):
        raise ValueError(f"the candidate models must differ (got {names})")
    return candidates, names


def _splits(recs, validate, folds, curve_angle) -> tuple[list, str]:
    """Training / validation split(s): a list of (training recordings, scored segments), and
    the mode's description."""
    if isinstance(validate, str):
        if validate != "cv":
            raise ValueError(
                f"validate: 'cv', a held-out fraction or held-out logs (got {validate!r})"
            )
        return _folds(recs, folds)
    if isinstance(validate, int | float) and not isinstance(validate, bool):
        return _held_out_fraction(recs, float(validate))
    vrecs = make_recordings(recordings=list(_as_recs(validate)), curve_angle=curve_angle)
    if not vrecs:
        raise ValueError("validate: give 'cv', a held-out fraction or held-out logs")
    return [(recs, [(r, 0, r.n) for r in vrecs])], f"held out: {len(vrecs)} validation recording(s)"


def _held_out_fraction(recs, frac: float) -> tuple[list, str]:
    """One split: the last ``frac`` of every recording held out."""
    if not 0.0 < frac < 1.0:
        raise ValueError(f"validate: the held-out fraction must be in (0, 1) (got {frac})")
    train, evals = [], []
    for i, r in enumerate(recs):
        if r.t is not None:
            cut = r.t[0] + (1.0 - frac) * (r.t[-1] - r.t[0])
            k = int(np.searchsorted(r.t, cut))
        else:
            k = int(round((1.0 - frac) * r.n))
        if k < 20 or r.n - k < 3:
            raise ValueError(
                f"recording {i}: {r.n} samples are too few to hold out {frac:g} of them"
            )
        train.append(_piece(r, 0, k))
        evals.append((r, k, r.n))
    return [(train, evals)], f"held out: the last {100 * frac:g} % of each recording"


def _validation_slots(splits, labels: list[str]) -> list[dict]:
    """One record per scored segment (a held-out part), for the report's loops and residuals
    and the candidates' eligibility: its fold, label and the training outputs' range."""
    slots = [
        {
            "x": r.x[a:b],
            "y": r.y[a:b],
            "s": (r.t[a:b] if r.t is not None else np.arange(a, b)),
            "has_t": r.t is not None,
            "predictions": {},
            "fold": k,
            "train_range": _output_range(train),
            "load_affine": _load_affine(train, r, a, b),
        }
        for k, (train, evals) in enumerate(splits)
        for r, a, b in evals
    ]
    for slot, label in zip(slots, labels, strict=True):
        slot["label"] = label
    return slots


def _output_range(train) -> tuple[float, float]:
    """The range of the training outputs a fold's models were fitted on (counted samples)."""
    ys = [r.y[r.skip :] for r in train if r.n > r.skip]
    if not ys:
        return (float("nan"), float("nan"))
    y = np.concatenate(ys)
    return float(np.min(y)), float(np.max(y))


def _load_affine(train, r, a: int, b: int) -> np.ndarray | None:
    """Where a measured load alone moves the output on a held-out part: the affine map in the
    input and the load (least squares on the training recordings) over the part, which widens
    the outputs' allowed range (a load beyond the training loads moves the whole loop); None
    where a recording carries no load."""
    if any(getattr(p, "load", None) is None for p in [*train, r]):
        return None
    x = np.concatenate([p.x for p in train])
    load = np.concatenate([p.load for p in train])
    y = np.concatenate([p.y for p in train])
    A = np.column_stack([np.ones_like(x), x, load])
    c = np.linalg.lstsq(A, y, rcond=None)[0]
    return c[0] + c[1] * r.x[a:b] + c[2] * r.load[a:b]


def _names(items: list, what: str) -> list[str]:
    """A file's name for each recording that has one (a Log's path), else "what i"."""
    out = []
    for i, item in enumerate(items):
        path = getattr(item, "path", "") if not isinstance(item, tuple) else ""
        out.append(Path(str(path)).name if path else f"{what} {i + 1}")
    return out


def _part_labels(splits, recs, logs, validate, whole_runs: bool) -> list[str]:
    """A label per held-out part, in the order of the splits' scored segments: the held-out
    recording's name, with the sample range where only part of it is held out."""
    names = {id(r): n for r, n in zip(recs, _names(_as_items(logs), "recording"), strict=True)}
    if not isinstance(validate, str | int | float):
        held = [r for r, _, _ in splits[0][1]]
        vnames = _names(_as_items(validate), "validation recording")
        names.update({id(r): n for r, n in zip(held, vnames, strict=True)})
    return [
        names.get(id(r), "recording") + ("" if whole_runs else f" [{a}:{b}]")
        for _, evals in splits
        for r, a, b in evals
    ]


def _winner(rows, fits, candidates, run, objective: str, parsimony: float):
    """Rank the rows (eligible ones first, by the objective's error) and choose the winner
    (``tendonsheath._util.parsimony``); the winner's model, Fit (refitted on all the data where
    needed), name and the choice in words. ``candidates``: (estimators, names, recordings)."""
    estimators, names, recs = candidates
    base, inv_base = rows[0]["val_rmse"], rows[0].get("inv_rmse", float("nan"))
    for r in rows:
        if not r.get("error"):
            r["ratio_to_affine"] = r["val_rmse"] / base if base > 0 else float("nan")
            inv = r.get("inv_rmse", float("nan"))
            r["inv_ratio_to_affine"] = inv / inv_base if inv_base > 0 else float("nan")
    rows.sort(key=eligibility.sort_key(objective))
    index, choice = parsimony_rule.choose(rows, objective, parsimony)
    best = rows[index]["model"]
    winner_fit = None
    if best == AFFINE:
        winner = fits[AFFINE]
    elif run.final:
        # cross-validation: every fold's fit saw part of the data; one split: the held-out
        # part too. The winner is fitted once on all of it (outside the time budget).
        start = time.perf_counter()
        run.view.show(f"{best}: final fit on all the data")
        final_estimator = estimators[names.index(best)].clone()
        final_estimator.fit(recs)
        winner_fit = final_estimator.fit_
        run.view.advance()
        rows[index]["final_fit_seconds"] = time.perf_counter() - start
        winner = winner_fit.model
    else:
        winner_fit = fits[best]  # held-out logs: fitted on all the training data already
        winner = winner_fit.model
    return winner, winner_fit, best, choice


class OutOfTime(Exception):
    """A candidate's folds ran past compare_models' time budget."""


class _Run:
    """Fits and scores every candidate over the splits, with the progress bar and the
    time budget."""

    def __init__(self, splits, validation, time_budget, progress, n_candidates, final):
        self.splits = splits
        self.validation = validation
        self.budget = time_budget
        self.deadline = None if time_budget is None else time.perf_counter() + time_budget
        self.final = final  # the winner is refitted on all the data at the end
        total = (n_candidates + 1) * len(splits) + int(final)  # the affine map too
        self.view = CompareProgress(progress, total)

    def _late(self) -> bool:
        return self.deadline is not None and time.perf_counter() > self.deadline

    def evaluate(self, name, fit_split, budgeted=True) -> tuple[dict, dict, float, float]:
        """Fit on every split's training part (fit_split(train) -> predict(rec)) and score:
        (training metrics, held-out metrics, wall s, CPU s); OutOfTime past the deadline
        (``budgeted``; the affine baseline is not)."""
        start, cpu = time.perf_counter(), time.process_time()
        n = len(self.splits)
        done = 0

        def shown(train):
            nonlocal done
            self.view.show(f"{name}: fold {done + 1}/{n}")
            done += 1
            return fit_split(train)

        def after_fit(k):
            self.view.advance()
            if budgeted and self._late():
                raise OutOfTime(
                    f"out of time: the {self.budget:g} s budget ran out after {k + 1} of "
                    f"{n} folds ({time.perf_counter() - start:.1f} s)"
                )

        tm, vm, preds = evaluate_splits(self.splits, shown, after_fit)
        for slot, p in zip(self.validation, preds, strict=True):
            slot["predictions"][name] = p
        return tm, vm, time.perf_counter() - start, time.process_time() - cpu

    def all_candidates(self, estimators, names, has_angle, on_fit):
        """The table's rows (the affine baseline first) and the fits."""

        def affine_split(train):
            b, a = _affine(train)
            return lambda r: a * r.x + b

        tm, vm, sec, cpu = self.evaluate(AFFINE, affine_split, budgeted=False)
        rows, fits = [_row(AFFINE, 2, tm, vm, sec, cpu)], {}
        affines = [Polynomial(coefficients=list(_affine(train))) for train, _ in self.splits]
        rows[0].update(self.inverse_scores(affines))
        if on_fit is not None:
            on_fit(AFFINE, sec)
        for estimator, name in zip(estimators, names, strict=True):
            if getattr(estimator.model, "uses_curve_angle", False) and not has_angle:
                rows.append({"model": name, "error": "needs a curve angle"})
                continue
            if self._late():
                rows.append(
                    _out_of_time(name, f"out of time: the {self.budget:g} s budget was spent")
                )
                continue
            fitted: list = []
            fit_split = estimator_split(estimator, fitted)
            if self.final:
                fit_split = _on_fewer_samples(fit_split, estimator.model)
            try:
                tm, vm, sec, cpu = self.evaluate(name, fit_split)
            except OutOfTime as exc:
                rows.append(_out_of_time(name, str(exc)))
                continue
            except ValueError as exc:
                rows.append({"model": name, "error": str(exc)})
                continue
            fold_fits = [est.fit_ for est in fitted]
            fits[name] = fold_fits[-1] if len(fold_fits) == 1 else fold_fits
            rows.append(_row(name, _count(fold_fits[-1].model), tm, vm, sec, cpu))
            rows[-1].update(self.inverse_scores([f.model for f in fold_fits]))
            if on_fit is not None:
                on_fit(name, sec)
        return rows, fits

    def inverse_scores(self, models: list) -> dict[str, Any]:
        """The offline inverse error of each split's model over its held-out segments (the
        inverse run over the whole recording, as the forward model is): inv_rmse, inv_nrmse
        and inv_out_of_range; an inverse that fails gives NaN and inv_error."""
        from ..status import Status
        from .inverse_error import offline_inverse

        errors, inputs, flagged = [], [], []
        try:
            for (_, evals), model in zip(self.splits, models, strict=True):
                for r, a, b in evals:
                    load = getattr(r, "load", None)
                    commands, flags = offline_inverse(model, r.t, r.y, r.angle_input, load)
                    errors.append(commands[a:b] - r.x[a:b])
                    inputs.append(r.x[a:b])
                    flagged.append((flags[a:b] & Status.OUT_OF_RANGE) != 0)
        except (ValueError, TypeError) as exc:
            nan = float("nan")
            return {"inv_rmse": nan, "inv_nrmse": nan, "inv_error": str(exc)}
        e = np.concatenate(errors)
        rmse = float(np.sqrt(np.mean(e * e)))
        span = float(np.ptp(np.concatenate(inputs)))
        return {
            "inv_rmse": rmse,
            "inv_nrmse": rmse / span if span > 0 else float("nan"),
            "inv_out_of_range": float(np.mean(np.concatenate(flagged))),
            "inv_rmse_parts": [float(np.sqrt(np.mean(p * p))) for p in errors],
        }


def _on_fewer_samples(fit_split, candidate):
    """``fit_split`` on the training records thinned (a rate-independent candidate) or
    decimated (a dynamic chain) to about :data:`FOLD_SAMPLES` where they hold more than
    :data:`FOLD_THIN_ABOVE` samples: a fold's fit only ranks."""
    from ..identify.data import decimate_for_search, thin_for_search

    if getattr(candidate, "rate_independent", False):
        fewer = thin_for_search
    elif is_dynamic_chain(candidate):
        fewer = decimate_for_search
    else:
        return fit_split

    def fit_on_fewer(train):
        train = list(train)
        if sum(r.n for r in train) <= FOLD_THIN_ABOVE:
            return fit_split(train)
        return fit_split(fewer(train, 0, FOLD_SAMPLES)[0])

    return fit_on_fewer


def _out_of_time(name: str, message: str) -> dict:
    return {"model": name, "error": message, "status": "out of time"}


def _row(name, n_params, tm, vm, seconds, cpu_seconds) -> dict:
    return {
        "model": name,
        "n_params": int(n_params),
        "train_rmse": tm["rmse"],
        "train_nrmse": tm["nrmse"],
        "val_rmse": vm["rmse"],
        "val_nrmse": vm["nrmse"],
        "val_fit_percent": vm["fit_percent"],
        "val_max_abs": vm["max_abs"],
        "seconds": float(seconds),
        "cpu_seconds": float(cpu_seconds),
    }


def _count(model: HysteresisModel) -> int:
    n = 0
    for v in model.params.values():
        if isinstance(v, list):
            n += len(v)
        elif isinstance(v, int | float):
            n += 1
    return n


__all__ = [
    "AFFINE",
    "CANDIDATES",
    "Comparison",
    "FOLD_REFINE_EVALUATIONS",
    "FOLD_SAMPLES",
    "FOLD_THIN_ABOVE",
    "INVERSE_NOTE",
    "LOADED_BASES",
    "MIN_PIECE",
    "OutOfTime",
    "PARTS_CAPTION",
    "SETTLE_FRACTION",
    "SETTLE_NOTE",
    "compare_models",
    "default_models",
    "model_name",
    "parse_model",
]
