"""`ggrun FILE`: grow drawings from a grammar and write them as SVG or gg-drawing/1 JSON."""

from __future__ import annotations

import argparse
import math
import multiprocessing
import sys
import threading
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Callable

from grammar_lang.blas import pin_blas_threads
from grammar_lang.cli_support import EXIT_FAILED, EXIT_INTERRUPTED
from grammar_lang.diagnostics import Diagnostic, Span, error

from . import interrupt

if TYPE_CHECKING:     # annotations only: `ggrun --version` must not load the model
    from grammar_lang.rules import Grammar

    from .engine.generate import Summary

DEFAULT_STEPS = 200


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("--steps", type=int, metavar="N",
                   help=f"rule applications per drawing (default {DEFAULT_STEPS}, or no bound "
                        "with --iterations)")
    p.add_argument("--iterations", type=int, metavar="N",
                   help="proposals per drawing, applied or not: the paper's N (Algorithm 3); "
                        "the run ends after N, or at --steps applied, whichever comes first")
    p.add_argument("--seed", type=_seed, default=0, metavar="S", help="random seed (default 0)")
    p.add_argument("--out", metavar="PATH",
                   help="output file, .svg, .png, .json or .graphml by extension "
                        "(default: FILE's name + .svg)")
    p.add_argument("--width", type=int, metavar="PX", help="PNG width in pixels")
    p.add_argument("--scale", type=float, metavar="F",
                   help="PNG size as F times the SVG's (800 px along the longer side)")
    p.add_argument("--count", type=int, default=1, metavar="K",
                   help="write K drawings with seeds S…S+K−1, named PATH-0001.svg …")
    p.add_argument("--jobs", type=int, default=1, metavar="N", help="parallel processes")
    p.add_argument("--cost", metavar="NAME[:ARGS]",
                   help="Metropolis cost: scene[:N] (default, N = steps: size plus the "
                        "example's proportions), size[:N], density:D, label:NAME[:F], none")
    p.add_argument("--temperature", type=float, default=1.0, metavar="T",
                   help="Metropolis temperature (default 1; 0 refuses every cost increase)")
    p.add_argument("--limit", action="append", default=[], metavar="PRIORITY=N",
                   help="at most N applied steps at that priority level (repeatable)")
    p.add_argument("--direction", choices=("both", "forward"),
                   help="use rules in both directions (default for compiled grammars) or "
                        "forward only (default for spo rule files)")
    p.add_argument("--extent", metavar="W×H",
                   help="size of the frame a framed example's drawing fills, in drawing units "
                        "(W×H or WxH; default: the example's own frame)")
    p.add_argument("--quiet", action="store_true", help="no progress display or summary")


def size_target(steps: int | None, iterations: int | None) -> int:
    """The default size cost's N: the steps asked for, else the iterations, else the
    default number of steps."""
    return steps if steps is not None else (iterations or DEFAULT_STEPS)


def _seed(text: str) -> int:
    """A seed numpy takes: a whole number from 0 to 2**63 - 1 (argparse reports the error)."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text[:40]}' is not a whole number") from None
    if not 0 <= value < 2 ** 63:
        raise argparse.ArgumentTypeError(f"{text[:40]} is out of range (0 to 2**63 - 1)")
    return value


@dataclass(frozen=True)
class Job:
    grammar: Grammar
    seed: int
    steps: int | None           # None: no bound (the run ends at `iterations`)
    cost: str | None
    temperature: float
    limits: tuple[tuple[int, int], ...]
    bidirectional: bool | None
    out: str
    name: str
    extent: tuple[float, float] | None = None
    png: tuple[int | None, float | None] = (None, None)     # --width, --scale
    iterations: int | None = None

    @property
    def size(self) -> int:
        return size_target(self.steps, self.iterations)


# What turns an example into a grammar: the compiler's `compile_example`, handed in by the
# `ggrun` entry point (report/ggrun.py), which sits above both packages. The runtime never
# imports the compiler, so on its own it runs rule files only.
CompileExample = Callable[[object], object]


def load_grammar(path: str, compile_example: CompileExample | None = None,
                 warn: Callable[[Diagnostic], None] | None = None) -> Grammar:
    """The grammar of a rule file, or of an example compiled here; `warn` is told of the
    example's warnings (a border that cannot be closed into a frame), as `ggc` prints them."""
    p = Path(path)
    suffix = p.suffix.lower()
    if suffix == ".ggr":
        from grammar_lang.ggr_parser import load_ggr
        return load_ggr(p)
    if suffix in (".gg", ".svg"):
        if compile_example is None:
            raise error(f"cannot compile '{p.name}' here: this entry point runs rule files",
                        Span(str(p)), f"compile it first ('ggc compile {p.name}'), or run "
                                      "the 'ggrun' command, which compiles examples")
        from grammar_lang.loader import load_example
        example = load_example(p)
        for note in example.notes if warn is not None else ():
            if note.severity == "warning":
                warn(note)
        result = compile_example(example)
        return getattr(result, "grammar", result)
    raise error(f"don't know how to read '{p.name}'", Span(str(p)),
                "give a grammar (.ggr) or an example (.gg, .svg)")


