"""Time writing and reading `.ggr` files for the grammars compiled from corpus examples.

Usage: python benchmarks/ggr_io.py [--repeat N] [NAME ...]
Prints, per example, the rule count, the file's lines, and the best-of-N times of emit_ggr and
parse_ggr (which includes all validation: names, gluing, face walks, ∂L = ∂R).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
CORPUS = Path(os.environ.get("GG_CORPUS", ROOT.parent / "shared" / "corpus" / "examples"))
sys.path.insert(0, str(ROOT))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from compiler.infer import compile_example  # noqa: E402
from grammar_lang.ggr_emit import emit_ggr  # noqa: E402
from grammar_lang.ggr_parser import parse_ggr  # noqa: E402
from grammar_lang.loader import load_example  # noqa: E402


def best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("names", nargs="*")
    ap.add_argument("--repeat", type=int, default=3)
    args = ap.parse_args()
    names = args.names or sorted(p.stem for p in CORPUS.glob("*.json"))
    print(f"{'example':24} {'rules':>6} {'lines':>7} {'emit s':>8} {'parse s':>8} {'lines/s':>9}")
    for name in names:
        grammar = compile_example(load_example(CORPUS / f"{name}.json")).grammar
        text = emit_ggr(grammar)
        assert parse_ggr(text) == grammar
        lines = text.count("\n")
        t_emit = best(lambda: emit_ggr(grammar), args.repeat)
        t_parse = best(lambda: parse_ggr(text), args.repeat)
        print(f"{name:24} {len(grammar.rules):6d} {lines:7d} {t_emit:8.3f} {t_parse:8.3f} "
              f"{lines / t_parse:9.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
