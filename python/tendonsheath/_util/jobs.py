"""Independent pieces of work (the demo's scenarios and studies) on a few worker processes.

Each job is a module-level function called with its keyword arguments and ``progress=``, a
callable that takes a line saying which step begins. In a worker the lines come back to this
process as they are said, and so do the warnings the job raised (once each, after every job
has finished, in the order of the jobs), so that a caller sees what a serial run shows. A job
that fails stops the others and its exception is raised here, naming the job, with the
worker's traceback as its cause. With one worker (one core) every job runs in this process,
in order.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import pickle
import queue
import signal
import threading
import time
import warnings
from collections.abc import Callable, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field
from typing import Any

Progress = Callable[[str], None] | None


@dataclass(frozen=True)
class Job:
    """``run(**kwargs, progress=...)`` under the name ``key``; ``cost`` (seconds of CPU, a
    rough figure) orders the jobs, longest first, so that the workers finish together."""

    key: str
    run: Callable[..., Any]
    kwargs: dict[str, Any] = field(default_factory=dict)
    cost: float = 1.0


def cores() -> int:
    """The cores this process may run on (its CPU affinity where the system says it)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - macOS, Windows
        return os.cpu_count() or 1


def travels(run: Callable) -> bool:
    """Whether a worker can import ``run`` by name (a module's top-level function; not a
    lambda, a local function or one of a script's)."""
    if getattr(run, "__module__", None) in (None, "__main__"):
        return False
    try:
        pickle.dumps(run)
    except Exception:  # noqa: BLE001 - local functions, lambdas
        return False
    return True


def run_jobs(
    jobs: Sequence[Job],
    workers: int,
    progress: Progress = None,
    preload: Sequence[str] = (),
) -> dict[str, tuple[Any, float]]:
    """key -> (what the job returned, its seconds), the jobs run on ``workers`` processes
    (1: in this process, in the order given). A job whose function cannot travel to a
    worker runs in this process while the workers run the others. ``preload``: modules the
    workers import before their first job.

    Every job runs with the BLAS on one thread, here and in the workers: a BLAS on several
    threads splits its sums by the thread count, so that an ill-conditioned fit lands
    elsewhere on a machine with more or fewer cores (up to a few percent in the demo's
    lau2015); on one thread the results are the same on any machine and for any
    ``workers``. The small matrices of the fits gain nothing from BLAS threads anyway, and
    lose much on a loaded machine (see identify.servo)."""
    from .blas import one_blas_thread
    from .main_guard import unguarded_script

    remote = [job for job in jobs if travels(job.run)]
    with one_blas_thread():
        if workers <= 1 or len(remote) <= 1 or unguarded_script() is not None:
            return {job.key: _timed(job, progress) for job in jobs}
        return _on_workers(jobs, remote, min(workers, len(remote)), progress, preload)


def _timed(job: Job, progress: Progress) -> tuple[Any, float]:
    start = time.perf_counter()
    value = job.run(**job.kwargs, progress=progress)
    return value, time.perf_counter() - start


# -- in the workers -------------------------------------------------------------------------

_LINES: Any = None  # the queue a worker's progress lines go back by


def _start_worker(lines, threads: int) -> None:
    """Ctrl-C is the main process's to handle (it stops the workers); each worker's batched
    calls run on its share of the cores, and its BLAS on one thread (see run_jobs)."""
    global _LINES
    _LINES = lines
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    os.environ["TENDONSHEATH_NUM_THREADS"] = str(threads)
    from .blas import limit_blas_threads

    limit_blas_threads(1, user_api="blas")


def _say(line: str) -> None:
    _LINES.put(line)


def _run_in_worker(run: Callable, kwargs: dict) -> tuple[Any, list[tuple], float]:
    """(value, warnings, seconds) of ``run(**kwargs)``: each distinct warning once, as
    (message, category, filename, lineno), for the main process to raise again."""
    start = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")  # the main process's filters decide
        value = run(**kwargs, progress=_say)
    said = dict.fromkeys((str(w.message), w.category, w.filename, w.lineno) for w in caught)
    return value, list(said), time.perf_counter() - start


# -- in this process ------------------------------------------------------------------------


