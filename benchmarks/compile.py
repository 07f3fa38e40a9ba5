"""Time `compile_example` on every corpus example and print a table (Markdown with --markdown).

Usage: python benchmarks/compile.py [--markdown] [--repeat N] [NAME ...]
Loading (SVG import, typing) is timed apart from inference; the compile time is the best of N.
"""

from __future__ import annotations

import argparse
import os
import platform
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = Path(os.environ.get("GG_CORPUS", ROOT.parent / "shared" / "corpus" / "examples"))
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from compiler.infer import compile_example  # noqa: E402
from grammar_lang.loader import load_example  # noqa: E402


def machine() -> str:
    cpu = platform.processor() or platform.machine()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return f"{cpu}, {os.cpu_count()} cores, Python {platform.python_version()}"


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*")
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    names = args.names or sorted(p.stem for p in CORPUS.glob("*.svg"))
    rows = []
    for name in names:
        t0 = time.perf_counter()
        ex = load_example(CORPUS / f"{name}.svg")
        load = time.perf_counter() - t0
        best, res = None, None
        for _ in range(max(1, args.repeat)):
            t0 = time.perf_counter()
            res = compile_example(ex)
            dt = time.perf_counter() - t0
            best = dt if best is None else min(best, dt)
        r = res.report
        verdict = "complete" if r.complete else "limited (" + ", ".join(r.limits_hit or ("frontier",)) + ")"
        rows.append((name, r.primitives, r.blocks, r.hierarchy_graphs, r.pruned, r.rules, r.starters,
                     verdict, load, best))
        if not args.markdown:
            print(f"{name:18s} {r.primitives:3d} prims {r.blocks:3d} blocks {r.hierarchy_graphs:6d} graphs "
                  f"{r.pruned:5d} pruned {r.rules:4d}+{r.starters} rules  {verdict:28s} "
                  f"load {load:6.3f}s  compile {best:6.3f}s", flush=True)
    times = [row[-1] for row in rows]
    if args.markdown:
        print("| example | primitives | blocks | hierarchy graphs | pruned | rules + starters "
              "| result | load (s) | compile (s) |")
        print("|---|---|---|---|---|---|---|---|---|")
        for n, p, b, h, pr, ru, st, v, ld, t in rows:
            print(f"| {n} | {p} | {b} | {h} | {pr} | {ru} + {st} | {v} | {ld:.3f} | {t:.3f} |")
        print()
    complete = sum(1 for row in rows if row[7] == "complete")
    print(f"{len(rows)} examples, {complete} complete; compile time median {statistics.median(times):.3f} s, "
          f"max {max(times):.3f} s; machine: {machine()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