def parse_limits(items: list[str]) -> tuple[tuple[int, int], ...]:
    """`--limit PRIORITY=N` items (ggrun and the REPL's set-up) as sorted (priority, N) pairs;
    a malformed item is a user error with a hint."""
    out = {}
    for item in items:
        try:
            k, v = item.split("=")
            out[int(k)] = int(v)
        except ValueError:
            raise error(f"--limit {item}: expected PRIORITY=N", None,
                        "write e.g. --limit 0=100 (at most 100 steps at priority 0)") from None
        if out[int(k)] < 0:
            raise error(f"--limit {item}: the limit must not be negative")
    return tuple(sorted(out.items()))


def output_paths(out: str, count: int) -> list[str]:
    p = Path(out)
    if count == 1:
        return [str(p)]
    return [str(p.with_name(f"{p.stem}-{k + 1:04d}{p.suffix}")) for k in range(count)]


def parse_extent(text: str | None, grammar: Grammar) -> tuple[float, float] | None:
    """`W×H` (or `WxH`): positive and finite (the engine checks that it holds every rigid
    part: Engine._check_extent)."""
    if text is None:
        return None
    hint = "give the frame's width and height in drawing units, for example --extent 1540x780"
    if grammar.header.frame is None:
        raise error("--extent sizes a frame, and this grammar has none", None,
                    "draw the example inside a closed loop of a border class (docs/scenes.md)")
    parts = text.replace("×", "x").lower().split("x")
    try:
        w, h = (float(p) for p in parts)
    except ValueError:
        raise error(f"--extent {text}: not W×H", None, hint) from None
    if not (0 < w < 1e9 and 0 < h < 1e9):
        raise error(f"--extent {text}: width and height must be positive and finite", None, hint)
    frame = grammar.header.frame
    fw, fh = frame.size
    if not frame.axis_aligned and abs(w / h - fw / fh) > 1e-9 * (fw / fh):
        raise error(f"--extent {text} would change the angles of this frame's slanted sides",
                    None, f"keep its proportions: --extent {w:g}x{w * fh / fw:g}")
    return w, h


def run_job(job: Job, progress=None) -> Summary | None:
    """Generate one drawing and write it; runs in a worker process for --jobs. After Ctrl-C a
    job still to start, or stopped before its first applied step, does nothing (None): it
    has made nothing to keep (its proposals so far were all refused). A running one writes
    what it has."""
    if interrupt.requested():
        return None
    if job.grammar.is_free:
        return _run_free(job, progress)
    from .engine.costs import parse_cost       # numpy and the engine load only when a run starts,
    from .engine.generate import Engine        # so --help and --version stay quick
    engine = Engine(job.grammar, job.seed,
                    parse_cost(job.cost, job.grammar.header.labels, job.size,
                               job.grammar.header),
                    job.temperature, bidirectional=job.bidirectional, limits=dict(job.limits),
                    extent=job.extent)
    summary = engine.run(job.steps, progress, stop=interrupt.requested,
                         iterations=job.iterations)
    if interrupt.requested() and summary.applied == 0:
        return None         # stopped before its first step: as a job still to start
    drawing = engine.host.to_drawing({"grammar": job.name, "seed": job.seed,
                                      "steps": summary.applied})
    write_drawing(drawing, job.grammar, job.out, job.png)
    return summary


