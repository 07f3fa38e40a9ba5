"""The paper's own examples (Table 1), compile and generation, beside the paper's figures.

For each illustration in ../shared/corpus/illustrations the example is loaded and compiled
(timed), then grown from its frame for the paper's N iterations (or --iterations), with the
default cost (or --cost). An iteration is one proposal, applied or not (Algorithm 3 counts
them so: the paper's N is not a number of applied steps).
The table shows our figures beside the paper's: compile time against its grammar time,
total time against its total, hierarchy graphs and rules, output vertices against its output
primitives (which count its merged rigid units, so they are smaller), the structures besides
the frame, the shares of the example's face labels and edge classes present, and how much
of the frame the drawing covers: the area of the convex hull of every vertex not on the
frame, over the frame's area. Units count the output as the paper counts its primitives:
a rigid part (vertices joined by edges of fixed length) is one unit, as are the other
vertices, the frame aside. `full at` is the first iteration (counted in fifties) at which
the drawing held 95 % of the most vertices it had during the run: the iterations after it
change the drawing but no longer grow it. `most×` and `least×` say how far the drawing keeps
the example's proportions: per group of the scene cost (the edges beside each face label, and
each class's bare lines; `costs.SceneCost`), its edges over what its share of the example
asks for, the largest and the smallest (1: as in the example).

By default each drawing fills the example's own frame (1540 × 780 px). `--paper-extent`
fills the extent of the original settings instead (the illustrations' README: castle
1600 × 800, station and flowers 2040 × 800 and 2040 × 1200, village 2720 × 1600). A start
that cannot be placed at that extent stays in its own frame, and the table's frame column
says so.

    .venv/bin/python benchmarks/paper.py                       # the paper's N
    .venv/bin/python benchmarks/paper.py --iterations 500      # a quick look
    .venv/bin/python benchmarks/paper.py --steps 300 castle    # time 300 applied steps
    .venv/bin/python benchmarks/paper.py --paper-extent        # the original settings' extents
    .venv/bin/python benchmarks/paper.py --seeds 0-4           # more seeds than the paper's
    .venv/bin/python benchmarks/paper.py --cost size           # another cost (ggrun's --cost)

With `--seeds` each illustration runs once per seed, and a last line per illustration says
in how many drawings every face label and edge class of its example was drawn.
"""

from __future__ import annotations

import argparse
import platform
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

ILLUSTRATIONS = ROOT.parent / "shared" / "corpus" / "illustrations"
# name: (N, seed, paper total s, paper grammar s, hierarchy graphs, rules, output primitives)
PAPER = {
    "castle": (4000, 80, 9.5, 0.7, 1030, 88, 181),
    "space-station": (4000, 22, 13.3, 0.3, 240, 25, 185),
    "flowers": (2000, 42, 10.5, 0.04, 20, 8, 364),
    "village": (4000, 65, 11.8, 0.5, 656, 55, 195),
}
# The original settings' extents, in grid cells of 40 px (the illustrations' README).
EXTENT = {"castle": (40, 20), "space-station": (51, 20), "flowers": (51, 30),
          "village": (68, 40)}


def measure(name: str, iterations: int | None, steps: int | None = None,
            paper_extent: bool = False, seed: int | None = None,
            cost_spec: str | None = None) -> dict:
    import networkx as nx
    import shapely

    from compiler.infer import compile_example
    from grammar_lang.diagnostics import UserError
    from grammar_lang.loader import load_example
    from runtime.engine.costs import default_cost, parse_cost
    from runtime.engine.generate import Engine

    n, paper_seed, *_ = PAPER[name]
    seed = paper_seed if seed is None else seed
    t0 = time.perf_counter()
    example = load_example(ILLUSTRATIONS / f"{name}.gg")
    result = compile_example(example)
    t_compile = time.perf_counter() - t0
    header = result.grammar.header
    cost = parse_cost(cost_spec, header.labels, iterations or n, header)
    extent = None
    if paper_extent:
        extent = tuple(40.0 * c for c in EXTENT[name])
    try:
        engine = Engine(result.grammar, seed=seed, cost=cost, extent=extent)
    except UserError:
        if extent is None:
            raise
        extent = None                      # its start does not fit there: its own frame
        engine = Engine(result.grammar, seed=seed, cost=cost)
    trace: list[tuple[int, int]] = []       # (proposals, vertices), every 50 proposals
    summary = engine.run(steps, progress=lambda s: trace.append((s.proposals, s.vertices)),
                         iterations=iterations or n)
    t_total = time.perf_counter() - t0
    host = engine.host
    g = nx.Graph()
    g.add_nodes_from(v for v in host.vertices() if v not in host.pinned)
    g.add_edges_from((v, w) for v, _, w, _ in host.edges()
                     if v not in host.pinned and w not in host.pinned)
    rigid = nx.Graph()
    rigid.add_nodes_from(g)
    rigid.add_edges_from((v, w) for v, i, w, _ in host.edges() if v in g and w in g
                         and host.t.lengths[host.t.label[host.prim[v]][i]][2] is not None)
    inner = [host.pos[v] for v in host.vertices() if host.prim[v] not in host.on_border]
    covered = 0.0
    if host.frame is not None and len(inner) >= 3:
        w, h = host.frame.size
        covered = shapely.MultiPoint(inner).convex_hull.area / (w * h)
    faces = {f for prim in range(len(host.t.rings)) if host.by_prim[prim]
             for f in host.t.left[prim] + host.t.right[prim]}
    wanted = set(example.face_labels) - {example.exterior}
    drawn = {host.t.label_class[host.t.label[host.prim[v]][i]] for v, i, _, _ in host.edges()}
    classes = {lab.cls for lab in result.grammar.header.labels}
    # The example's proportions (the default cost's groups, whatever cost the run had).
    ratios = default_cost(header, n).ratios(engine.stats())
    return {"name": name, "seed": seed, "iterations": summary.proposals, "steps": summary.applied,
            "compile": t_compile, "total": t_total,
            "graphs": result.report.hierarchy_graphs, "rules": len(result.grammar.rules),
            "vertices": len(host), "components": nx.number_connected_components(g),
            "units": nx.number_connected_components(rigid), "extent": host.frame.size,
            "labels": len(faces & wanted) / max(1, len(wanted)), "covered": covered,
            "classes": len(drawn & classes) / max(1, len(classes)),
            "full_at": _full_at(trace + [(summary.proposals, len(host))]),
            "most": max(ratios), "least": min(ratios),
            "stop": summary.stop}


