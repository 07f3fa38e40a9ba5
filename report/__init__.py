"""What needs both the compiler and the runtime: `ggc report` and `ggc draw`.

`compiler` and `runtime` never import each other. The report shows a compiled grammar (the
compiler's product) drawn with the runtime's geometry (rule sides are placed by
`runtime.geometry.place_side`, the generation solver, not by a second layout engine) and its
engine (the gallery). So it lives here, one layer above both, and so does the `ggc` entry
point that offers it (`report.ggc`): it extends the compiler's command line with these two
commands, so the compiler's own CLI stays free of runtime imports.
"""
