"""Numeric kernels: one code path on every machine, one BLAS thread per process.

**The same code path.** numpy and OpenBLAS pick their kernels for the CPU they run on (AVX2,
AVX-512, FMA, …). Those kernels round differently, and the solver's least squares carry the
difference into the last printed digits of a drawing: a drawing made on an AVX-512 machine
differed in its sixth decimal from the same run on an AVX2 machine. `fix_kernels` therefore
asks both libraries for the baseline kernels every x86-64 CPU that runs numpy has (numpy's
baseline features, OpenBLAS's Nehalem kernels). Both read these settings once, when they load,
so this runs when `grammar_lang` is imported, before anything of ours imports numpy; it is set
in this process only (and so in the worker processes it starts), never in the user's shell.
The cost on the castle illustration was within timing noise. Other architectures run
their own kernels: there, drawings are reproducible on the same kind of CPU.

**One thread.** The solver works on many small matrices (tens of rows): OpenBLAS's worker
threads spin up and wait on each product, which made a castle run 4–5× slower on two cores
than with one thread. The pool is limited through threadpoolctl. The CLIs call
`pin_blas_threads` once their arguments are parsed (so `--help` and `--version` never load
numpy), worker processes call it as their initializer, and the tests and benchmarks call it at
start-up.
"""

from __future__ import annotations

import os
import platform
import sys
from importlib import metadata

_pinned = False


def baseline_settings() -> dict[str, str]:
    """The environment settings that select the baseline kernels, for the numpy installed
    (numpy 2.4 renamed its x86 feature groups; an unknown name stops numpy from loading)."""
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return {}
    try:
        major, minor = (int(p) for p in metadata.version("numpy").split(".")[:2])
    except (metadata.PackageNotFoundError, ValueError):
        return {}
    baseline = "X86_V2" if (major, minor) >= (2, 4) else "SSE2"
    return {"NPY_ENABLE_CPU_FEATURES": baseline, "OPENBLAS_CORETYPE": "Nehalem"}


def fix_kernels() -> None:
    """Select the baseline kernels, if numpy is not loaded yet (after that it is too late)."""
    if "numpy" not in sys.modules:
        os.environ.update(baseline_settings())


def pin_blas_threads() -> None:
    global _pinned
    if _pinned:
        return
    # A BLAS loaded later (scipy's own OpenBLAS, which the solver's pseudo-inverse loads on
    # first use) reads its thread count from the environment when it loads; unpinned, it
    # ran the castle on both cores for no gain (user time 21.7 s against 10.5 s wall).
    os.environ["OPENBLAS_NUM_THREADS"] = "1"
    import numpy  # noqa: F401 - threadpoolctl only sees libraries that are loaded
    from threadpoolctl import threadpool_limits
    threadpool_limits(limits=1, user_api="blas")
    _pinned = True
