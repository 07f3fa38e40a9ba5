"""`ggrun`: grow drawings from a grammar, check drawings, or explore a grammar in a REPL."""

from __future__ import annotations

from typing import Sequence

from grammar_lang.blas import pin_blas_threads
from grammar_lang.cli_support import ArgumentParser, common_flags, run


def build_check_parser() -> ArgumentParser:
    p = ArgumentParser(prog="ggrun check",
                       description="check a drawing against its example and explain failures")
    p.add_argument("example", help="the example (.gg, .svg) or its grammar (.ggr)")
    p.add_argument("drawing", help="a gg-drawing/1 JSON file")
    p.add_argument("--tolerance", type=float, metavar="DEG",
                   help="angle tolerance for matching edges to labels (default: the example's)")
    p.add_argument("--all", action="store_true", help="show every failure, not the first 50")
    common_flags(p)
    return p


def build_parser() -> ArgumentParser:
    p = ArgumentParser(prog="ggrun", description=__doc__,
                       epilog="Also: 'ggrun check EXAMPLE DRAWING.json' verifies a drawing.")
    p.add_argument("file", nargs="?", help="a grammar (.ggr), or an example (.gg, .svg)")
    from .run_cmd import add_arguments
    add_arguments(p)
    p.add_argument("--repl", action="store_true",
                   help="explore the grammar interactively (commands from stdin when it is "
                        "not a terminal); generation flags set up its engine")
    common_flags(p)
    return p


def _main(argv: Sequence[str], compile_example=None) -> int:
    if argv and argv[0] == "check":
        args = build_check_parser().parse_args(argv[1:])
        pin_blas_threads()
        from .verifier import check_command
        return check_command(args.example, args.drawing, args.tolerance, 0 if args.all else 50)
    args = build_parser().parse_args(argv)
    args.compile_example = compile_example    # None: rule files only (see report/ggrun.py)
    pin_blas_threads()
    if args.repl:
        from .repl.session import repl_command
        return repl_command(args)
    from .run_cmd import run_command
    return run_command(args)


def main(argv: Sequence[str] | None = None, compile_example=None) -> int:
    """`ggrun`; given the compiler's `compile_example`, it also runs examples (.gg, .svg)."""
    return run(lambda a: _main(a, compile_example), argv)


if __name__ == "__main__":
    raise SystemExit(main())
