"""The `ggc` command: the compiler's commands plus `report` and `draw`, which also need the
runtime (see the package docstring). This is the composition point: it alone imports both."""

from __future__ import annotations

import re
import sys
import time
from pathlib import Path
from typing import Sequence

from compiler import cli
from grammar_lang.cli_support import common_flags, run
from grammar_lang.diagnostics import Span, UserError, error
from grammar_lang.fileio import atomic_write


def add_commands(sub) -> None:
    p = sub.add_parser("report", help="write one self-contained HTML page that shows the "
                                      "example, its primitives, every rule and a gallery")
    p.add_argument("file", help="an example (.gg, .svg) or a rule file (.ggr)")
    p.add_argument("-o", "--output", metavar="OUT.html",
                   help="where to write the page (default: FILE's name + .html, here)")
    p.add_argument("--gallery", type=int, default=6, metavar="K",
                   help="generated drawings in the gallery (default 6; 0 for none)")
    p.add_argument("--seed", type=int, default=0, metavar="S",
                   help="gallery seeds S…S+K−1 (default 0); also seeds the rule layouts")
    p.add_argument("--steps", type=int, default=200, metavar="N",
                   help="rule applications per gallery drawing (default 200)")
    p.add_argument("--png", metavar="DIR",
                   help="also write every figure as PNG into DIR (example, rules, gallery)")
    p.add_argument("--width", type=int, metavar="PX", help="PNG width in pixels")
    p.add_argument("--scale", type=float, metavar="F", help="PNG size as F times the SVG's")
    p.add_argument("--no-times", action="store_true",
                   help="leave timings out, so the same input gives a byte-identical page")
    common_flags(p)

    p = sub.add_parser("draw", help="draw an example (.gg or .svg) as the tool reads it")
    p.add_argument("file", help="the example (.gg or .svg)")
    p.add_argument("-o", "--output", metavar="OUT.svg",
                   help="the drawing, .svg or .png (default: FILE's name + -read.svg, here)")
    p.add_argument("--width", type=int, metavar="PX", help="PNG width in pixels")
    p.add_argument("--scale", type=float, metavar="F", help="PNG size as F times the SVG's")
    common_flags(p)


def _write_figure(svg: str, path: Path, width, scale) -> None:
    if path.suffix.lower() == ".png":
        from grammar_lang.png import write_png
        write_png(svg, path, width, scale)
    else:
        atomic_write(path, svg)


def run_draw(args) -> int:
    from grammar_lang.loader import load_example
    from grammar_lang.png import check_size

    from .figures import example_svg

    out = Path(args.output or Path(args.file).stem + "-read.svg")
    if out.suffix.lower() not in (".svg", ".png"):
        raise error(f"-o {out}: unknown output format", Span(str(out)),
                    "end the name with .svg or .png")
    check_size(args.width, args.scale)
    example = load_example(args.file)
    if example.graph is None:
        raise error(f"{args.file} gives its primitives directly, so there is no drawing",
                    Span(args.file), "draw a .gg file with polygons or lines, or an .svg")
    _write_figure(example_svg(example), out, args.width, args.scale)
    sys.stderr.write(f"{out}: {len(example.graph.vertices)} vertices, "
                     f"{len(example.graph.edges)} edges, {len(example.primitives)} primitives\n")
    return 0


def run_report(args) -> int:
    from grammar_lang.png import check_size

    from .build import MAX_GALLERY, gallery, load_subject
    from .figures import Drafter
    from .page import Page

    if not 0 <= args.gallery <= MAX_GALLERY:
        raise error(f"--gallery {args.gallery} is out of range", None,
                    f"give 0 to {MAX_GALLERY} drawings")
    if (args.width is not None or args.scale is not None) and not args.png:
        raise error("--width and --scale size the PNG files; they need --png DIR", None,
                    "add --png DIR, or leave the size out")
    if args.png:
        check_size(args.width, args.scale)
    out = Path(args.output or Path(args.file).stem + ".html")
    subject = load_subject(args.file)
    t0 = time.perf_counter()
    drafter = Drafter(subject.grammar.header, args.seed)
    t1 = time.perf_counter()
    shots, trouble = [], ""
    try:
        shots = gallery(subject.grammar, [args.seed + k for k in range(args.gallery)],
                        args.steps)
    except UserError as exc:      # the grammar cannot be run (say, its frame): say so
        trouble = exc.diagnostics[0].message
        sys.stderr.write(f"note: no gallery: {trouble}\n")
    subject.times["gallery"] = time.perf_counter() - t1
    page = Page(subject, drafter, shots, not args.no_times, trouble)
    t2 = time.perf_counter()
    text = page.html()
    subject.times["figures"] = time.perf_counter() - t2 + (t1 - t0)
    atomic_write(out, page.with_times(text))
    if args.png:
        _write_pngs(Path(args.png), subject, drafter, shots, args.width, args.scale)
    for key in drafter.failed:
        sys.stderr.write(f"note: no placement found for {key}; it is shown as text\n")
    if drafter.crossed:
        sys.stderr.write(f"note: {len(drafter.crossed)} rule sides have no placement that "
                         "meets every test; they are drawn keeping only the edge directions "
                         "(their cards say so)\n")
    sys.stderr.write(f"{out}: {len(subject.grammar.rules)} rules, {len(shots)} gallery "
                     f"drawings; {subject.verdict.text}\n")
    return 0


def _slug(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_-]+", "_", name)[:60] or "_"


def _write_pngs(folder: Path, subject, drafter, shots, width, scale) -> None:
    from grammar_lang.png import write_png

    from .figures import example_svg
    if subject.example is not None and subject.example.graph is not None:
        write_png(example_svg(subject.example), folder / "example.png", width, scale)
    for k, rule in enumerate(subject.grammar.rules):
        write_png(drafter.rule_svg(rule), folder / f"rule-{k:03d}-{_slug(rule.name)}.png",
                  width, scale)
    for sh in shots:
        write_png(sh.svg, folder / f"gallery-seed{sh.seed}.png", width, scale)


def _main(argv: Sequence[str]) -> int:
    args = cli.build_parser(add_commands).parse_args(argv)
    if args.command in ("report", "draw"):
        from grammar_lang.blas import pin_blas_threads
        pin_blas_threads()
    if args.command == "report":
        return run_report(args)
    if args.command == "draw":
        return run_draw(args)
    return cli.dispatch(args)


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    raise SystemExit(main())
