"""Generation (Merrell 2023, §6), laid out by role: `engine` (host, matching, rewriting,
schedule, generation), `geometry` (placement solver, spatial grid, faces, landing, frame),
`output` (drawing JSON, SVG, GraphML), `verifier` (local similarity of a drawing to its
example), `repl`; `cli` and `run_cmd` are `ggrun`'s command line, `interrupt` its Ctrl-C."""

import grammar_lang  # noqa: F401,E402 - fixes numpy's kernels first (grammar_lang/blas.py)
