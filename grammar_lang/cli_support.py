"""What `ggc` and `ggrun` share: error handling, exit codes and the rich console."""

from __future__ import annotations

import argparse
import sys
from typing import Callable, Sequence

from . import __version__
from .diagnostics import UserError

EXIT_OK, EXIT_FAILED, EXIT_USAGE = 0, 1, 2
EXIT_INTERNAL, EXIT_INTERRUPTED = 70, 130


class ArgumentParser(argparse.ArgumentParser):
    """argparse, but usage errors exit 2 with a hint rather than a bare usage dump."""

    def error(self, message: str):  # noqa: D401 - argparse's signature
        self.print_usage(sys.stderr)
        sys.stderr.write(f"{self.prog}: error: {message}\n  hint: run '{self.prog} --help'\n")
        raise SystemExit(EXIT_USAGE)


def common_flags(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    parser.add_argument("--debug", action="store_true",
                        help="show internal details (tracebacks) on errors")


def stderr_console():
    from rich.console import Console     # loaded only by commands that print rich output
    return Console(stderr=True, highlight=False, soft_wrap=True)


def run(main: Callable[[Sequence[str]], int], argv: Sequence[str] | None) -> int:
    """Run a CLI body: user errors print a diagnostic and give exit 2, never a traceback."""
    args = list(sys.argv[1:] if argv is None else argv)
    debug = "--debug" in args
    try:
        return main(args)
    except UserError as exc:
        if debug:
            raise
        sys.stderr.write(exc.render() + "\n")
        return EXIT_USAGE
    except KeyboardInterrupt:
        sys.stderr.write("interrupted\n")
        return EXIT_INTERRUPTED
    except BrokenPipeError:
        return EXIT_OK
    except RecursionError as exc:  # deeply nested input; still the user's input, not our bug
        if debug:
            raise
        sys.stderr.write(f"error: input too deeply nested ({exc})\n")
        return EXIT_USAGE
    except Exception as exc:  # noqa: BLE001 - last line of defence for users
        if debug:
            raise
        sys.stderr.write(f"internal error: {type(exc).__name__}: {exc}\n"
                         "  hint: this is a bug in the tool; rerun with --debug and report it\n")
        return EXIT_INTERNAL