def _full_at(trace: list[tuple[int, int]]) -> int:
    """The first iteration of `trace` at which the vertices reached 95 % of their most."""
    most = max(v for _, v in trace)
    return next(p for p, v in trace if v >= 0.95 * most)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("names", nargs="*", default=sorted(PAPER), help="illustrations to run")
    ap.add_argument("--iterations", type=int,
                    help="proposals per drawing, applied or not (default: the paper's N)")
    ap.add_argument("--steps", type=int,
                    help="stop after this many applied steps (within the iterations)")
    ap.add_argument("--paper-extent", action="store_true",
                    help="fill the original settings' extent, not the example's frame")
    ap.add_argument("--cost", metavar="NAME[:ARGS]",
                    help="the Metropolis cost, as ggrun's --cost (default: scene with N = "
                         "the iterations)")
    ap.add_argument("--seeds", type=_seeds, help="seeds to run, as 0-4 or 1,5,80 "
                    "(default: the paper's seed for each)")
    args = ap.parse_args(argv)
    print(f"machine: {platform.machine()}, {platform.processor() or platform.system()}, "
          f"Python {platform.python_version()}")
    print(f"{'example':<14}{'seed':>5}{'iter.':>6}{'steps':>6}{'compile s':>10}{'(paper)':>8}{'total s':>9}{'(paper)':>8}"
          f"{'graphs':>7}{'(paper)':>8}{'rules':>6}{'(paper)':>8}{'vertices':>9}{'units':>6}"
          f"{'(paper)':>8}{'parts':>6}{'labels':>7}{'classes':>8}{'covered':>8}{'most×':>6}{'least×':>7}"
          f"{'full at':>8}{'frame':>11}")
    from grammar_lang.diagnostics import UserError
    for name in args.names:
        whole = []
        for seed in args.seeds or [PAPER[name][1]]:
            try:
                r = measure(name, args.iterations, args.steps, args.paper_extent, seed,
                            args.cost)
            except UserError as e:
                print(f"{name:<14}  does not run: {str(e).splitlines()[0]}")
                break
            print(_row(r), flush=True)
            whole.append(r["labels"] == 1.0 and r["classes"] == 1.0)
        if args.seeds and whole:
            print(f"{name:<14} every label and class drawn in {sum(whole)} of {len(whole)}")
    return 0


def _row(r: dict) -> str:
    _, _, total, gram, graphs, rules, out = PAPER[r["name"]]
    return (f"{r['name']:<14}{r['seed']:>5}{r['iterations']:>6}{r['steps']:>6}{r['compile']:>10.2f}"
            f"{gram:>8}{r['total']:>9.1f}{total:>8}{r['graphs']:>7}{graphs:>8}{r['rules']:>6}"
            f"{rules:>8}{r['vertices']:>9}{r['units']:>6}{out:>8}{r['components']:>6}"
            f"{r['labels']:>7.0%}{r['classes']:>8.0%}{r['covered']:>8.1%}{r['most']:>6.2f}"
            f"{r['least']:>7.2f}{r['full_at']:>8}"
            f"{'%g×%g' % r['extent']:>11}" + (f"  ({r['stop']})" if r["stop"] else ""))


def _seeds(text: str) -> list[int]:
    if "-" in text:
        a, b = text.split("-", 1)
        return list(range(int(a), int(b) + 1))
    return [int(s) for s in text.split(",")]


if __name__ == "__main__":
    raise SystemExit(main())