def _run_free(job: Job, progress=None) -> Summary:
    """Hand-written productions: their own engine (runtime.engine.free_engine) and SVG painter."""
    from .engine.free_engine import FreeEngine
    from .output.free_svg import free_drawing, write_free_svg
    engine = FreeEngine(job.grammar, job.seed, dict(job.limits))
    summary = engine.run(job.steps, progress, stop=interrupt.requested)
    if job.out.lower().endswith(".svg"):
        write_free_svg(engine.host, job.grammar.header, job.out)
    elif job.out.lower().endswith(".png"):
        from grammar_lang.png import write_png
        from .output.free_svg import render_free_svg
        write_png(render_free_svg(engine.host, job.grammar.header), job.out, *job.png)
    else:       # .json and .graphml, as for rules
        write_drawing(free_drawing(engine.host, {"grammar": job.name, "seed": job.seed,
                                                 "steps": summary.applied}),
                      job.grammar, job.out)
    return summary


def write_drawing(drawing, grammar: Grammar, path: str,
                  png: tuple[int | None, float | None] = (None, None)) -> None:
    if path.lower().endswith(".json"):
        drawing.save(path)
        return
    if path.lower().endswith(".graphml"):
        from .output.graphml_out import write_graphml
        write_graphml(drawing, path)
        return
    if path.lower().endswith(".png"):
        from grammar_lang.png import write_png
        from .output.svg_out import render_svg
        write_png(render_svg(drawing, grammar.header), path, *png)
        return
    from .output.svg_out import write_svg
    write_svg(drawing, grammar.header, path)


def run_command(args: argparse.Namespace) -> int:
    out = _output_path(args)
    from grammar_lang.reach import connected_warning
    warn = None if args.quiet else lambda d: sys.stderr.write(d.render() + "\n")
    grammar = load_grammar(args.file, getattr(args, "compile_example", None), warn)
    if warn is not None and (gap := connected_warning(grammar)) is not None:
        warn(gap)
    _check_run_options(args, grammar)
    both = None if args.direction is None else args.direction == "both"
    extent = parse_extent(args.extent, grammar)
    jobs = [Job(grammar, args.seed + k, args.steps, args.cost, args.temperature,
                parse_limits(args.limit), both, path, Path(args.file).name, extent,
                (args.width, args.scale), args.iterations)
            for k, path in enumerate(output_paths(out, args.count))]
    parallel = args.jobs > 1 and len(jobs) > 1
    stop = multiprocessing.Event() if parallel else threading.Event()
    with interrupt.catching(stop):
        done = _run_jobs(jobs, args.jobs if parallel else 1, stop, show=not args.quiet)
    if stop.is_set():
        sys.stderr.write(f"interrupted: wrote the last valid drawing of {len(done)} of "
                         f"{len(jobs)} runs" + (f" ({', '.join(j.out for j, _ in done)})"
                                                if done else "") + "\n")
        return EXIT_INTERRUPTED
    return _report_empty(args, done)


def _output_path(args: argparse.Namespace) -> str:
    """The output path (or the first of --count's), after checking the arguments that need no
    grammar: a file is given, the counts are in range, the format and PNG size are known."""
    if args.file is None:
        raise error("no grammar given", None, "run 'ggrun FILE.ggr', or 'ggrun --help'")
    if args.steps is None and getattr(args, "iterations", None) is None:
        args.steps = DEFAULT_STEPS
    for flag, least in (("steps", 0), ("iterations", 0), ("count", 1), ("jobs", 1)):
        value = getattr(args, flag, None)
        if value is not None and value < least:
            raise error(f"--{flag} {value} is out of range", None,
                        f"--{flag} takes a whole number of at least {least}")
    out = args.out or str(Path(Path(args.file).name).with_suffix(".svg"))
    if Path(out).suffix.lower() not in (".svg", ".png", ".json", ".graphml"):
        raise error(f"--out {out}: unknown output format", None,
                    "end the name with .svg, .png, .json or .graphml")
    from grammar_lang.png import check_size
    check_size(args.width, args.scale)
    return out


