"""Where the runs execute: in this process, on a local process pool, or on a Dask cluster.

Every engine runs *batches* of (run index, parameters) and returns, per run, the index with
the run's output or its error text; results are keyed by run index, so a batch that is run
twice (a retry after a worker died) never counts twice, and the table does not depend on
the order in which batches finish.
"""

from __future__ import annotations

import math
import multiprocessing
import os
import pickle
import signal
import time
import traceback
import uuid
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor, as_completed
from concurrent.futures.process import BrokenProcessPool
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any

from .._util.blas import limit_blas_threads
from .._util.main_guard import ADVICE, in_bootstrapping_worker, unguarded_script
from .._util.progress import StepProgress

Item = tuple[int, dict[str, Any]]
Outcome = tuple[int, Any, str | None, float]  # index, output, error text, seconds


class SweepError(RuntimeError):
    """A sweep could not finish (a run failed with on_error='raise', or batches were lost)."""


def run_batch(run: Callable, items: Sequence[Item]) -> list[Outcome]:
    """Run each item; an exception becomes error text (the batch itself never fails)."""
    out: list[Outcome] = []
    for index, params in items:
        start = time.perf_counter()
        try:
            value, error = run(dict(params)), None
        except Exception as exc:  # noqa: BLE001 - reported per run
            value, error = None, traceback.format_exception_only(type(exc), exc)[-1].strip()
        out.append((index, value, error, time.perf_counter() - start))
    return out


class ByValue:
    """A run shipped by value (cloudpickle): lambdas, closures and functions of a notebook or
    script (``__main__``), which a worker process could not import by name."""

    def __init__(self, run):
        import cloudpickle

        self.payload = cloudpickle.dumps(run)
        self.name = getattr(run, "__name__", type(run).__name__)
        self._run = None

    def __call__(self, params):
        if self._run is None:
            self._run = pickle.loads(self.payload)
        return self._run(params)

    def __getstate__(self):
        return {"payload": self.payload, "name": self.name, "_run": None}


def portable(run):
    """``run`` as it can travel to another process: by name when it can, else by value;
    a clear ValueError, before any work, when it cannot travel at all."""
    module = getattr(run, "__module__", None) or getattr(type(run), "__module__", None)
    try:
        pickle.dumps(run)
        by_name = module != "__main__"
    except Exception:  # noqa: BLE001 - lambdas, closures, local classes
        by_name = False
    if by_name:
        return run
    try:
        return ByValue(run)
    except ImportError:
        if module == "__main__":
            return run  # the workers re-import __main__ (a script with a __main__ guard)
        raise ValueError(
            "sweep: the run function cannot be pickled (a lambda or a local function?): "
            "define it at the top level of a module, or install cloudpickle"
        ) from None
    except Exception as exc:  # noqa: BLE001
        raise ValueError(f"sweep: the run function cannot be pickled ({exc})") from None


def auto_batch_size(n_runs: int, workers: int) -> int:
    """About 10 batches per worker, at most 32 runs per batch: few enough tasks that the
    per-task cost (about a millisecond on Dask) stays small against runs of 10 ms and more,
    small enough that the last batches do not leave workers idle for long."""
    return max(1, min(32, math.ceil(n_runs / (10 * max(1, workers)))))


def make_batches(items: Sequence[Item], size: int) -> list[list[Item]]:
    return [list(items[k : k + size]) for k in range(0, len(items), size)]


@dataclass
class EngineStats:
    engine: str
    workers: int
    batches: int
    batch_size: int
    resubmitted: int = 0
    duplicates_dropped: int = 0
    seconds: float = 0.0
    #: the runs' own time, summed (measured around each call, on the worker)
    compute_seconds: float = 0.0
    extra: dict = field(default_factory=dict)


class _Collector:
    """Keeps the first outcome of every run index; counts duplicates."""

    def __init__(self, n: int, progress, record=None):
        self.results: dict[int, tuple[Any, str | None]] = {}
        self.duplicates = 0
        self.compute = 0.0
        self.progress = progress
        self.record = record  # called with each batch's new outcomes (a checkpoint)

    def add(self, outcomes: list[Outcome]) -> None:
        new = []
        for index, value, error, seconds in outcomes:
            if index in self.results:
                self.duplicates += 1
                continue
            self.results[index] = (value, error)
            self.compute += seconds
            new.append((index, value, error, seconds))
        if self.record is not None:
            self.record(new)
        self.progress(len(new))


