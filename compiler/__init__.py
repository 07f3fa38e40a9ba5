"""Inference: from a typed example to a DPO graph grammar (Merrell 2023, §4-5)."""

import grammar_lang  # noqa: F401,E402 - fixes numpy's kernels first (grammar_lang/blas.py)
