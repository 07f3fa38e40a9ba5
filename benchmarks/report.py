"""`ggc report` on large grammars: time to draw every rule and build the page, page size,
and (when Chromium is installed) the time a headless browser takes to load it and to lay out
every card.

A grammar of N rules is made by repeating a corpus grammar's rules under new names, so that
the page holds N distinct cards (the figures differ: each is laid out with its own seed).

    .venv/bin/python benchmarks/report.py                  # 50, 150 and 300 rules
    .venv/bin/python benchmarks/report.py --rules 300 --example x-box-square.svg
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))

from grammar_lang.blas import pin_blas_threads  # noqa: E402

pin_blas_threads()

from compiler.infer import compile_example  # noqa: E402
from grammar_lang.ggr_emit import emit_ggr  # noqa: E402
from grammar_lang.ggr_parser import parse_ggr  # noqa: E402
from grammar_lang.loader import load_example  # noqa: E402
from report.build import Subject, Verdict  # noqa: E402
from report.figures import Drafter  # noqa: E402
from report.page import Page  # noqa: E402

CORPUS = ROOT.parent / "shared" / "corpus" / "examples"


def grammar_of(example: str, n: int):
    base = compile_example(load_example(CORPUS / example)).grammar
    rules = tuple(replace(r, name=f"{r.name}_{k // len(base.rules)}")
                  for k, r in zip(range(n), (base.rules * (n // len(base.rules) + 1))))
    text = emit_ggr(replace(base, rules=rules))
    return parse_ggr(text, "big.ggr"), text


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rules", default="50,150,300")
    ap.add_argument("--example", default="x-box-square.svg")
    args = ap.parse_args()
    from browser import Browser, find_chromium
    chromium = find_chromium()
    browser = Browser(chromium) if chromium else None
    print(f"{'rules':>6} {'figures s':>10} {'page MB':>8} {'load s':>7} {'all cards s':>12}")
    try:
        for n in (int(x) for x in args.rules.split(",")):
            grammar, text = grammar_of(args.example, n)
            subject = Subject("big.ggr", grammar, text, "big.ggr", None,
                              Verdict(None, "not known", ()))
            t0 = time.perf_counter()
            html = Page(subject, Drafter(grammar.header), [], times=False).html()
            build = time.perf_counter() - t0
            load = cards = float("nan")
            if browser is not None:
                with tempfile.TemporaryDirectory() as tmp:
                    page = Path(tmp) / "big.html"
                    page.write_text(html)
                    t1 = time.perf_counter()
                    browser.load(page.as_uri())
                    load = time.perf_counter() - t1
                    t2 = time.perf_counter()
                    browser.evaluate("(() => { for (const c of document.querySelectorAll("
                                     "'.card')) { c.scrollIntoView(); "
                                     "c.getBoundingClientRect(); } return 0; })()")
                    cards = time.perf_counter() - t2
            print(f"{n:>6} {build:>10.2f} {len(html) / 1e6:>8.2f} {load:>7.2f} {cards:>12.2f}")
    finally:
        if browser is not None:
            browser.close()
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