@contextmanager
def progress_bar(enabled: bool | None, total: int, label: str):
    """A rich progress bar on stderr (enabled=None: only on a terminal); yields advance(k)."""
    with StepProgress(
        enabled is not False, total, label, "runs", terminal_only=enabled is None, transient=False
    ) as bar:
        yield bar.advance


# -- serial and local ------------------------------------------------------------------------


def run_serial(run, items, progress=None, record=None) -> tuple[dict, EngineStats]:
    start = time.perf_counter()
    with progress_bar(progress, len(items), "sweep (this process)") as advance:
        col = _Collector(len(items), advance, record)
        for item in items:
            col.add(run_batch(run, [item]))
    stats = EngineStats(
        "serial", 1, len(items), 1, seconds=time.perf_counter() - start, compute_seconds=col.compute
    )
    return col.results, stats


def _default_context() -> str:
    # forkserver: no fork of a process that may hold threads (a Dask client, rich), cheaper
    # start-up than spawn; spawn where forkserver does not exist.
    return "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"


_POOLS: dict[tuple[int, str], ProcessPoolExecutor] = {}


def local_pool(workers: int, method: str, preload: str | None = None) -> ProcessPoolExecutor:
    """A process pool kept between sweeps (start-up is paid once per session, as on a
    Dask cluster); a pool broken by a crashed worker is replaced."""
    key = (workers, method)
    pool = _POOLS.get(key)
    if pool is not None and not getattr(pool, "_broken", False):
        return pool
    ctx = multiprocessing.get_context(method)
    if method == "forkserver":
        # workers fork from a server that has already imported the package and the run's
        # module (effective when this process starts its fork server, i.e. the first time)
        ctx.set_forkserver_preload(["tendonsheath", *([preload] if preload else [])])
    pool = ProcessPoolExecutor(
        max_workers=workers,
        mp_context=ctx,
        initializer=_start_worker,
        initargs=(max(1, (os.cpu_count() or 1) // workers),),
    )
    _POOLS[key] = pool
    return pool


def _start_worker(threads: int) -> None:
    """Workers leave Ctrl-C to the main process (which stops them): a terminal sends SIGINT
    to every process of the command, and each worker would print its own traceback. An
    identification inside a run uses the worker's share of the cores, not all of them, in
    tendonsheath's batched calls and in the BLAS (OpenBLAS threads spinning in every worker
    on every core made a calibration inside a run 4x slower on 2 cores)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    os.environ.setdefault("TENDONSHEATH_NUM_THREADS", str(threads))
    # the BLAS was loaded by the fork server before any environment variable could cap it
    limit_blas_threads(threads)


def _stop_pool(key) -> None:
    """Stop a pool's workers now (after Ctrl-C or an error: their batches are not wanted)."""
    pool = _POOLS.pop(key, None)
    if pool is None:
        return
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        proc.terminate()
    pool.shutdown(wait=True, cancel_futures=True)


def run_local(
    run, items, workers=None, batch_size=None, progress=None, mp_context=None, record=None
) -> tuple[dict, EngineStats]:
    """A process pool over this machine's cores (workers=None: os.cpu_count())."""
    method = mp_context or _default_context()
    if in_bootstrapping_worker():  # a worker re-running an unguarded script: stop it quietly
        raise SystemExit(f"tendonsheath sweep: {ADVICE}")
    script = unguarded_script() if method != "fork" else None
    if script is not None:
        raise SweepError(f"sweep(engine='local') in {script}: {ADVICE}")
    workers = int(workers or os.cpu_count() or 1)
    if workers < 1:
        raise ValueError(f"sweep: workers must be >= 1 (got {workers})")
    size = int(batch_size or auto_batch_size(len(items), workers))
    batches = make_batches(items, size)
    run = portable(run)
    start = time.perf_counter()
    pool = local_pool(workers, method, getattr(run, "__module__", None))
    label = f"sweep (local, {workers} worker{'s' if workers > 1 else ''})"
    with progress_bar(progress, len(items), label) as advance:
        col = _Collector(len(items), advance, record)
        futures = [pool.submit(run_batch, run, b) for b in batches]
        try:
            for fut in as_completed(futures):
                col.add(fut.result())
        except BrokenProcessPool as exc:
            _POOLS.pop((workers, method), None)
            raise SweepError(
                f"a local worker process died ({exc}); the local engine does not retry: "
                "use the Dask engine for fault tolerance (a script that starts a sweep outside "
                'its `if __name__ == "__main__":` block also kills its workers)'
            ) from None
        except BaseException:
            for f in futures:
                f.cancel()
            _stop_pool((workers, mp_context or _default_context()))
            raise
    stats = EngineStats(
        "local",
        workers,
        len(batches),
        size,
        seconds=time.perf_counter() - start,
        compute_seconds=col.compute,
    )
    return col.results, stats


# -- Dask --------------------------------------------------------------------------------------


def connect(address: str, timeout: float):
    """A Client for the scheduler at ``address``, or a clear ConnectionError within timeout."""
    try:
        from distributed import Client
    except ImportError:  # pragma: no cover - depends on the install
        raise ValueError(
            "sweep: the Dask engine needs dask.distributed: pip install 'tendonsheath[sweep]'"
        ) from None
    try:
        return Client(address, timeout=f"{timeout}s", set_as_default=False)
    except (OSError, TimeoutError) as exc:
        raise ConnectionError(
            f"cannot reach the Dask scheduler at {address} within {timeout:g} s "
            f"({type(exc).__name__}); is it running and is the address right?"
        ) from None


def is_dask_client(engine) -> bool:
    mod = type(engine).__module__ or ""
    return mod.startswith("distributed") and type(engine).__name__ == "Client"


def run_dask(
    run,
    items,
    client,
    batch_size=None,
    retries: int = 3,
    progress=None,
    record=None,
) -> tuple[dict, EngineStats]:
    """Batches as Dask tasks; a batch lost with its worker is rescheduled (by the scheduler,
    then by us, up to ``retries`` times); outcomes are deduplicated by run index."""
    from distributed import as_completed as dask_as_completed

    workers = max(1, sum(client.nthreads().values()))  # worker threads: the parallelism
    run = portable(run)
    size = int(batch_size or auto_batch_size(len(items), workers))
    batches = make_batches(items, size)
    token = uuid.uuid4().hex[:12]
    start = time.perf_counter()
    attempts = [0] * len(batches)
    batch_of: dict[str, int] = {}
    submitted = []

    def submit(b: int):
        key = f"tendonsheath-sweep-{token}-{b}-{attempts[b]}"
        fut = client.submit(run_batch, run, batches[b], key=key, pure=False, retries=retries)
        batch_of[fut.key] = b
        submitted.append(fut)
        return fut

    resubmitted = 0
    label = f"sweep (dask, {workers} worker{'s' if workers > 1 else ''})"
    with progress_bar(progress, len(items), label) as advance:
        col = _Collector(len(items), advance, record)
        futures = [submit(b) for b in range(len(batches))]
        ac = dask_as_completed(futures)
        try:
            for fut in ac:
                b = batch_of[fut.key]
                try:
                    outcomes = fut.result()
                except Exception as exc:  # noqa: BLE001 - KilledWorker, lost connection, ...
                    if attempts[b] >= retries:
                        raise SweepError(
                            f"batch {b} (runs {batches[b][0][0]}..{batches[b][-1][0]}) failed "
                            f"{attempts[b] + 1} times, last with {type(exc).__name__}: {exc}"
                        ) from exc
                    attempts[b] += 1
                    resubmitted += 1
                    ac.add(submit(b))
                    continue
                finally:
                    fut.release()
                col.add(outcomes)
        except BaseException:
            client.cancel(submitted)
            raise
    missing = [i for i, _ in items if i not in col.results]
    if missing:  # pragma: no cover - would be a scheduler bug
        raise SweepError(f"sweep: {len(missing)} runs came back from no batch: {missing[:10]}")
    stats = EngineStats(
        "dask",
        workers,
        len(batches),
        size,
        resubmitted=resubmitted,
        duplicates_dropped=col.duplicates,
        seconds=time.perf_counter() - start,
        compute_seconds=col.compute,
        extra={"scheduler": client.scheduler.address},
    )
    return col.results, stats


__all__ = [
    "ByValue",
    "EngineStats",
    "Item",
    "Outcome",
    "SweepError",
    "auto_batch_size",
    "connect",
    "is_dask_client",
    "local_pool",
    "make_batches",
    "portable",
    "progress_bar",
    "run_batch",
    "run_dask",
    "run_local",
    "run_serial",
]
