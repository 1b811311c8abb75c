"""The tidy table of a sweep, its summary, sensitivity ranking, files and figures."""

from __future__ import annotations

import json
import math
import numbers
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._util.atomic import atomic_path, write_json
from .._util.extras import require

if TYPE_CHECKING:  # pandas is imported when a table is built (an optional dependency)
    import pandas as pd

QUANTILES = {"q05": 0.05, "q25": 0.25, "median": 0.5, "q75": 0.75, "q95": 0.95}


def _pandas():
    return require("pandas", extra="sweep", feature="the sweep's table")


def _is_number(x) -> bool:
    return isinstance(x, numbers.Real) and not isinstance(x, bool)


def _metrics_of(index: int, out) -> dict[str, float]:
    if not isinstance(out, Mapping) or not out:
        raise ValueError(
            f"run {index} returned {type(out).__name__}; a run must return a non-empty dict "
            "metric -> number, or compensator -> {metric -> number}"
        )
    bad = [k for k, v in out.items() if not _is_number(v)]
    if bad:
        raise ValueError(f"run {index}: metric(s) {bad} are not numbers")
    return {str(k): float(v) for k, v in out.items()}


def build_table(plan, results: dict[int, tuple[Any, str | None]]):
    """One row per run (or per run and compensator), sorted by run index."""
    pd = _pandas()
    nested = None
    metric_names: list[str] = []
    compensators: list[str] = []
    parsed: dict[int, Any] = {}
    for index in range(len(plan)):
        out, error = results[index]
        if error is not None:
            continue
        is_nested = isinstance(out, Mapping) and bool(out)
        is_nested = is_nested and all(isinstance(v, Mapping) for v in out.values())
        if nested is None:
            nested = is_nested
        elif nested != is_nested:
            raise ValueError(
                f"run {index} returned a different shape from earlier runs (a dict of metrics "
                "and a dict of compensators -> metrics do not mix)"
            )
        if nested:
            parsed[index] = {str(c): _metrics_of(index, m) for c, m in out.items()}
            for c, m in parsed[index].items():
                if c not in compensators:
                    compensators.append(c)
                metric_names += [k for k in m if k not in metric_names]
        else:
            parsed[index] = _metrics_of(index, out)
            metric_names += [k for k in parsed[index] if k not in metric_names]
    rows = []
    any_error = False
    for index, params in enumerate(plan.runs):
        base = {"run": index, **{k: params[k] for k in plan.drawn}}
        error = results[index][1]
        any_error |= error is not None
        if nested:
            for c in compensators if error is not None else parsed[index]:
                m = parsed[index][c] if error is None else {}
                rows.append({**base, "compensator": c, **m, "error": error})
        else:
            m = parsed.get(index, {})
            rows.append({**base, **m, "error": error})
    columns = ["run", *plan.drawn, *(["compensator"] if nested else []), *metric_names]
    table = pd.DataFrame(rows)
    for m in metric_names:
        if m not in table:
            table[m] = np.nan
    if any_error:
        columns.append("error")
    table = table.reindex(columns=columns)
    for m in metric_names:
        table[m] = table[m].astype(np.float64)
    return table.reset_index(drop=True), metric_names, (compensators if nested else None)


def _ranked(block: list[dict], key) -> list[dict]:
    """``block`` sorted by ``key`` with a 1-based ``rank`` in each row."""
    block.sort(key=key)
    for k, r in enumerate(block, 1):
        r["rank"] = k
    return block


def _standardized_regression(X: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float]:
    """Least-squares coefficients of standardized ``y`` on the standardized columns of
    ``X``, and the r2 of that linear model (zeros and NaN when ``y`` is constant)."""
    Xs = (X - X.mean(0)) / X.std(0)
    sy = y.std()
    if sy == 0:
        return np.zeros(X.shape[1]), float("nan")
    ys = (y - y.mean()) / sy
    coef, *_ = np.linalg.lstsq(Xs, ys, rcond=None)
    resid = ys - Xs @ coef
    return coef, float(1.0 - resid @ resid / (ys @ ys))


