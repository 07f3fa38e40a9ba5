"""Generation speed: applied rule steps per second, geometry included, as the drawing grows.

For each example the grammar is compiled once (not timed), grown to each size in turn with the
`size` cost, and then measured over a window of steps at that size, so the rows show whether
the per-step time stays flat as the drawing grows.

    .venv/bin/python benchmarks/generate.py                       # a few corpus examples
    .venv/bin/python benchmarks/generate.py EXAMPLE.svg|.gg|.ggr --sizes 100,1000 --window 500
"""

from __future__ import annotations

import argparse
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
DEFAULT = ["square-filled.svg", "l.svg", "plus.svg", "h.svg", "branches.svg"]


def measure(path: str, sizes: list[int], window: int, seed: int) -> list[dict]:
    grammar = load_grammar(path, compile_example)
    rows = []
    engine = Engine(grammar, seed=seed)
    for size in sizes:
        engine.cost = SizeCost(size)
        engine.run(10 * size)                    # grow (stops once `size` steps are applied)
        while len(engine.host) < 0.9 * size:
            before = len(engine.host)
            engine.run(size)
            if len(engine.host) <= before:
                break
        t0 = time.perf_counter()
        s = engine.run(window)
        dt = time.perf_counter() - t0
        rows.append({"example": Path(path).name, "target": size, "vertices": len(engine.host),
                     "applied": s.applied, "proposals": s.proposals,
                     "steps_per_s": s.applied / dt if dt else 0.0,
                     "ms_per_step": 1000 * dt / max(s.applied, 1), "stop": s.stop})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", help="examples (.svg, .gg) or grammars (.ggr)")
    ap.add_argument("--sizes", default="100,300,1000", help="drawing sizes, in vertices")
    ap.add_argument("--window", type=int, default=500, help="steps measured at each size")
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    paths = args.examples or [str(CORPUS / n) for n in DEFAULT]
    sizes = [int(x) for x in args.sizes.split(",")]
    print(f"{'example':<22}{'target':>7}{'vertices':>9}{'applied':>8}{'proposals':>10}"
          f"{'steps/s':>9}{'ms/step':>9}")
    for p in paths:
        for r in measure(p, sizes, args.window, args.seed):
            print(f"{r['example']:<22}{r['target']:>7}{r['vertices']:>9}{r['applied']:>8}"
                  f"{r['proposals']:>10}{r['steps_per_s']:>9.0f}{r['ms_per_step']:>9.2f}"
                  + ("" if r["stop"].startswith("reached") else f"  ({r['stop']})"), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
