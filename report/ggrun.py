"""The `ggrun` command: the runtime's command line, handed the compiler so that it can also
run an example (.gg, .svg) by compiling it in memory. The runtime never imports the compiler;
this module, above both, joins them (see the package docstring)."""

from __future__ import annotations

from typing import Sequence


def compile_example(example):
    from compiler.infer import compile_example as compile_
    return compile_(example)


def main(argv: Sequence[str] | None = None) -> int:
    from runtime.cli import main as run_main
    return run_main(argv, compile_example)


if __name__ == "__main__":
    raise SystemExit(main())