def _on_workers(jobs, remote, workers: int, progress: Progress, preload):
    method = "forkserver" if "forkserver" in multiprocessing.get_all_start_methods() else "spawn"
    ctx = multiprocessing.get_context(method)
    if method == "forkserver":  # effective when this process starts its fork server
        ctx.set_forkserver_preload(["tendonsheath", *preload])
    threads = max(1, cores() // workers)
    pool: ProcessPoolExecutor | None = None
    done: dict[str, tuple[Any, list, float]] = {}
    try:
        # the Ctrl-C held back here arrives as the block ends, still inside this try: the
        # workers are then stopped before this process exits and removes the queue's
        # semaphore, which a worker still starting would fail to find (a traceback)
        with _ctrl_c_held():  # the processes started here never see Ctrl-C
            lines = ctx.Queue()
            pool = ProcessPoolExecutor(
                workers, ctx, initializer=_start_worker, initargs=(lines, threads)
            )
            futures = {
                pool.submit(_run_in_worker, job.run, job.kwargs): job
                for job in sorted(remote, key=lambda j: -j.cost)
            }
        for job in jobs:  # what cannot travel runs here meanwhile
            if job not in remote:
                value, seconds = _timed(job, lambda line: _relay(lines, progress, line))
                done[job.key] = (value, [], seconds)
        pending: set[Future] = set(futures)
        while pending:
            finished, pending = wait(pending, timeout=0.1, return_when=FIRST_COMPLETED)
            _relay(lines, progress)
            for fut in finished:
                done[futures[fut].key] = _outcome(fut, futures[fut], futures)
        pool.shutdown(wait=True)
        _relay(lines, progress)
    except BaseException:
        if pool is not None:
            _stop(pool)
        raise
    for job in jobs:  # the warnings in the jobs' order, as a serial run raises them
        for message, category, filename, lineno in done[job.key][1]:
            warnings.warn_explicit(message, category, filename, lineno)
    return {key: (value, seconds) for key, (value, _, seconds) in done.items()}


@contextlib.contextmanager
def _ctrl_c_held():
    """Hold Ctrl-C (SIGINT) back while the fork server and the workers start, and deliver it
    once they have. The block (a thread's signal mask) is inherited by the processes started
    here, which keep it: a Ctrl-C at the terminal reaches the whole process group, and the
    fork server imports its preload before it ignores SIGINT (a KeyboardInterrupt there
    printed a traceback or left the pool waiting on a dead server). The mask holds only this
    thread, and the kernel hands a process's signal to any thread that does not block it (a
    BLAS or progress thread), so this process's handler is also swapped for one that notes
    the Ctrl-C: raised mid-start, the KeyboardInterrupt left a worker started but not yet
    counted by the pool, never stopped, failing with a traceback once this process had exited
    and removed the queue's semaphore. Off the main thread, or where signals cannot be
    blocked, it does nothing."""
    if not hasattr(signal, "pthread_sigmask") or (
        threading.current_thread() is not threading.main_thread()
    ):
        yield
        return
    from multiprocessing import resource_tracker

    resource_tracker.ensure_running()  # first: starting it unblocks SIGINT
    noted: list[int] = []
    handler = signal.signal(signal.SIGINT, lambda signum, frame: noted.append(signum))
    mask = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)  # one held back is noted now
        signal.signal(signal.SIGINT, handler)
        if noted:
            signal.raise_signal(signal.SIGINT)  # to the handler this process had


def _outcome(fut: Future, job: Job, futures: dict[Future, Job]):
    try:
        return fut.result()
    except BrokenProcessPool:
        lost = ", ".join(j.key for f, j in futures.items() if not f.done() or f is fut)
        raise RuntimeError(
            f"a worker process died (killed, or out of memory?) while running: {lost}"
        ) from None
    except Exception as exc:
        exc.add_note(f"(raised in the worker process running {job.key})")
        raise


def _relay(lines, progress: Progress, line: str | None = None) -> None:
    """Pass the workers' progress lines said so far (and ``line``, said here) on."""
    while True:
        try:
            said = lines.get_nowait()
        except queue.Empty:
            break
        if progress:
            progress(said)
    if line is not None and progress:
        progress(line)


def _stop(pool: ProcessPoolExecutor) -> None:
    """Stop the workers now (after an error or Ctrl-C: the rest of their work is not wanted)."""
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        proc.terminate()
    pool.shutdown(wait=True, cancel_futures=True)


__all__ = ["Job", "cores", "run_jobs", "travels"]
