"""The same numeric kernels on every machine (grammar_lang/blas.py): numpy and OpenBLAS run
their baseline code paths in every process of ours, the tests' included, so that a drawing's
bytes do not depend on the CPU (AVX2, AVX-512) it was made on."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from grammar_lang.blas import baseline_settings

PROBE = """
import json, sys
import {module}
import numpy
try:
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__
except ImportError:     # numpy 1.x
    from numpy.core._multiarray_umath import __cpu_dispatch__, __cpu_features__
from threadpoolctl import threadpool_info
print(json.dumps({{"dispatch": [f for f in __cpu_dispatch__ if __cpu_features__.get(f)],
                   "blas": [i.get("architecture") for i in threadpool_info()
                            if i.get("internal_api") == "openblas"]}}))
"""

pytestmark = pytest.mark.skipif(not baseline_settings(), reason="x86-64 only")


def kernels(module: str) -> dict:
    out = subprocess.run([sys.executable, "-c", PROBE.format(module=module)],
                         capture_output=True, text=True, timeout=60, check=True)
    return json.loads(out.stdout)


@pytest.mark.parametrize("module", ["runtime.geometry.solver", "compiler.infer",
                                    "report.ggrun", "grammar_lang.planar_noding"])
def test_every_entry_point_runs_the_baseline_kernels(module):
    k = kernels(module)
    assert k["dispatch"] == [], f"numpy dispatches to {k['dispatch']}"
    assert k["blas"] and set(k["blas"]) == {"Nehalem"}, k["blas"]


def test_the_tests_run_the_baseline_kernels():
    # conftest imports grammar_lang before any test module imports numpy
    import numpy
    from threadpoolctl import threadpool_info
    assert numpy is not None and {i.get("architecture") for i in threadpool_info()
                                  if i.get("internal_api") == "openblas"} == {"Nehalem"}


LATE = """
import json
import numpy as np
from grammar_lang.blas import pin_blas_threads
pin_blas_threads()
from runtime.geometry.min_norm import min_norm_inverse
min_norm_inverse(np.eye(3))               # loads scipy's own OpenBLAS, after the pinning
from threadpoolctl import threadpool_info
print(json.dumps([[i.get("filepath"), i.get("num_threads"), i.get("architecture")]
                  for i in threadpool_info() if i.get("internal_api") == "openblas"]))
"""


def test_a_blas_loaded_after_the_pinning_runs_one_thread_and_the_baseline_kernels():
    out = subprocess.run([sys.executable, "-c", LATE], capture_output=True, text=True,
                         timeout=60, check=True, env={**os.environ, "OPENBLAS_NUM_THREADS": "2"})
    libs = json.loads(out.stdout)
    assert len(libs) >= 2, libs          # numpy's and scipy's
    assert {n for _, n, _ in libs} == {1}, libs
    assert {a for _, _, a in libs} == {"Nehalem"}, libs
