"""`sweep`: run a design's points on an engine (serial, local pool, Dask) with checkpoints
and retries, into a SweepResult."""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING

from .checkpoint import Checkpoint
from .distributions import (
    Design,
    as_design,
)
from .engines import (
    EngineStats,
    SweepError,
    connect,
    is_dask_client,
    run_dask,
    run_local,
    run_serial,
)
from .plan import Plan, make_plan
from .result import SweepResult, build_table, engine_info

if TYPE_CHECKING:
    from dask.distributed import Client


def declared_parameters(run, parameters=None) -> list[str] | None:
    """The names ``run`` accepts: ``parameters=`` or the run's ``parameters`` attribute."""
    names = parameters if parameters is not None else getattr(run, "parameters", None)
    if names is None:
        return None
    if isinstance(names, str) or not isinstance(names, Iterable):
        raise ValueError(f"sweep: parameters must be a list of names (got {names!r})")
    return list(names)


def _check_names(design: Design, accepted: list[str] | None) -> None:
    if accepted is None:
        return
    unknown = [n for n in design.names if n not in accepted]
    if unknown:
        raise ValueError(
            f"sweep: unknown parameter name(s) {unknown}; the run accepts {sorted(accepted)}"
        )


def sweep(
    run: Callable[[dict], Mapping],
    design: Design | Mapping,
    n: int | None = None,
    seed: int | None = None,
    engine: str | Client = "local",
    *,
    workers: int | None = None,
    batch_size: int | None = None,
    parameters: Iterable[str] | None = None,
    on_error: str = "raise",
    retries: int = 3,
    progress: bool | None = None,
    connect_timeout: float = 5.0,
    checkpoint: str | Path | None = None,
    checkpoint_tag: str | None = None,
) -> SweepResult:
    """Evaluate ``run`` over a design and return a :class:`SweepResult` (a tidy table).

    ``design``: a dict parameter -> :class:`Distribution` (or constant) for ``n`` random
    draws, or a :class:`LatinHypercube`, :class:`Grid` or :class:`Saltelli`. ``seed`` fixes
    every draw (None: a fresh seed, kept in the result); the table does not depend on the
    engine, ``workers`` or ``batch_size``.

    ``engine``: ``"local"`` (a process pool, ``workers`` processes, default all cores),
    ``"serial"`` (this process, for debugging), a ``dask.distributed.Client``, or a
    scheduler address such as ``"tcp://scheduler:8786"`` (connected within
    ``connect_timeout`` seconds, else ConnectionError before any run). On Dask, runs go in
    batches of ``batch_size`` (default: about 10 batches per worker, at most 32 runs); a
    batch lost with its worker is run again elsewhere (``retries``), each run counted once.

    ``parameters``: the names the run accepts (default: the run's ``parameters`` attribute);
    any other name is an error before work starts. ``on_error``: ``"raise"`` (a failed run
    stops the sweep with its index and parameters) or ``"record"`` (NaN metrics and an
    ``error`` column). ``progress``: a progress bar on stderr (None: on a terminal only).

    ``checkpoint``: a file (JSON lines) where every finished run is stored as its batch
    comes back; when it already holds runs of this same sweep (design, seed, number of
    runs, ``checkpoint_tag`` and every run's parameters), those runs are not run again, so
    an interrupted sweep resumes. The runs of another sweep there are a ValueError.

    Parameters
    ----------
    run : callable
        dict of parameters -> mapping of metric name -> value; must pickle for the local
        and Dask engines.
    design : Design or mapping
        The parameters and how they are drawn (a mapping: Monte Carlo).
    n : int, optional
        Number of draws (Saltelli: base samples); not needed for a Grid.
    seed : int, optional
        Seed of every draw; None: a fresh one, kept in the result.
    engine : {"local", "serial"}, str or dask.distributed.Client, default "local"
        Where the runs go (see above).
    workers : int, optional
        Processes of the local engine (default all cores).
    batch_size : int, optional
        Runs per batch.
    parameters : iterable of str, optional
        The names the run accepts (default the run's ``parameters`` attribute).
    on_error : {"raise", "record"}, default "raise"
        What a failed run does.
    retries : int, default 3
        Re-runs of a batch lost with its Dask worker.
    progress : bool, optional
        Show a progress bar (None: on a terminal only).
    connect_timeout : float, default 5.0
        Seconds to connect to a scheduler address.
    checkpoint : str or Path, optional
        A JSON-lines file of finished runs, to resume from.
    checkpoint_tag : str, optional
        Tells sweeps apart in one checkpoint file.

    Returns
    -------
    SweepResult
        The tidy table of every run's parameters and metrics, with the engine's figures.

    Raises
    ------
    ValueError
        A bad argument, an unknown parameter name, or a checkpoint of another sweep.
    SweepError
        A run failed (with ``on_error="raise"``), or every run failed.
    ConnectionError
        The scheduler could not be reached within ``connect_timeout``.
    """
    _check_options(run, on_error, batch_size, workers, retries, connect_timeout)
    design = as_design(design)
    _check_names(design, declared_parameters(run, parameters))
    plan = make_plan(design, n, seed)
    ck = Checkpoint(checkpoint, plan, checkpoint_tag) if checkpoint is not None else None
    stored: dict = ck.load() if ck is not None else {}
    items = [(i, p) for i, p in enumerate(plan.runs) if i not in stored]
    client, own_client = _client(engine, connect_timeout)
    start = time.perf_counter()
    record = None
    if ck is not None:
        ck.open(keep=bool(stored))
        record = ck.record
    try:
        engines = (engine, client, workers, batch_size, retries)
        results, stats = _run_items(run, items, engines, progress, record)
    finally:
        if own_client:
            client.close()
        if ck is not None:
            ck.close()
    results = {**stored, **results}
    failed = _failed_runs(plan, results, on_error)
    built = build_table(plan, results)
    info = engine_info(stats)
    info["wall_seconds"] = time.perf_counter() - start
    info.update(_throughput(stats, info["wall_seconds"], len(items), len(failed), len(stored)))
    return _sweep_result(plan, built, info)


