"""Reading `gg-example/1` JSON (the corpus's plain format) as an example source.

Only the classes' rigidity is taken from the file: its length limits (0.1-4 "grid units") are
broken by the corpus examples' own edges, so lengths keep the documented defaults, which are
relative to the example and always admit it.
"""

from __future__ import annotations

from pathlib import Path

from .diagnostics import Span, error
from . import limits
from .fileio import read_text
from .json_doc import Reader
from .source import EdgeClass, ExampleSource, ExplicitEdge


def load_example_json(path: str | Path) -> ExampleSource:
    text = read_text(path)
    where = str(path)
    r = Reader(where, "gg-example/1 file", "vertices are [x, y]; edges are [u, v, left, right, "
               "class]; classes map a name to {\"rigid\": true|false}")
    doc = r.parse(text)
    if not isinstance(doc, dict) or doc.get("format") != "gg-example/1":
        raise error("not a gg-example/1 file", Span(where),
                    'the top-level object needs "format": "gg-example/1"')
    pts = [_point(r, p, f"vertices[{k}]") for k, p in enumerate(
        r.array(r.key(doc, "vertices", "the file"), "vertices", limit=limits.POINTS))]
    raw = r.array(r.key(doc, "edges", "the file"), "edges")
    places = _edge_places(text, where, len(raw))
    edges = [_edge(r, e, f"edges[{k}]", pts, span) for k, (e, span) in enumerate(zip(raw, places))]
    classes = {}
    for name, spec in r.obj(doc.get("classes", {}), "classes").items():
        at = f"classes.{name}"
        rigid = r.boolean(r.obj(spec, at).get("rigid", False), f"{at}.rigid")
        classes[r.string(name, at)] = EdgeClass(name, rigid=rigid)
    name = r.string(doc.get("name", Path(path).stem), "name")
    return ExampleSource(path=where, name=name, paint=list(edges), classes=classes, text=text)


def _point(r: Reader, p: object, at: str) -> tuple[float, float]:
    x, y = r.array(p, at, length=2)
    return r.number(x, f"{at}[0]"), r.number(y, f"{at}[1]")


def _edge(r: Reader, e: object, at: str, pts: list, span: Span) -> ExplicitEdge:
    u, v, left, right, cls = r.array(e, at, length=5)
    u, v = (r.integer(x, f"{at}[{k}]", 0, len(pts) - 1) for k, x in ((0, u), (1, v)))
    return ExplicitEdge(pts[u], pts[v], r.string(left, f"{at}[2]"), r.string(right, f"{at}[3]"),
                        _class_name(r, cls, f"{at}[4]"), span)


def _class_name(r: Reader, value: object, at: str) -> str:
    # The corpus writes classes as numbers (0) as often as strings ("0").
    if isinstance(value, int) and not isinstance(value, bool):
        return str(r.integer(value, at))
    return r.string(value, at)


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

