"""`ggc`: check an example, show its primitives, compile it into a grammar, verify a grammar."""

from __future__ import annotations

from typing import Callable, Sequence

from grammar_lang.blas import pin_blas_threads
from grammar_lang.cli_support import ArgumentParser, common_flags, run


def build_parser(more: Callable | None = None) -> ArgumentParser:
    """The `ggc` parser; `more(subparsers)` adds commands that live above the compiler (the
    report, see report.ggc), so that this module imports nothing from the runtime."""
    parser = ArgumentParser(prog="ggc", description=__doc__)
    common_flags(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=ArgumentParser)
    sub.required = True

    p = sub.add_parser("check", help="validate an example (.gg or .svg) and print a summary")
    p.add_argument("file")
    common_flags(p)

    p = sub.add_parser("primitives", help="print face labels, edge labels and primitives")
    p.add_argument("file")
    p.add_argument("--json", action="store_true", help="machine-readable output")
    p.add_argument("--ascii", action="store_true", help="ASCII boundary strings")
    common_flags(p)

    p = sub.add_parser("compile", help="infer a grammar from an example and write a .ggr file")
    p.add_argument("file", help="the example (.gg or .svg)")
    p.add_argument("-o", "--output", metavar="OUT.ggr",
                   help="where to write the rules (default: beside the example)")
    p.add_argument("--force", action="store_true",
                   help="overwrite a .ggr file even if it was edited by hand, and a --report "
                        "file that ggc did not write")
    p.add_argument("--report", metavar="FILE.json", help="also write the summary as JSON")
    common_flags(p)

    p = sub.add_parser("verify", help="check that a grammar reduces every complete graph to ∅")
    p.add_argument("file", help="the rule file (.ggr)")
    p.add_argument("--max-primitives", type=int, default=8, metavar="N",
                   help="check every complete graph of at most N primitives (default 8)")
    p.add_argument("--seconds", type=float, default=None, metavar="S",
                   help="stop after S seconds and report a partial check (default: no limit)")
    common_flags(p)
    if more is not None:
        more(sub)
    return parser


def _main(argv: Sequence[str]) -> int:
    return dispatch(build_parser().parse_args(argv))


def dispatch(args) -> int:
    pin_blas_threads()
    if args.command in ("check", "primitives"):
        from . import inspect_cmd
        return inspect_cmd.run(args)
    if args.command == "compile":
        from . import compile_cmd
        return compile_cmd.run_compile(args)
    if args.command == "verify":
        from . import compile_cmd
        return compile_cmd.run_verify(args)
    raise AssertionError(args.command)


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    raise SystemExit(main())
