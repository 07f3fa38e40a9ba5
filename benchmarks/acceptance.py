"""Acceptance sweep (issue 4): every corpus example and every examples/*.gg, many seeds.

For each example the grammar is compiled once; each seed grows a drawing for `--steps` steps
(`size` cost) and the verifier checks it; structures are told apart by the primitive counts of
their components. One more run per seed-0 grammar asks for many steps (target
`--grow` × the example's vertex count) and reports how far the drawing grew. Examples that do
not compile, or whose grammar has no starter rule, are listed with the reason, not left out.

    .venv/bin/python benchmarks/acceptance.py                    # the whole table
    .venv/bin/python benchmarks/acceptance.py a.svg examples/tree.gg --seeds 5
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from grammar_lang.diagnostics import UserError  # noqa: E402
from runtime.engine.costs import SizeCost  # noqa: E402
from runtime.engine.generate import Engine  # noqa: E402
from runtime.verifier import check_drawing  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "examples"


def all_examples() -> list[Path]:
    return sorted(CORPUS.glob("*.svg")) + sorted((ROOT / "examples").glob("*.gg"))


def structure(engine: Engine) -> tuple:
    """A drawing's structure up to ids and positions: primitive counts per component."""
    h = engine.host
    comps = []
    for comp in h.components():
        counts = [0] * len(h.t.rings)
        for v in comp:
            counts[h.prim[v]] += 1
        comps.append(tuple(counts))
    return tuple(sorted(comps))


@dataclass
class Compiled:
    example: object
    grammar: object | None
    vertices: int                  # the example's vertex count
    problem: str = ""              # why no drawing can be made, when none can

    @property
    def grows(self) -> bool:
        return self.grammar is not None and any(not r.is_starter for r in self.grammar.rules)


def compile_path(path: Path) -> Compiled:
    from compiler.infer import compile_example
    from grammar_lang.loader import load_example
    try:
        example = load_example(path)
        grammar = compile_example(example).grammar
    except UserError as e:
        return Compiled(None, None, 0, f"does not compile: {e}".splitlines()[0])
    n = len(example.graph.vertices) if example.graph else sum(p.count for p in example.primitives)
    if not any(r.is_starter for r in grammar.rules):
        return Compiled(example, grammar, n, "no starter rule")
    return Compiled(example, grammar, n)


@dataclass
class SeedRun:
    seed: int
    failures: list
    structure: tuple
    vertices: int
    consistent: bool


def run_seed(c: Compiled, seed: int, steps: int) -> SeedRun:
    engine = Engine(c.grammar, seed=seed, cost=SizeCost(max(steps, 2 * c.vertices)))
    engine.run(steps)
    failures = check_drawing(c.example, engine.host.to_drawing())
    return SeedRun(seed, failures, structure(engine), len(engine.host),
                   engine.host.check_consistency() == [])


def growth(c: Compiled, factor: float, seed: int = 0) -> tuple[float, float]:
    """(vertices reached / example vertices, seconds) when asked for `factor` × the example."""
    target = int(factor * max(c.vertices, 1))
    engine = Engine(c.grammar, seed=seed, cost=SizeCost(target))
    t0 = time.perf_counter()
    engine.run(3 * target)
    return len(engine.host) / max(c.vertices, 1), time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("examples", nargs="*", help="corpus names (a.svg) or paths; default all")
    ap.add_argument("--seeds", type=int, default=20)
    ap.add_argument("--steps", type=int, default=100, help="steps per seed")
    ap.add_argument("--grow", type=float, default=12.0, help="growth target, × example size")
    args = ap.parse_args(argv)
    paths = [Path(p) if Path(p).exists() else CORPUS / p for p in args.examples] or all_examples()
    print(f"{'example':<24}{'verts':>6}{'seeds ok':>10}{'distinct':>9}{'growth':>8}{'grow s':>8}"
          "  note")
    bad = 0
    for path in paths:
        c = compile_path(path)
        if c.problem:
            bad += 1
            print(f"{path.name:<24}{c.vertices:>6}{'-':>10}{'-':>9}{'-':>8}{'-':>8}  {c.problem}",
                  flush=True)
            continue
        runs = [run_seed(c, s, args.steps) for s in range(args.seeds)]
        ok = sum(1 for r in runs if not r.failures and r.consistent and r.vertices > 0)
        distinct = len({r.structure for r in runs})
        note = []
        if c.grows:
            g, dt = growth(c, args.grow)
            gtxt, ttxt = f"{g:.1f}x", f"{dt:.1f}"
            one_shape = len({comp for r in runs for comp in r.structure}) == 1
            if one_shape:
                note.append("one component shape: drawings differ in copies only")
            if distinct < (3 if one_shape else 5):
                note.append("too few structures")
            if g < 10:
                note.append("grew less than 10x")
        else:
            gtxt, ttxt = "-", "-"
            note.append("starters only")
        if ok < len(runs):
            first = next(r for r in runs if r.failures or not r.consistent or not r.vertices)
            why = first.failures[0].render().splitlines()[0] if first.failures else \
                ("empty drawing" if not first.vertices else "inconsistent host")
            note.append(f"seed {first.seed}: {why}")
        bad += bool(ok < len(runs) or (c.grows and (distinct < (3 if one_shape else 5)
                                                    or g < 10)))
        print(f"{path.name:<24}{c.vertices:>6}{f'{ok}/{len(runs)}':>10}{distinct:>9}{gtxt:>8}"
              f"{ttxt:>8}  {'; '.join(note)}", flush=True)
    print(f"\n{bad} of {len(paths)} examples fall short")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
