"""What needs both the compiler and the runtime: `ggc report` and `ggc draw`.

`compiler` and `runtime` never import each other. The report shows a compiled grammar (the
compiler's product) drawn with the runtime's geometry (rule sides are placed by
`runtime.geometry.solver.place_side`, the generation solver, not by a second layout engine) and its
engine (the gallery). So it lives here, one layer above both, and so do the two entry points:
`report.ggc` extends the compiler's command line with these two commands, so the compiler's
own CLI stays free of runtime imports, and `report.ggrun` hands the runtime's command line the
compiler, so that `ggrun` can run an example by compiling it in memory.
"""

import grammar_lang  # noqa: F401,E402 - fixes numpy's kernels first (grammar_lang/blas.py)
