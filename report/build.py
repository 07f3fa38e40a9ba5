"""Gather what a report shows: the grammar and its rule file text, the example, the compile
verdict, the drawn figures and a gallery of generated drawings."""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from grammar_lang.diagnostics import Span, UserError, error
from grammar_lang.example import Example
from grammar_lang.fileio import read_text
from grammar_lang.rules import Grammar

MAX_GALLERY = 64
MAX_STEPS = 100000


@dataclass(frozen=True)
class Verdict:
    complete: bool | None
    text: str
    counts: tuple[tuple[str, str], ...]        # (what, value) rows
    remaining: tuple = ()                       # a few remaining irreducible graphs (Sides)
    remaining_strings: tuple[str, ...] = ()


@dataclass(frozen=True)
class Shot:
    seed: int
    steps: int
    vertices: int
    edges: int
    seconds: float
    stop: str
    svg: str


@dataclass
class Subject:
    path: str
    grammar: Grammar                  # as parsed from `ggr_text`, so rules carry their lines
    ggr_text: str
    ggr_name: str
    example: Example | None
    verdict: Verdict
    times: dict[str, float] = field(default_factory=dict)


def load_subject(path: str) -> Subject:
    """A `.gg`/`.svg` example is compiled in memory (its rule file is the text `ggc compile`
    would write); a `.ggr` is read, and the example it names is drawn when it can be found."""
    from grammar_lang.ggr_emit import emit_ggr
    from grammar_lang.ggr_parser import parse_ggr
    from grammar_lang.loader import load_example

    p = Path(path)
    suffix = p.suffix.lower()
    t0 = time.perf_counter()
    if suffix in (".gg", ".svg"):
        from compiler.infer import compile_example
        example = load_example(p)
        result = compile_example(example)
        text = emit_ggr(result.grammar)
        name = p.with_suffix(".ggr").name
        verdict = _compiled_verdict(result.report)
    elif suffix == ".ggr":
        text = read_text(p)
        name = p.name
        example = None
        verdict = None
    else:
        raise error(f"don't know how to report on '{p.name}'", Span(str(p)),
                    "give an example (.gg, .svg) or a rule file (.ggr)")
    seconds = time.perf_counter() - t0
    grammar = parse_ggr(text, name if suffix != ".ggr" else str(p))
    if grammar.is_free:
        raise error(f"{p.name} holds hand-written productions; the report draws DPO rule "
                    "files (compiled from an example) only", Span(str(p)),
                    f"grow drawings from it with 'ggrun {p.name}'")
    if suffix == ".ggr":
        example = _named_example(grammar, p)
        verdict = _recorded_verdict(grammar)
    times = {"load and compile": seconds}
    if suffix != ".ggr":
        times["of which inference"] = result.report.seconds
    return Subject(str(p), grammar, text, name, example, verdict, times)


def _compiled_verdict(r) -> Verdict:
    counts = (("primitives", f"{r.primitives} ({r.blocks} blocks after grouping)"),
              ("hierarchy graphs", f"{r.hierarchy_graphs} ({r.irreducible} irreducible, "
                                   f"{r.pruned} pruned, {r.generations} generations)"),
              ("rules", f"{r.rules} + {r.starters} starters"),
              ("limits hit", ", ".join(r.limits_hit) or "none"))
    return Verdict(r.complete, r.verdict, counts, r.remaining_sides, r.remaining_boundaries)


def _recorded_verdict(g: Grammar) -> Verdict:
    text = {True: "complete (as recorded in the rule file)",
            False: "limited (as recorded in the rule file; compile the example for details)",
            None: "not known (the rule file records no status)"}[g.header.complete]
    starters = sum(1 for r in g.rules if r.is_starter)
    counts = (("primitives", str(len(g.header.primitives))),
              ("rules", f"{len(g.rules) - starters} + {starters} starters"))
    return Verdict(g.header.complete, text, counts)


def _named_example(g: Grammar, ggr: Path) -> Example | None:
    """The example a rule file names, looked up beside the file and from the working folder."""
    from grammar_lang.loader import load_example
    src = g.header.source
    if not src:
        return None
    for cand in (ggr.parent / src, Path(src), ggr.parent / Path(src).name):
        if cand.is_file():
            try:
                return load_example(cand)
            except UserError:
                return None
    return None


def gallery(grammar: Grammar, seeds: list[int], steps: int) -> list[Shot]:
    """Drawings grown by the runtime's engine, one per seed, as SVG text."""
    from runtime.engine.costs import parse_cost
    from runtime.engine.generate import Engine
    from runtime.output.svg_out import render_svg

    if not 0 <= steps <= MAX_STEPS:
        raise error(f"--steps {steps} is out of range", None, f"give 0 to {MAX_STEPS}")
    cost = parse_cost(None, grammar.header.labels, steps, grammar.header)
    out = []
    for seed in seeds:
        engine = Engine(grammar, seed, cost)
        s = engine.run(steps)
        drawing = engine.host.to_drawing({"seed": seed, "steps": s.applied})
        out.append(Shot(seed, s.applied, s.vertices, s.edges, s.seconds, s.stop,
                        render_svg(drawing, grammar.header)))
    return out
