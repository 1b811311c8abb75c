"""The BLAS on a given number of threads: NumPy's and SciPy's, which are two libraries.

threadpoolctl limits only the libraries loaded when it is asked, and SciPy's own OpenBLAS loads
with ``scipy.linalg``, which ``import tendonsheath`` no longer imports: a fit that imported it
inside a limit ran its least squares on every core, and its sums split by the thread count (the
demo's shape-aware figures moved in the ninth digit). So SciPy's BLAS is loaded first.
"""

from __future__ import annotations

import contextlib
from collections.abc import Iterator


def _load_scipy_blas() -> None:
    import scipy.linalg  # noqa: F401 - loads SciPy's OpenBLAS, for threadpoolctl to see


@contextlib.contextmanager
def one_blas_thread() -> Iterator[None]:
    """NumPy's and SciPy's BLAS on one thread inside the block (or the decorated function).

    Yields
    ------
    None
    """
    import threadpoolctl

    _load_scipy_blas()
    with threadpoolctl.threadpool_limits(1, user_api="blas"):
        yield


def limit_blas_threads(threads: int | None, user_api: str | None = None) -> None:
    """NumPy's and SciPy's BLAS (and, with ``user_api`` None, OpenMP) on ``threads`` threads
    for the rest of the process (a worker's start).

    Parameters
    ----------
    threads : int or None
        The threads each may use.
    user_api : str, optional
        "blas" for the BLAS only; None for every thread pool threadpoolctl knows.
    """
    import threadpoolctl

    _load_scipy_blas()
    threadpoolctl.threadpool_limits(threads, user_api=user_api)


__all__ = ["limit_blas_threads", "one_blas_thread"]
