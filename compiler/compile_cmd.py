"""`ggc compile` and `ggc verify`: the front of inference and of its independent check."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from rich.console import Console
from rich.table import Table

from grammar_lang.diagnostics import Span, UserError, error
from grammar_lang.fileio import atomic_write, read_text
from grammar_lang.reach import connected_warning

from .infer import CompileResult, Report, compile_example


def _progress_bar(err: Console, title: str):
    """A rich progress display on a terminal; nothing when stderr is not one."""
    if not sys.stderr.isatty():
        return None, None
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
    bar = Progress(TextColumn("[bold]{task.description}"), BarColumn(),
                   TextColumn("{task.fields[info]}"), TimeElapsedColumn(), console=err,
                   transient=True)
    task = bar.add_task(title, total=None, info="")
    return bar, task


REPORT_FORMAT = "ggc-report/1"


def _check_report_target(p: Path) -> None:
    """Like the rule file, --report replaces only what ggc wrote: an earlier report."""
    if not (p.exists() or p.is_symlink()):
        return
    try:
        doc = json.loads(read_text(p))
    except (UserError, ValueError, RecursionError):
        doc = None
    if not (isinstance(doc, dict) and doc.get("format") == REPORT_FORMAT):
        raise error(f"{p} exists and is not a report written by ggc; not overwriting it",
                    Span(str(p)), "choose another --report path, or pass --force to replace it")


def run_compile(args) -> int:
    from grammar_lang.ggr_file import write_ggr
    from grammar_lang.loader import load_example

    example = load_example(args.file)
    out = Console(highlight=False, soft_wrap=True)
    err = Console(stderr=True, highlight=False, soft_wrap=True)
    for note in example.notes:
        err.print(note.render(), markup=False)
    target = Path(args.output) if args.output else Path(args.file).with_suffix(".ggr")
    if args.report and Path(args.report).resolve() == target.resolve():
        raise error("the report and the rule file would be the same file", Span(args.report),
                    "give --report a .json path")
    if args.report and not args.force:
        _check_report_target(Path(args.report))
    bar, task = _progress_bar(err, f"compiling {Path(args.file).name}")

    def progress(gen: int, graphs: int, rules: int) -> None:
        if bar is not None:
            bar.update(task, info=f"generation {gen}, {graphs} graphs, {rules} rules")

    if bar is not None:
        with bar:
            result = compile_example(example, progress)
    else:
        result = compile_example(example)
    write_ggr(target, result.grammar, force=args.force)
    gap = connected_warning(result.grammar)
    if gap is not None:
        err.print(gap.render(), markup=False)
    if args.report:
        data = {"format": REPORT_FORMAT, **result.report.as_dict()}
        data["output"] = str(target)
        atomic_write(Path(args.report), json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    out.print(summary_table(result, str(target)))
    return 0


def summary_table(result: CompileResult, target: str) -> Table:
    r: Report = result.report
    t = Table(title=f"{r.example} → {target}", show_header=False)
    t.add_column("what")
    t.add_column("value")
    t.add_row("primitives", f"{r.primitives} ({r.blocks} blocks after grouping)")
    t.add_row("hierarchy graphs", f"{r.hierarchy_graphs} ({r.irreducible} irreducible, "
              f"{r.pruned} pruned, {r.generations} generations)")
    n = r.rules_stood
    stood = f" ({n} stand{'s' if n == 1 else ''} a structure on the frame or a line across it)" \
        if n else ""
    t.add_row("rules", f"{r.rules} + {r.starters} starter{'s' if r.starters != 1 else ''}{stood}")
    t.add_row("time", f"{r.seconds:.2f} s")
    t.add_row("result", r.verdict)
    if not r.complete and r.remaining_boundaries:
        t.add_row("e.g.", ", ".join(r.remaining_boundaries))
    return t


def run_verify(args) -> int:
    from grammar_lang.ggr_parser import load_ggr

    from .verify import verify

    grammar = load_ggr(args.file)
    if grammar.is_free:
        raise error(f"{Path(args.file).name} holds hand-written productions; 'ggc verify' "
                    "checks the completeness of angle-graph rules", Span(args.file),
                    "productions are not reductions of complete graphs: there is nothing to verify")
    out = Console(highlight=False, soft_wrap=True)
    err = Console(stderr=True, highlight=False, soft_wrap=True)
    if args.max_primitives < 1:
        raise error("--max-primitives must be at least 1", Span(args.file))
    if args.seconds is not None and not args.seconds > 0:
        raise error("--seconds must be positive", Span(args.file), "leave it out for no limit")
    bar, task = _progress_bar(err, f"verifying {Path(args.file).name}")

    def progress(done: int, total: int) -> None:
        bar.update(task, total=total, completed=done, info=f"{done}/{total} graphs reduced")

    def enumerating(seen: int, size: int) -> None:
        bar.update(task, info=f"enumerating: {seen} graphs seen, now {size} primitives")

    if bar is not None:
        with bar:
            res = verify(grammar, args.max_primitives, progress, seconds=args.seconds,
                         enumerating=enumerating)
    else:
        res = verify(grammar, args.max_primitives, seconds=args.seconds)
    names = [p.name for p in grammar.header.primitives]
    for name in res.skipped_rules:
        err.print(f"note: rule '{name}' has a disconnected left side; verify does not apply it",
                  markup=False)
    if res.enumeration_capped:
        err.print("note: stopped enumerating at the graph cap; lower --max-primitives for a "
                  "complete check", markup=False)
    elif res.stopped:
        err.print(f"note: stopped at the {args.seconds:g} s time limit after {res.checked} of "
                  f"{res.enumerated} complete graphs found so far; this is not a complete check "
                  "(lower --max-primitives or raise --seconds)", markup=False)
    goal = "∅ or the frame" if grammar.header.frame is not None else "∅"
    out.print(f"checked {res.checked} complete graphs with at most {args.max_primitives} "
              f"primitives: {res.checked - len(res.failed)} reduce to {goal}, "
              f"{len(res.failed)} failed" + (f" ({res.stopped}: partial)" if res.stopped else ""),
              markup=False)
    for g in res.failed[:20]:
        prims = ", ".join(names[p] for p in g.verts)
        out.print(f"  failed: {len(g.verts)} vertices [{prims}], edges {list(g.edges)}",
                  markup=False)
    _explain_unreached(grammar, res.failed, err)
    return 0 if res.ok else 1


def _explain_unreached(grammar, failed, err) -> None:
    """A grammar whose frame starts from its start graph cannot draw a scene that holds the
    frame in another way (one strip of land, not two): say so, since no rule is wrong."""
    frame = grammar.header.frame
    if frame is None or frame.start is None:
        return
    corners = {c.prim for c in frame.corners}
    held = sum(1 for g in failed if corners & set(g.verts))
    if held:
        err.print(f"note: {held} failed graph(s) hold the frame but are not its start graph "
                  f"({len(frame.start.vertices)} vertices); generation starts from the start "
                  "graph and no rule touches the frame's corners, so such scenes are locally "
                  "similar but cannot be drawn", markup=False)