def _sweep_result(plan: Plan, built: tuple, info: dict) -> SweepResult:
    """The result of ``plan``'s runs: ``built`` is build_table's (table, metrics,
    compensators) and ``info`` the engine's figures."""
    table, metrics, compensators = built
    return SweepResult(
        table=table,
        parameters=list(plan.drawn),
        metrics=metrics,
        compensators=compensators,
        fixed=dict(plan.fixed),
        design=plan.kind,
        seed=plan.seed,
        engine=info,
        salib_problem=plan.salib_problem,
        unranked=plan.unranked,
    )


def _check_options(run, on_error, batch_size, workers, retries, connect_timeout) -> None:
    """One-line errors for the options of :func:`sweep`, before any work."""
    if not callable(run):
        raise ValueError(f"sweep: run must be callable (got {type(run).__name__})")
    if on_error not in ("raise", "record"):
        raise ValueError(f"sweep: on_error must be 'raise' or 'record' (got {on_error!r})")
    if batch_size is not None and (int(batch_size) != batch_size or batch_size < 1):
        raise ValueError(f"sweep: batch_size must be a positive integer (got {batch_size!r})")
    if workers is not None and (int(workers) != workers or workers < 1):
        raise ValueError(f"sweep: workers must be a positive integer (got {workers!r})")
    if isinstance(retries, bool) or int(retries) != retries or retries < 0:
        raise ValueError(f"sweep: retries must be an integer >= 0 (got {retries!r})")
    if not connect_timeout > 0:
        raise ValueError(f"sweep: connect_timeout must be > 0 s (got {connect_timeout!r})")


def _client(engine, connect_timeout: float):
    """The Dask client ``engine`` names (None for "local" and "serial"), and whether the
    sweep opened it (and so closes it)."""
    if isinstance(engine, str) and engine not in ("local", "serial"):
        if "://" not in engine and ":" not in engine:
            raise ValueError(
                f"sweep: engine must be 'local', 'serial', a dask Client or a scheduler "
                f"address like tcp://host:8786 (got {engine!r})"
            )
        return connect(engine, connect_timeout), True
    if is_dask_client(engine):
        return engine, False
    if engine not in ("local", "serial"):
        raise ValueError(
            "sweep: engine must be 'local', 'serial', a dask.distributed.Client or a scheduler "
            f"address (got {type(engine).__name__})"
        )
    return None, False


def _run_items(run, items: list, engines: tuple, progress, record):
    """Run ``items`` (index, parameters) on the engine ``engines`` names (engine, Dask
    client or None, workers, batch size, retries): (index -> result, EngineStats)."""
    engine, client, workers, batch_size, retries = engines
    if not items:  # every run was stored by an earlier, interrupted call
        return {}, EngineStats("resumed", 0, 0, 0)
    if client is not None:
        return run_dask(run, items, client, batch_size, retries, progress, record)
    if engine == "serial":
        return run_serial(run, items, progress, record)
    return run_local(run, items, workers, batch_size, progress, record=record)


def _failed_runs(plan: Plan, results: dict, on_error: str) -> list:
    """(index, error) of every failed run; a SweepError where the sweep cannot go on."""
    n_all = len(plan.runs)
    failed = [(i, results[i][1]) for i in range(n_all) if results[i][1] is not None]
    if failed and on_error == "raise":
        i, err = failed[0]
        raise SweepError(
            f"run {i} with {plan.runs[i]} failed: {err}"
            + (f" ({len(failed) - 1} more runs failed)" if len(failed) > 1 else "")
            + "; pass on_error='record' to keep going"
        )
    if len(failed) == n_all:
        raise SweepError(f"sweep: every run failed; the first: run 0: {failed[0][1]}")
    return failed


def _throughput(stats: EngineStats, wall: float, ran: int, failed: int, resumed: int) -> dict:
    """Runs per second, failed and resumed runs, and the worker-time each run cost beyond
    its own compute (start-up, transfer, scheduling, idle)."""
    info = {
        "runs_per_second": ran / wall if wall else math.inf,
        "failed_runs": failed,
        "resumed_runs": resumed,
    }
    if stats.compute_seconds > 0:
        used = stats.seconds * stats.workers
        info["overhead_per_run"] = (used - stats.compute_seconds) / stats.compute_seconds
    return info


__all__ = ["declared_parameters", "sweep"]
