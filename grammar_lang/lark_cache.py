"""The project's lark parsers, their LALR tables kept between processes.

Building a parser's tables takes 15–55 ms (the `.gg` grammar 35 ms, the `.ggr` one 53 ms), which
every run of ggc and ggrun paid before reading a line of its input: most of a small example's
compile time. The tables depend only on the grammar's text, its options and lark's version, so
the first process writes them to the user's cache and later ones load them in a few ms. They
are stored as JSON, so reading them back runs no code; tuples and dicts with other keys than
strings are tagged (`{"__t": [...]}`, `{"__d": [[key, value], ...]}`) to come back as they were.

A cache that cannot be read, written or trusted (another grammar, options or lark, or a torn
file) costs only the build. `GG_CACHE_DIR` moves the cache; `GG_CACHE_DIR=off` turns it off.
"""

from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path

import lark
from lark import Lark

from .diagnostics import UserError
from .fileio import atomic_write

ENV = "GG_CACHE_DIR"


def lalr_parser(grammar: Path, runtime: dict | None = None, **options) -> Lark:
    """A contextual-lexer LALR parser for the grammar file `grammar`, with lark `options`;
    `runtime` options (a postlexer object) are given to it but are no part of its tables."""
    text = grammar.read_text(encoding="utf-8")
    options = {"parser": "lalr", "lexer": "contextual", **options}
    runtime = runtime or {}
    key = hashlib.sha256(json.dumps([lark.__version__, text, sorted(options.items())],
                                    default=repr).encode()).hexdigest()
    path = _cache_dir()
    path = path and path / f"{grammar.stem}-{key[:20]}.json"
    if path is not None:
        loaded = _load(path, key, runtime)
        if loaded is not None:
            return loaded
    parser = Lark(text, **options, **runtime)
    if path is not None:
        _store(parser, path, key, set(runtime))
    return parser


def _cache_dir() -> Path | None:
    where = os.environ.get(ENV)
    if where == "off":
        return None
    if where:
        return Path(where)
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "graph-grammar-toolchain"


def _load(path: Path, key: str, runtime: dict) -> Lark | None:
    try:
        doc = json.loads(path.read_text(encoding="utf-8"), object_hook=_untag)
        if doc.get("key") != key:
            return None
        return Lark.__new__(Lark)._load(doc["tables"], **runtime)
    except Exception:       # noqa: BLE001 - any failure to read a cache only means: build
        return None


def _store(parser: Lark, path: Path, key: str, runtime: set[str]) -> None:
    from lark.grammar import Rule
    from lark.lexer import TerminalDef
    try:
        data, memo = parser.memo_serialize([TerminalDef, Rule])
        data["options"] = {k: v for k, v in data["options"].items() if k not in runtime}
        atomic_write(path, json.dumps({"key": key, "tables": _tag({"data": data, "memo": memo})}))
    except (TypeError, UserError):     # a table JSON cannot hold, or a cache not writable
        pass


def _tag(x):
    if isinstance(x, dict):
        if all(isinstance(k, str) and not k.startswith("__") for k in x):
            return {k: _tag(v) for k, v in x.items()}
        return {"__d": [[_tag(k), _tag(v)] for k, v in x.items()]}
    if isinstance(x, tuple):
        return {"__t": [_tag(v) for v in x]}
    if isinstance(x, list):
        return [_tag(v) for v in x]
    if x is None or isinstance(x, (str, int, float, bool)):
        return x
    raise TypeError(f"no JSON form for {type(x).__name__}")


def _untag(d: dict):
    if len(d) == 1:
        if "__t" in d:
            return tuple(d["__t"])
        if "__d" in d:
            return {k: v for k, v in d["__d"]}
    return d
