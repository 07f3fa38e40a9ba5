"""Reading `gg-example/1` JSON (the corpus's plain format) as an example source.

The corpus's edge classes give lengths in grid units of 40 px (the original editor's grid).
"""

from __future__ import annotations

import json
from pathlib import Path

from .diagnostics import Span, error
from .fileio import read_text
from .source import EdgeClass, ExampleSource, ExplicitEdge

GRID = 40.0


def load_example_json(path: str | Path) -> ExampleSource:
    text = read_text(path)
    where = str(path)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise error(f"not valid JSON: {exc.msg}", Span(where, exc.lineno, exc.colno), source=text)
    if not isinstance(doc, dict) or doc.get("format") != "gg-example/1":
        raise error("not a gg-example/1 file", Span(where),
                    'the top-level object needs "format": "gg-example/1"')
    try:
        pts = [(float(x), float(y)) for x, y in doc["vertices"]]
        edges = [ExplicitEdge(pts[int(u)], pts[int(v)], str(l), str(r), str(c), Span(where))
                 for u, v, l, r, c in doc["edges"]]
        classes = {
            str(name): EdgeClass(str(name),
                                 float(spec.get("min_length", 0.1)) * GRID,
                                 float(spec.get("max_length", 4.0)) * GRID,
                                 rigid=bool(spec.get("rigid", False)))
            for name, spec in doc.get("classes", {}).items()
        }
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise error(f"malformed gg-example/1 file: {type(exc).__name__}: {exc}", Span(where),
                    'vertices are [x, y]; edges are [u, v, left, right, class]')
    return ExampleSource(path=where, name=str(doc.get("name", Path(path).stem)),
                         paint=list(edges), classes=classes, text=text)
