"""How fast `.gg` text parses: a generated grid of cells as polygons, lines and edges.

    .venv/bin/python benchmarks/bench_gg_parser.py [--cells 60]

Prints statements per second and points per second for the syntax pass and the whole parse
(syntax + name resolution and checks; no planar graph).
"""

from __future__ import annotations

import argparse
import time

from grammar_lang.gg_parser import parse_syntax, parse_text


def grid_text(n: int) -> tuple[str, int, int]:
    lines = ['example "bench grid"', "face cell #c0f0ff", "face hole", "class rail { min: 1 }"]
    points = 0
    for i in range(n):
        for j in range(n):
            x, y = 10 * i, 10 * j
            if (i + j) % 3 == 0:
                lines.append(f"polygon cell rect ({x}, {y}) ({x + 10}, {y + 10})")
                points += 2
            elif (i + j) % 3 == 1:
                lines.append(f"edge ({x}, {y}) -> ({x + 10}, {y}) -> ({x + 10}, {y + 10}) "
                             f"left hole right cell")
                points += 3
            else:
                lines.append(f"polyline [({x}, {y}) ({x + 5}, {y + 3.5e0}) ({x + 10}, {y})] "
                             f"class rail")
                points += 3
    return "\n".join(lines) + "\n", len(lines), points


def best_of(fn, repeat: int = 3) -> float:
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--cells", type=int, default=60, help="grid side (cells² statements)")
    args = ap.parse_args()
    text, n_stmts, n_points = grid_text(args.cells)
    parse_syntax("face a\n")                       # build the LALR tables once
    syntax = best_of(lambda: parse_syntax(text, "bench.gg"))
    whole = best_of(lambda: parse_text(text, "bench.gg"))
    print(f"{n_stmts} statements, {n_points} points, {len(text) / 1024:.0f} KiB")
    print(f"syntax : {syntax * 1000:8.1f} ms  {n_stmts / syntax:10.0f} statements/s  "
          f"{n_points / syntax:10.0f} points/s")
    print(f"parse  : {whole * 1000:8.1f} ms  {n_stmts / whole:10.0f} statements/s  "
          f"{n_points / whole:10.0f} points/s")


if __name__ == "__main__":
    main()