@dataclass
class SweepResult:
    """What :func:`tendonsheath.sweep` returns.

    ``table``: a pandas DataFrame, one row per run (per run and compensator when the run
    returned compensator -> metrics), columns ``run``, the drawn parameters, ``compensator``
    (if any), the metrics, and ``error`` (only when some run failed with on_error='record').

    Parameters
    ----------
    table : pandas.DataFrame
        One row per run (and compensator).
    parameters : list of str
        The drawn parameters.
    metrics : list of str
        The metric columns.
    compensators : list of str or None
        The compensators, when the run returned compensator -> metrics.
    fixed : dict
        The constants passed to every run.
    design : str
        The design's kind.
    seed : int
        The sweep's seed.
    engine : dict, optional
        The engine's figures (workers, wall time, runs per second, ...).
    salib_problem : dict, optional
        SALib's problem (Saltelli designs).
    unranked : list of str, optional
        Drawn parameters that sensitivity rankings leave out.
    """

    table: pd.DataFrame
    parameters: list[str]
    metrics: list[str]
    compensators: list[str] | None
    fixed: dict[str, Any]
    design: str
    seed: int
    engine: dict = field(default_factory=dict)
    salib_problem: dict | None = None
    unranked: list[str] = field(default_factory=list)

    # -- basic views ---------------------------------------------------------------------
    def __len__(self) -> int:
        return len(self.table)

    @property
    def n_runs(self) -> int:
        """The number of runs."""
        return int(self.table["run"].nunique())

    def __repr__(self) -> str:
        comp = f", compensators={self.compensators}" if self.compensators else ""
        return (
            f"SweepResult({self.n_runs} runs, design={self.design!r}, seed={self.seed}, "
            f"parameters={self.parameters}, metrics={self.metrics}{comp})"
        )

    def _groups(self):
        if self.compensators:
            for c in self.compensators:
                yield c, self.table[self.table["compensator"] == c]
        else:
            yield "all", self.table

    def primary_metric(self) -> str:
        """The metric a bare number bound applies to: mse if present, else the first.

        Returns
        -------
        str
            The metric's name.
        """
        return "mse" if "mse" in self.metrics else self.metrics[0]

    def _bounds(self, bound) -> dict[str, float]:
        check_bound(bound)
        if bound is None:
            return {}
        if isinstance(bound, Mapping):
            unknown = sorted(set(bound) - set(self.metrics))
            if unknown:
                raise ValueError(f"bound: unknown metric(s) {unknown}; known: {self.metrics}")
            return {k: float(v) for k, v in bound.items()}
        return {self.primary_metric(): float(bound)}

    # -- summary ---------------------------------------------------------------------------
    def summary(self, bound: float | Mapping[str, float] | None = None) -> pd.DataFrame:
        """Quantiles of each metric per compensator; with ``bound`` (a number for the
        primary metric, mse if present, or {metric: bound}) the fraction of runs whose
        metric is <= the bound (failed runs count as not meeting it).

        Parameters
        ----------
        bound : float or mapping of str to float, optional
            A bound on the primary metric, or per metric.

        Returns
        -------
        pandas.DataFrame
            One row per compensator and metric: n, failed, mean, std, min, quantiles, max,
            and bound and within_bound with a bound.

        Raises
        ------
        ValueError
            A bound that is not a number, or on an unknown metric.
        """
        pd = _pandas()
        bounds = self._bounds(bound)
        rows = []
        for comp, g in self._groups():
            for m in self.metrics:
                x = g[m].to_numpy(dtype=np.float64)
                ok = x[np.isfinite(x)]
                row = {
                    "compensator": comp,
                    "metric": m,
                    "n": int(x.size),
                    "failed": int(x.size - ok.size),
                }
                if ok.size:
                    row.update(
                        mean=float(ok.mean()),
                        std=float(ok.std(ddof=1)) if ok.size > 1 else 0.0,
                        min=float(ok.min()),
                    )
                    row.update({k: float(np.quantile(ok, q)) for k, q in QUANTILES.items()})
                    row["max"] = float(ok.max())
                if m in bounds:
                    row["bound"] = bounds[m]
                    row["within_bound"] = float(np.mean(np.nan_to_num(x, nan=np.inf) <= bounds[m]))
                rows.append(row)
        return pd.DataFrame(rows)

    # -- sensitivity -------------------------------------------------------------------------
    def numeric_parameters(self) -> list[str]:
        """The drawn parameters a sensitivity analysis regresses on: numeric, varying, ranked.

        Returns
        -------
        list of str
            Their names.
        """
        pd = _pandas()
        out = []
        for p in self.parameters:
            if p in self.unranked:
                continue
            col = self.table[p]
            if pd.api.types.is_numeric_dtype(col) and not pd.api.types.is_bool_dtype(col):
                if col.nunique() > 1:
                    out.append(p)
        return out

    def sensitivity(
        self, method: str = "auto", metrics: str | Sequence[str] | None = None
    ) -> pd.DataFrame:
        """Which parameter matters most, per compensator and metric.

        * ``"src"``: standardized regression coefficients (least squares on the standardized
          numeric parameters; ``r2`` tells how much of the variance a linear model explains);
          ``"srrc"``: the same on ranks (monotone, non-linear effects).
        * ``"sobol"``: first-order (S1) and total (ST) Sobol indices with SALib; only for a
          Saltelli design. ``"auto"``: sobol for a Saltelli design, else src.

        Rows are sorted by importance (|src| or ST) within each compensator and metric.

        Parameters
        ----------
        method : {"auto", "src", "srrc", "sobol"}, default "auto"
            The analysis.
        metrics : str or list of str, optional
            The metrics to analyse (default all).

        Returns
        -------
        pandas.DataFrame
            One row per compensator, metric and parameter, with its rank.

        Raises
        ------
        ValueError
            An unknown method, sobol without a Saltelli design or with failed runs, or no
            numeric parameter that varies.
        """
        pd = _pandas()
        if method == "auto":
            method = "sobol" if self.salib_problem is not None else "src"
        if method not in ("src", "srrc", "sobol"):
            raise ValueError(f"sensitivity: method must be auto, src, srrc or sobol ({method!r})")
        metrics = [metrics] if isinstance(metrics, str) else list(metrics or self.metrics)
        if method == "sobol":
            return pd.DataFrame(self._sobol_rows(metrics))
        return pd.DataFrame(self._regression_rows(method, metrics))

    def _sobol_rows(self, metrics: list[str]) -> list[dict]:
        """First-order and total Sobol indices (SALib), ranked by ST."""
        if self.salib_problem is None:
            raise ValueError("sensitivity: Sobol indices need a Saltelli design")
        from SALib.analyze import sobol

        rows = []
        for comp, g in self._groups():
            g = g.sort_values("run")
            for m in metrics:
                y = g[m].to_numpy(dtype=np.float64)
                if not np.all(np.isfinite(y)):
                    raise ValueError(f"sensitivity: {comp}/{m} has failed runs (NaN)")
                res = sobol.analyze(
                    self.salib_problem,
                    y,
                    calc_second_order=False,
                    print_to_console=False,
                    seed=self.seed,
                )
                block = [
                    {
                        "compensator": comp,
                        "metric": m,
                        "parameter": name,
                        "method": "sobol",
                        "S1": float(res["S1"][j]),
                        "S1_conf": float(res["S1_conf"][j]),
                        "ST": float(res["ST"][j]),
                        "ST_conf": float(res["ST_conf"][j]),
                    }
                    for j, name in enumerate(self.salib_problem["names"])
                ]
                rows += _ranked(block, lambda r: -np.nan_to_num(r["ST"], nan=-np.inf))
        return rows

    def _regression_rows(self, method: str, metrics: list[str]) -> list[dict]:
        """Standardized regression coefficients (``"src"``, or on ranks ``"srrc"``) of the
        numeric parameters, ranked by their magnitude."""
        names = self.numeric_parameters()
        if not names:
            raise ValueError("sensitivity: no numeric parameter varies in this sweep")
        rows = []
        for comp, g in self._groups():
            for m in metrics:
                sub = g[[*names, m]].dropna()
                if len(sub) <= len(names) + 1:
                    continue
                if method == "srrc":
                    sub = sub.rank()
                X = sub[names].to_numpy(dtype=np.float64)
                coef, r2 = _standardized_regression(X, sub[m].to_numpy(dtype=np.float64))
                block = [
                    {
                        "compensator": comp,
                        "metric": m,
                        "parameter": p,
                        "method": method,
                        "coefficient": float(c),
                        "r2": r2,
                    }
                    for p, c in zip(names, coef, strict=True)
                ]
                rows += _ranked(block, lambda r: -abs(r["coefficient"]))
        return rows

    # -- files ---------------------------------------------------------------------------------
    def to_csv(self, path: str | Path) -> Path:
        """Write the table as CSV (atomically; folders made as needed).

        Parameters
        ----------
        path : str or Path
            The file.

        Returns
        -------
        Path
            The file written.
        """
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        with atomic_path(path) as tmp:
            self.table.to_csv(tmp, index=False)
        return path

    def to_parquet(self, path: str | Path) -> Path:
        """Write the table as Parquet (mixed-type columns as text; atomically).

        Parameters
        ----------
        path : str or Path
            The file.

        Returns
        -------
        Path
            The file written.
        """
        require("pyarrow", extra="sweep", feature="the sweep's Parquet table")
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        table = self.table.copy()
        for c in table.columns:  # mixed-type (object) parameter columns: as text
            if table[c].dtype == object and c != "error":
                table[c] = table[c].astype(str)
        with atomic_path(path) as tmp:
            table.to_parquet(tmp, index=False)
        return path

    def metadata(self) -> dict:
        """How the sweep was made, JSON-ready: design, seed, runs, parameters, fixed values,
        metrics, compensators and the engine's figures.

        Returns
        -------
        dict
            The metadata (non-finite numbers as None).
        """

        def plain(v):
            if isinstance(v, np.generic):
                return v.item()
            if isinstance(v, float) and not math.isfinite(v):
                return None
            return v if isinstance(v, str | int | float | bool | type(None)) else repr(v)

        return {
            "design": self.design,
            "seed": self.seed,
            "runs": self.n_runs,
            "parameters": self.parameters,
            "fixed": {k: plain(v) for k, v in self.fixed.items()},
            "metrics": self.metrics,
            "compensators": self.compensators,
            "engine": {
                k: plain(v) if not isinstance(v, dict) else v for k, v in self.engine.items()
            },
        }

    def save(
        self,
        out_dir: str | Path,
        bound: float | Mapping[str, float] | None = None,
        figures: bool = True,
    ) -> list[Path]:
        """table.csv, table.parquet, summary.csv, summary.json (summary, sensitivity, how the
        sweep was made) and, with ``figures``, the plots of :meth:`plots`.

        Parameters
        ----------
        out_dir : str or Path
            The folder (made as needed).
        bound : float or mapping of str to float, optional
            As for :meth:`summary`.
        figures : bool, default True
            Also draw the plots.

        Returns
        -------
        list of Path
            The files written.
        """
        pd = _pandas()
        out = Path(out_dir)
        out.mkdir(parents=True, exist_ok=True)
        written = [self.to_csv(out / "table.csv"), self.to_parquet(out / "table.parquet")]
        summary = self.summary(bound)
        with atomic_path(out / "summary.csv") as tmp:
            summary.to_csv(tmp, index=False)
        written.append(out / "summary.csv")
        sens_note: str | None
        try:
            sens = self.sensitivity()
        except ValueError as exc:
            sens, sens_note = pd.DataFrame(), str(exc)
        else:
            sens_note = None
        payload = {
            **self.metadata(),
            "bound": self._bounds(bound),
            "summary": json.loads(summary.to_json(orient="records")),
            "sensitivity": json.loads(sens.to_json(orient="records")) if len(sens) else [],
        }
        if sens_note:
            payload["sensitivity_note"] = sens_note
        write_json(out / "summary.json", payload)
        written.append(out / "summary.json")
        if figures:
            written += self.plots(out, sensitivity=sens if len(sens) else None)
        return written

    def plots(self, out_dir: str | Path, sensitivity: pd.DataFrame | None = None) -> list[Path]:
        """hist_<metric>.png (per compensator), <metric>_vs_parameters.png and
        sensitivity.png (the primary metric's ranking) in ``out_dir``.

        Parameters
        ----------
        out_dir : str or Path
            The folder.
        sensitivity : pandas.DataFrame, optional
            A :meth:`sensitivity` table for the ranking figure.

        Returns
        -------
        list of Path
            The figures written.
        """
        from .plots import plot_all

        return plot_all(self, Path(out_dir), sensitivity)


def engine_info(stats) -> dict:
    d = asdict(stats)
    extra = d.pop("extra", {}) or {}
    return {**d, **extra}


# error metrics are >= 0: a bound on one at or below 0 can only be a mistake
_ERROR_METRICS = ("mse", "rmse", "max_abs", "percent_error", "max_percent_error")


def check_bound(bound) -> None:
    """A bound is a finite number (for the primary metric) or {metric: finite number}; on an
    error metric (mse, rmse, ... or a plain number) it must be > 0."""
    if bound is None:
        return
    items = bound.items() if isinstance(bound, Mapping) else [(None, bound)]
    for metric, value in items:
        what = "bound" if metric is None else f"bound on {metric}"
        if isinstance(value, bool) or not isinstance(value, int | float | np.number):
            raise ValueError(f"{what} must be a number (got {value!r})")
        if not np.isfinite(value):
            raise ValueError(f"{what} must be finite (got {value})")
        if (metric is None or metric in _ERROR_METRICS) and value <= 0:
            raise ValueError(f"{what} must be > 0: an error metric is >= 0 (got {value})")


__all__ = ["QUANTILES", "SweepResult", "build_table", "check_bound", "engine_info"]
