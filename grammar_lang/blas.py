"""One BLAS thread per process.

The solver works on many small matrices (tens of rows): OpenBLAS's worker threads spin up and
wait on each product, which made a castle run 4–5× slower on two cores than with one thread.
An environment variable set after numpy is loaded does nothing, so the pool is limited through
threadpoolctl, in this process only (the user's environment is left alone). The CLIs call it
once their arguments are parsed (so `--help` and `--version` never load numpy), worker
processes call it as their initializer, and the tests and benchmarks call it at start-up.
"""

from __future__ import annotations

_pinned = False


def pin_blas_threads() -> None:
    global _pinned
    if _pinned:
        return
    import numpy  # noqa: F401 - threadpoolctl only sees libraries that are loaded
    from threadpoolctl import threadpool_limits
    threadpool_limits(limits=1, user_api="blas")
    _pinned = True
