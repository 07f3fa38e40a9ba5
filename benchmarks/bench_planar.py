"""How fast drawings become planar graphs: SVG import and `build_planar_graph` at growing sizes.

    .venv/bin/python benchmarks/bench_planar.py [--sizes 10 20 40]

Three generated drawings per size n: an n×n grid of overlapping filled squares (painter's
order, hidden outlines), n² jittered hand-drawn strokes forming a lattice (merging, near
T-junctions), and 3n random long segments (many crossings). Prints input size, output size and
seconds for import and build.
"""

from __future__ import annotations

import argparse
import random
import time

from grammar_lang.planar import build_planar_graph
from grammar_lang.svg_import import import_svg

HEAD = '<svg xmlns="http://www.w3.org/2000/svg">\n'


def squares(n: int, rng: random.Random) -> str:
    body = []
    for i in range(n):
        for j in range(n):
            x, y = 10 * i, 10 * j
            colour = ["#c0f0ff", "#ffc0c0", "#c0ffc0"][(i * 7 + j) % 3]
            body.append(f'<rect x="{x}" y="{y}" width="14" height="14" fill="{colour}" '
                        'stroke="#000"/>')
    return HEAD + "\n".join(body) + "\n</svg>"


def lattice(n: int, rng: random.Random) -> str:
    def jitter() -> float:
        return rng.uniform(-0.3, 0.3)
    body = []
    for i in range(n + 1):
        for j in range(n):
            body.append(f'<line x1="{20 * i + jitter()}" y1="{20 * j + jitter()}" '
                        f'x2="{20 * i + jitter()}" y2="{20 * j + 20 + jitter()}" stroke="#000"/>')
            body.append(f'<line x1="{20 * j + jitter()}" y1="{20 * i + jitter()}" '
                        f'x2="{20 * j + 20 + jitter()}" y2="{20 * i + jitter()}" stroke="#000"/>')
    return HEAD + "\n".join(body) + "\n</svg>"


def crossings(n: int, rng: random.Random) -> str:
    body = [f'<line x1="{rng.uniform(0, 1000)}" y1="{rng.uniform(0, 1000)}" '
            f'x2="{rng.uniform(0, 1000)}" y2="{rng.uniform(0, 1000)}" stroke="#000"/>'
            for _ in range(3 * n)]
    return HEAD + "\n".join(body) + "\n</svg>"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="+", default=[10, 20, 40])
    args = parser.parse_args()
    print(f"{'drawing':<10} {'n':>4} {'shapes':>7} {'vertices':>9} {'edges':>8} "
          f"{'import s':>9} {'build s':>8}")
    for n in args.sizes:
        for make in (squares, lattice, crossings):
            text = make(n, random.Random(n))
            start = time.perf_counter()
            source = import_svg(f"{make.__name__}.svg", text)
            imported = time.perf_counter()
            graph = build_planar_graph(source)
            built = time.perf_counter()
            print(f"{make.__name__:<10} {n:>4} {len(source.paint):>7} {len(graph.vertices):>9} "
                  f"{len(graph.edges):>8} {imported - start:>9.3f} {built - imported:>8.3f}")


if __name__ == "__main__":
    main()
