"""Generation speed: applied rule steps per second, geometry included, as the drawing grows.

For each example and size the grammar is compiled (not timed) in a fresh process, grown with
the `size` cost until the drawing holds that many vertices, and then measured over a window of
steps at that size, so the rows show whether the per-step time stays flat as the drawing
grows. Beside the applied steps per second it prints the iterations per second (proposals,
applied or not: the paper's steps, which its Table 1 counts so), the time per proposal, the
solver's samples per applied step and the drawing's bounding-box area per vertex (in square
units): a grown drawing packs denser as it gets larger, and then more of its proposals fail
their crossing tests: a time per proposal that grows little while the samples per step grow
is the drawing getting harder, not the code getting slower. Each process also reports its
peak memory (`ru_maxrss`), once after compiling and once at the end, so the second minus the
first is what the drawing and its indexes take.

    .venv/bin/python benchmarks/generate.py                       # the simple corpus grammars
    .venv/bin/python benchmarks/generate.py EXAMPLE.svg|.gg|.ggr --sizes 1000,5000 --window 500
    .venv/bin/python benchmarks/generate.py --profile 20000 curl.svg   # cProfile of the window (--sort cumtime)
"""

from __future__ import annotations

import argparse
import gc
import json
import resource
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from runtime.engine.costs import SizeCost  # noqa: E402
from runtime.engine.generate import Engine  # noqa: E402
from report.ggrun import compile_example  # noqa: E402
from runtime.run_cmd import load_grammar  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "examples"
DEFAULT = ["square-filled.svg", "branches.svg", "curl.svg", "h-complex.svg"]


def peak_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024      # KiB on Linux


def measure(path: str, size: int, window: int, seed: int, profile: bool = False,
            sort: str = "tottime") -> dict:
    """Grow one drawing to `size` vertices and time `window` applied steps there."""
    grammar = load_grammar(path, compile_example)
    base = peak_mib()
    engine = Engine(grammar, seed=seed, cost=SizeCost(size))
    t0 = time.perf_counter()
    grow = engine.run(20 * size, stop=lambda: len(engine.host) >= size)
    grown = time.perf_counter() - t0
    # The growth's deferred garbage collection, outside the window: run() holds the automatic
    # collector off, and the first full collection after it walks the whole drawing (0.12 s
    # at 20,000 vertices of branches), once per run, not per step. Left in, it fell on the
    # window's 500 steps and halved branches' steps/s at that size (2,320 → 1,380).
    gc.collect()
    profiler = None
    if profile:
        import cProfile
        profiler = cProfile.Profile()
        profiler.enable()
    samples0 = engine.late.samples
    t0 = time.perf_counter()
    s = engine.run(window)
    dt = time.perf_counter() - t0
    samples = engine.late.samples - samples0
    if profiler is not None:
        import pstats
        profiler.disable()
        pstats.Stats(profiler, stream=sys.stderr).sort_stats(sort).print_stats(40)
    return {"example": Path(path).name, "target": size, "vertices": len(engine.host),
            "area_per_vertex": engine.stats().area / max(len(engine.host), 1),
            "grow_steps": grow.applied, "grow_s": grown,
            "applied": s.applied, "proposals": s.proposals,
            "steps_per_s": s.applied / dt if dt else 0.0,
            "iterations_per_s": s.proposals / dt if dt else 0.0,
            "ms_per_step": 1000 * dt / max(s.applied, 1),
            "us_per_proposal": 1e6 * dt / max(s.proposals, 1),
            "samples_per_step": samples / max(s.applied, 1), "stop": s.stop,
            "base_mib": base, "peak_mib": peak_mib()}


def in_fresh_process(path: str, size: int, window: int, seed: int) -> dict:
    """`measure` in a new interpreter, so that its peak memory is this size's alone."""
    out = subprocess.run([sys.executable, __file__, path, "--sizes", str(size), "--window",
                          str(window), "--seed", str(seed), "--one"],
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", help="examples (.svg, .gg) or grammars (.ggr)")
    ap.add_argument("--sizes", default="1000,5000,20000", help="drawing sizes, in vertices")
    ap.add_argument("--window", type=int, default=500, help="steps measured at each size")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--profile", type=int, metavar="SIZE",
                    help="profile the window at SIZE (cProfile, to stderr) in this process")
    ap.add_argument("--sort", default="tottime", choices=("tottime", "cumtime"),
                    help="how --profile orders its functions (default: own time)")
    ap.add_argument("--one", action="store_true", help=argparse.SUPPRESS)  # a child's run
    args = ap.parse_args(argv)
    # A bare corpus name (curl.svg), as the usage above writes it, is looked up in the corpus.
    paths = [p if Path(p).exists() or not (CORPUS / p).exists() else str(CORPUS / p)
             for p in args.examples] or [str(CORPUS / n) for n in DEFAULT]
    sizes = [int(x) for x in args.sizes.split(",")]
    if args.one or args.profile:
        print(json.dumps(measure(paths[0], args.profile or sizes[0], args.window, args.seed,
                                 profile=bool(args.profile), sort=args.sort)))
        return 0
    print(f"{'example':<20}{'target':>7}{'vertices':>9}{'grown in':>9}{'applied':>8}"
          f"{'proposals':>10}{'steps/s':>9}{'iter./s':>9}{'ms/step':>9}{'µs/prop.':>9}{'samp./step':>11}"
          f"{'area/v':>7}{'MiB base':>9}{'MiB peak':>9}")
    for p in paths:
        for size in sizes:
            r = in_fresh_process(p, size, args.window, args.seed)
            print(f"{r['example']:<20}{r['target']:>7}{r['vertices']:>9}{r['grow_s']:>8.1f}s"
                  f"{r['applied']:>8}{r['proposals']:>10}{r['steps_per_s']:>9.0f}{r['iterations_per_s']:>9.0f}"
                  f"{r['ms_per_step']:>9.2f}{r['us_per_proposal']:>9.0f}"
                  f"{r['samples_per_step']:>11.2f}{r['area_per_vertex']:>7.2f}"
                  f"{r['base_mib']:>9.0f}{r['peak_mib']:>9.0f}"
                  + ("" if r["stop"].startswith("reached") else f"  ({r['stop']})"), flush=True)
    print("goal: 2,000 steps/s on these grammars; the paper's figures count iterations (its "
          "castle: 4,000 in 9.5 s, about 450/s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
