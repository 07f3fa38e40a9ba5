"""How fast drawings are checked (`check_drawing`) and drawn (`render_svg`) as they grow.

    .venv/bin/python benchmarks/verify.py [--sizes 5 10 20 40] [--examples star-filled h]

Each drawing is an n×n grid of copies of a corpus example drawn as itself (so it passes every
check and every check runs to the end: faces, nesting, crossings). Prints vertices, edges and
seconds per call, and microseconds per edge, which should stay flat as n grows.
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

from grammar_lang.loader import load_example  # noqa: E402
from runtime.output.drawing import DEdge, Drawing, DVertex, drawing_from_example  # noqa: E402
from runtime.output.svg_out import render_svg  # noqa: E402
from runtime.verifier import check_drawing  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "examples"


def grid(d: Drawing, n: int) -> Drawing:
    xs = [v.x for v in d.vertices]
    ys = [v.y for v in d.vertices]
    step = max(max(xs) - min(xs), max(ys) - min(ys)) * 1.5
    size = max(v.id for v in d.vertices) + 1
    verts, edges = [], []
    for i in range(n):
        for j in range(n):
            off = (i * n + j) * size
            verts += [DVertex(v.id + off, v.x + i * step, v.y + j * step) for v in d.vertices]
            edges += [DEdge(e.u + off, e.v + off, e.left, e.right, e.cls, e.label)
                      for e in d.edges]
    return Drawing(tuple(verts), tuple(edges))


def best_of(f, repeat: int = 3) -> float:
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        f()
        times.append(time.perf_counter() - t)
    return min(times)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[5, 10, 20, 40])
    ap.add_argument("--examples", nargs="+", default=["star-filled", "x-box-square", "h"])
    args = ap.parse_args()
    print(f"{'example':14} {'n':>4} {'vertices':>9} {'edges':>7} {'check s':>8} {'µs/edge':>8} "
          f"{'svg s':>7} {'µs/edge':>8}")
    for name in args.examples:
        ex = load_example(CORPUS / f"{name}.svg")
        own = drawing_from_example(ex)
        for n in args.sizes:
            d = grid(own, n)
            failures = check_drawing(ex, d)
            assert not failures, failures[0].render()
            tc = best_of(lambda: check_drawing(ex, d))
            ts = best_of(lambda: render_svg(d, ex))
            m = len(d.edges)
            print(f"{name:14} {n:>4} {len(d.vertices):>9} {m:>7} {tc:>8.3f} {tc / m * 1e6:>8.1f} "
                  f"{ts:>7.3f} {ts / m * 1e6:>8.1f}")


if __name__ == "__main__":
    main()
