"""The languages (.gg examples, .ggr rule files), their diagnostics, and the shared model of
labels, graphs, boundary strings and rules."""

__version__ = "0.1.0"

# Before anything imports numpy: the same numeric kernels on every machine (see blas.py).
from .blas import fix_kernels as _fix_kernels  # noqa: E402

_fix_kernels()
