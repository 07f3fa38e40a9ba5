"""Reading `gg-example/1` JSON (the corpus's plain format) as an example source.

Only the classes' rigidity is taken from the file: its length limits (0.1-4 "grid units") are
broken by the corpus examples' own edges, so lengths keep the documented defaults, which are
relative to the example and always admit it.
"""

from __future__ import annotations

import json
from pathlib import Path

from .diagnostics import Span, error
from .fileio import read_text
from .source import EdgeClass, ExampleSource, ExplicitEdge


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
        places = _edge_places(text, where, len(doc["edges"]))
        edges = [ExplicitEdge(pts[int(u)], pts[int(v)], str(l), str(r), str(c), span)
                 for (u, v, l, r, c), span in zip(doc["edges"], places)]
        classes = {str(name): EdgeClass(str(name), rigid=bool(spec.get("rigid", False)))
                   for name, spec in doc.get("classes", {}).items()}
    except (KeyError, TypeError, ValueError, IndexError) as exc:
        raise error(f"malformed gg-example/1 file: {type(exc).__name__}: {exc}", Span(where),
                    'vertices are [x, y]; edges are [u, v, left, right, class]')
    return ExampleSource(path=where, name=str(doc.get("name", Path(path).stem)),
                         paint=list(edges), classes=classes, text=text)


def _edge_places(text: str, where: str, count: int) -> list[Span]:
    """Where each entry of the "edges" array starts, so diagnostics (and the drawing order that
    direction typing follows) refer to the file. Falls back to the file alone."""
    start = text.find('"edges"')
    spans: list[Span] = []
    if start >= 0:
        i = text.find("[", start) + 1
        depth, in_str, esc = 0, False, False
        while 0 < i < len(text) and len(spans) < count:
            ch = text[i]
            if in_str:
                esc, in_str = (False, in_str) if esc else (ch == "\\", ch != '"')
            elif ch == '"':
                in_str = True
            elif ch == "[":
                if depth == 0:
                    line = text.count("\n", 0, i) + 1
                    spans.append(Span(where, line, i - (text.rfind("\n", 0, i) + 1) + 1))
                depth += 1
            elif ch == "]":
                if depth == 0:
                    break
                depth -= 1
            i += 1
    return spans if len(spans) == count else [Span(where)] * count

