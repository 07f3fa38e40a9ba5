"""Speed of hand-written productions: the seed's five modelling tasks, and per-step time as
the graph grows.

Table 1 runs each example for the seed's step count (Pogrzebacz & Ilčík §5) and prints the
derivation time, wall and CPU (loading and SVG not included), the elements it made, and the
seed's time on this machine where the issue measured it; the speed-up is by wall time. A
derivation that ends before the step count (the façade, the rosette) is terminal. Table 2 grows the Koch curve and the tree to about
100k elements and prints the mean time per step in windows along the way: flat rows mean
matching stays anchored and nothing is copied.

    .venv/bin/python benchmarks/handwritten.py                 # both tables
    .venv/bin/python benchmarks/handwritten.py --elements 20000 --repeat 3
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402
from grammar_lang.ggr_parser import load_ggr  # noqa: E402
from runtime.engine.free_engine import FreeEngine  # noqa: E402

# example, the seed's step count, the seed tool's time here in seconds (None: not measured)
TASKS = [("koch", 192, 5.5), ("honda-tree", 200, 2.9), ("facade", 116, 4.4),
         ("tiles", 128, None), ("rosette", 28, None)]


def derive(name: str, steps: int, seed: int) -> tuple[float, float, int, int]:
    """Wall and CPU seconds of one derivation (CPU time is what the machine's other work
    does not inflate), the steps applied and the elements made."""
    engine = FreeEngine(load_ggr(ROOT / "examples" / f"{name}.ggr"), seed)
    t0, c0 = time.perf_counter(), time.process_time()
    summary = engine.run(steps)
    return (time.perf_counter() - t0, time.process_time() - c0, summary.applied,
            engine.host.size)


def table_tasks(repeat: int) -> None:
    print(f"{'example':<12} {'steps':>6} {'applied':>8} {'elements':>9} {'wall ms':>9} "
          f"{'CPU ms':>8} {'seed tool s':>12} {'speed-up':>9}   (medians over {repeat} seeds)")
    for name, steps, seed_s in TASKS:
        runs = [derive(name, steps, seed) for seed in range(repeat)]
        wall = statistics.median(r[0] for r in runs) * 1000
        cpu = statistics.median(r[1] for r in runs) * 1000
        applied, size = runs[0][2], runs[0][3]
        speed = f"{seed_s * 1000 / wall:.0f}×" if seed_s else "—"
        print(f"{name:<12} {steps:>6} {applied:>8} {size:>9} {wall:>9.2f} {cpu:>8.2f} "
              f"{seed_s if seed_s else '—':>12} {speed:>9}")


def table_growth(name: str, elements: int, windows: int) -> None:
    engine = FreeEngine(load_ggr(ROOT / "examples" / f"{name}.ggr"), 0)
    marks: list[tuple[float, int]] = []
    t0 = time.perf_counter()
    while engine.host.size < elements:
        if not engine.step():
            break
        marks.append((time.perf_counter(), engine.host.size))
    total = time.perf_counter() - t0
    print(f"\n{name}: {len(marks)} steps to {engine.host.size} elements in {total:.2f} s")
    print(f"{'elements':>10} {'µs per step':>12}")
    size = len(marks) // windows
    for k in range(windows):
        chunk = marks[max(1, k * size):(k + 1) * size]
        if len(chunk) < 2:
            continue
        per = (chunk[-1][0] - chunk[0][0]) / (len(chunk) - 1) * 1e6
        print(f"{chunk[-1][1]:>10} {per:>12.1f}")


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--repeat", type=int, default=5, help="seeds per task (median time)")
    p.add_argument("--elements", type=int, default=100_000, help="size of the growth runs")
    p.add_argument("--windows", type=int, default=8, help="rows of the growth table")
    args = p.parse_args()
    pin_blas_threads()
    table_tasks(args.repeat)
    for name in ("koch", "honda-tree"):
        table_growth(name, args.elements, args.windows)


if __name__ == "__main__":
    main()