def _check_run_options(args: argparse.Namespace, grammar: Grammar) -> None:
    """The options that depend on the grammar, checked once, before any work."""
    from .engine.costs import parse_cost
    if grammar.is_free and (args.cost or args.direction or args.extent or args.iterations):
        raise error("--cost, --direction, --extent and --iterations apply to angle-graph "
                    "rules, not to productions",
                    None, "productions run forward, one step at a time, by priority and weight")
    parse_cost(args.cost, grammar.header.labels, size_target(args.steps, args.iterations),
               grammar.header)
    if not (math.isfinite(args.temperature) and args.temperature >= 0):
        raise error(f"--temperature {args.temperature:g} makes no sense", None,
                    "give a finite temperature of at least 0 (0 refuses every cost increase)")
    check_limits(parse_limits(args.limit), grammar)


def check_limits(limits, grammar: Grammar) -> None:
    """A `--limit` on a level no rule has would do nothing (a typo for another level)."""
    levels = {r.priority for r in (*grammar.rules, *grammar.productions)}
    for level, n in limits:
        if level not in levels:
            raise error(f"--limit {level}={n}: no rule of this grammar has priority {level}",
                        None, "its priorities: " + ", ".join(map(str, sorted(levels))))


def _run_jobs(jobs: list[Job], workers: int, stop, show: bool) -> list[tuple[Job, Summary]]:
    """Run the jobs, in `workers` processes when more than one, and report each as it ends;
    the finished ones. After Ctrl-C (`stop`) no new job starts."""
    done: list[tuple[Job, Summary]] = []
    if workers > 1:
        with ProcessPoolExecutor(max_workers=workers, initializer=_init_worker,
                                 initargs=(stop,)) as pool:
            for job, s in zip(jobs, pool.map(run_job, jobs)):
                if s is not None:
                    done.append((job, s))
                    if show:
                        _report(job, s)
        return done
    for job in jobs:
        s = _run_with_progress(job) if show and sys.stderr.isatty() else run_job(job)
        if s is None:
            break
        done.append((job, s))
        if show:
            _report(job, s)
    return done


def _report_empty(args: argparse.Namespace, done: list[tuple[Job, Summary]]) -> int:
    """Say which drawings came out empty, with a hint why: the exit status."""
    empty = [(j, s) for j, s in done if s.vertices == 0 and j.size > 0]
    hint = ("check --cost and --limit: a size:0 cost or a --limit of 0 steps keeps the "
            "drawing empty" if args.cost or args.limit else
            "the grammar draws nothing from an empty drawing; see its starter rules")
    for job, s in empty:
        sys.stderr.write(f"{job.out}: error: the drawing is empty ({s.stop}); wrote it anyway\n"
                         f"  hint: {hint}\n")
    return EXIT_FAILED if empty else 0


def _init_worker(stop) -> None:
    pin_blas_threads()
    interrupt.worker_init(stop)


def _run_with_progress(job: Job) -> Summary:
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
    from grammar_lang.cli_support import stderr_console
    with Progress(TextColumn("[bold]seed {task.fields[seed]}"), BarColumn(),
                  TextColumn("{task.completed}/{task.total} steps"),
                  TextColumn("{task.fields[size]} vertices"), TimeElapsedColumn(),
                  console=stderr_console(), transient=True) as bar:
        by_steps = job.steps is not None
        bar.columns[2].text_format = "{task.completed}/{task.total} " + \
            ("steps" if by_steps else "iterations")
        task = bar.add_task("grow", total=job.size, seed=job.seed, size=0)

        def tick(s: Summary) -> None:
            bar.update(task, completed=s.applied if by_steps else s.proposals, size=s.vertices)

        return run_job(job, tick)


def _report(job: Job, s: Summary) -> None:
    rate = s.applied / s.seconds if s.seconds > 0 else 0.0
    why = ", ".join(f"{k} {v}" for k, v in sorted(s.reasons.items()))
    sys.stderr.write(
        f"{job.out}: seed {job.seed}: {s.applied} steps applied, {s.rejected} rejected"
        f"{' (' + why + ')' if why else ''}; {s.vertices} vertices, {s.edges} edges; "
        f"{s.seconds:.2f} s ({rate:.0f} steps/s)\n")
    if not s.stop.startswith("reached"):
        sys.stderr.write(f"  stopped early: {s.stop}; wrote the last valid drawing\n")
