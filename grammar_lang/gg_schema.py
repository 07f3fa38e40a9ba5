"""What `.gg` blocks may say: property names, value types and ranges, and colour syntax.

One table per block kind (`options`, `limits`, `class`, `decorate face|edge|vertex`), so the
language doc, validation and "did you mean" hints all come from the same place.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from . import gg_ast as A
from .diagnostics import did_you_mean, error
from .source import EdgeClass, Limits, Options
from .svg_colors import NAMED, normalize_color

_O, _L = Options(), Limits()   # the defaults the docs of each setting quote

IMAGE_SUFFIXES = (".svg", ".png", ".jpg", ".jpeg", ".gif", ".webp")
_BOOLS = {"yes": True, "true": True, "on": True, "no": False, "false": False, "off": False}
_UNITS = {  # value kind → {suffix: factor}
    "length": {"": 1.0, "px": 1.0},
    "angle": {"": 1.0, "deg": 1.0},
    "seconds": {"": 1.0, "s": 1.0, "ms": 0.001, "min": 60.0},
    "number": {"": 1.0},
    "int": {"": 1.0},
    "fraction": {"": 1.0, "%": 0.01},
}


def is_hex_colour(text: str) -> bool:
    return text.startswith("#") and normalize_color(text) is not None


def colour(word: A.Word, palette: dict[str, str], source: str | None) -> str:
    """A colour value as lowercase #rrggbb (the form SVG labels take): #hex, a palette name
    (`colour` statements), a CSS colour name, or "rgb(…)" in quotes."""
    if word.kind in ("colour", "string") and word.text.startswith("#"):
        hexed = normalize_color(word.text)
        if hexed is None:
            raise error(f"'{word.text}' is not a colour", word.span,
                        "write a colour as # and 3, 4, 6 or 8 hex digits, e.g. #c0f0ff",
                        source=source)
        return hexed
    if word.kind in ("name", "string"):
        name = word.text
        if name in palette:
            return palette[name]
        hexed = normalize_color(name)
        if hexed is not None:
            return hexed
        raise error(f"unknown colour '{name}'", word.span,
                    did_you_mean(name, [*palette, *NAMED])
                    or "write #rrggbb, a CSS colour name, or define it with `colour NAME #rrggbb`",
                    source=source)
    raise error(f"expected a colour, got {word.text}", word.span,
                "write a colour like #c0f0ff or a name like steelblue", source=source)


@dataclass(frozen=True)
class Field:
    kind: str                   # length angle seconds number int fraction bool colour file enum
    lo: float | None = None
    hi: float | None = None
    lo_open: bool = False
    hi_open: bool = False
    choices: tuple[str, ...] = ()
    doc: str = ""


def _positive(kind: str, doc: str) -> Field:
    return Field(kind, 0, None, lo_open=True, doc=doc)


OPTIONS = {
    "angle-tolerance": Field("angle", 0, 45, hi_open=True,
                             doc="directions closer than this are one edge label "
                                 f"(default {_O.angle_tolerance:g}°)"),
    "snap-angle": Field("angle", 0, 90, doc="snap label directions to multiples of this "
                                            f"(default {_O.snap_angle:g}°, 0 = off)"),
    "merge-distance": Field("length", 0, doc="points closer than this are one vertex "
                                             "(default 0.5 % of the drawing's diagonal)"),
    "unit": _positive("length", "the length that class defaults are relative to "
                                "(default the median edge length)"),
    "connected": Field("bool", doc="generate one connected shape (paper Appendix A)"),
    "no-loops": Field("bool", doc="generate trees and streams without loops (Appendix A)"),
}
LIMITS = {
    "generations": Field("int", 1, 1000, doc="gluing generations of the hierarchy "
                                          f"(default {_L.generations})"),
    "half-edges": Field("int", 1, 1000, doc="most open half-edges of a graph "
                                         f"(default {_L.half_edges})"),
    "graphs": Field("int", 1, 10**9, doc="most graphs in the hierarchy "
                                          f"(default {_L.graphs})"),
    "time": _positive("seconds", "time budget of the inference (default: none; a time "
                                 "limit makes the rules depend on the machine's speed)"),
}
CLASS = {
    "min": Field("length", 0, doc=f"shortest length (default {EdgeClass.DEFAULT_MIN:g} × unit)"),
    "max": _positive("length", f"longest length (default {EdgeClass.DEFAULT_MAX:g} × unit)"),
    "fixed": _positive("length", "every edge has exactly this length"),
    "tile": _positive("length", "lengths are whole multiples of this"),
    "rigid": Field("bool", doc="the edge keeps the exact vector it has in the example"),
    "border": Field("bool", doc="the edge is part of the drawing's border (Appendix A)"),
}
MARKERS = ("circle", "square", "diamond", "triangle", "cross", "none")
DECORATIONS = {
    "face": {
        "fill": Field("colour", doc="fill colour"),
        "pattern": Field("file", doc="image tiled over the face"),
        "pattern-scale": _positive("number", "scale of the pattern image"),
        "opacity": Field("fraction", 0, 1, doc="0 transparent … 1 opaque"),
    },
    "edge": {
        "stroke": Field("colour", doc="line colour"),
        "width": Field("length", 0, doc="line width"),
        "image": Field("file", doc="image or SVG snippet tiled along the edge"),
        "spacing": _positive("length", "distance between tiled images"),
        "bend": Field("angle", 0, 90, hi_open=True,
                      doc="largest random bend per segment (Appendix B; 0 = straight)"),
        "bend-step": _positive("length", "segment length used for bending"),
        "opacity": Field("fraction", 0, 1, doc="0 transparent … 1 opaque"),
    },
    "vertex": {
        "marker": Field("enum", choices=MARKERS, doc="marker shape"),
        "size": _positive("length", "marker size"),
        "fill": Field("colour", doc="marker fill colour"),
        "stroke": Field("colour", doc="marker outline colour"),
        "image": Field("file", doc="image placed at the vertex"),
        "scale": _positive("number", "scale of the image"),
        "rotate": Field("bool", doc="turn the image with the vertex's first half-edge"),
    },
}
# Where a misplaced key belongs, for a better hint than "unknown".
_HOME = {k: "options { }" for k in OPTIONS} | {k: "limits { }" for k in LIMITS} \
    | {k: "class NAME { }" for k in CLASS}


def _range_text(f: Field) -> str:
    lo = "" if f.lo is None else f"{f.lo:g} {'<' if f.lo_open else '≤'} "
    hi = "" if f.hi is None else f" {'<' if f.hi_open else '≤'} {f.hi:g}"
    return f"{lo}value{hi}"


def check_value(prop: A.Prop, field: Field, palette: dict[str, str], base: Path,
                source: str | None):
    """The typed value of one property, or a diagnostic pointing at it."""
    v = prop.value
    where = v.span if v is not None else prop.span
    if field.kind == "bool":
        return _bool_value(prop, v, where, source)
    if v is None:
        raise error(f"'{prop.key}' needs a value", prop.span,
                    f"write '{prop.key}: …' ({field.doc})" if field.doc else None, source=source)
    if field.kind == "colour":
        if isinstance(v, A.Num):
            raise error(f"expected a colour, got {v.text}", where,
                        "write a colour like #c0f0ff or a name like steelblue", source=source)
        return colour(v, palette, source)
    if field.kind == "file":
        return _file_value(prop, v, where, base, source)
    if field.kind == "enum":
        if isinstance(v, A.Word) and v.kind in ("name", "string") and v.text in field.choices:
            return v.text
        raise error(f"'{getattr(v, 'text', v)}' is not a {prop.key}", where,
                    did_you_mean(str(getattr(v, "text", "")), field.choices)
                    or "choose one of " + ", ".join(field.choices), source=source)
    return _number_value(prop, field, v, where, source)


def _bool_value(prop: A.Prop, v, where, source: str | None) -> bool:
    if v is None:
        return True
    if isinstance(v, A.Word) and v.kind == "name" and v.text.lower() in _BOOLS:
        return _BOOLS[v.text.lower()]
    raise error(f"'{prop.key}' is a yes/no setting", where,
                f"write just '{prop.key}', or '{prop.key}: yes' / '{prop.key}: no'",
                source=source)


def _file_value(prop: A.Prop, v, where, base: Path, source: str | None) -> str:
    """An image file's resolved path, relative to the .gg file's folder."""
    if not (isinstance(v, A.Word) and v.kind == "string"):
        raise error(f"'{prop.key}' needs a file name in quotes", where,
                    f'write {prop.key}: "picture.svg"', source=source)
    p = (base / v.text)
    if p.suffix.lower() not in IMAGE_SUFFIXES:
        raise error(f"'{v.text}' is not an image", where,
                    "use an " + ", ".join(IMAGE_SUFFIXES) + " file", source=source)
    if not p.is_file():
        raise error(f"image file not found: {v.text}", where,
                    f"paths are relative to the .gg file's folder ({base})", source=source)
    return str(p.resolve())


def _number_value(prop: A.Prop, field: Field, v, where, source: str | None):
    """A number of one of the numeric kinds, in its base unit, within the field's range."""
    if not isinstance(v, A.Num):
        raise error(f"'{prop.key}' needs a number, got {v.text}", where,
                    f"{prop.key} is the {field.doc}", source=source)
    units = _UNITS[field.kind]
    if v.unit not in units:
        allowed = [u for u in units if u]
        raise error(f"'{prop.key}' does not take the unit '{v.unit}'", where,
                    ("write a plain number" + (" or use " + ", ".join(allowed) if allowed else ""))
                    , source=source)
    value = v.value * units[v.unit]
    if not math.isfinite(value):
        raise error(f"{prop.key} {v.text} is out of range", where,
                    f"{prop.key} needs a finite number", source=source)
    if field.kind == "int":
        if value != int(value):
            raise error(f"'{prop.key}' needs a whole number, got {v.text}", where,
                        f"write e.g. {prop.key}: {max(1, round(value))}", source=source)
        value = int(value)
    bad_lo = field.lo is not None and (value <= field.lo if field.lo_open else value < field.lo)
    bad_hi = field.hi is not None and (value >= field.hi if field.hi_open else value > field.hi)
    if bad_lo or bad_hi:
        raise error(f"{prop.key} {v.text} is out of range", where,
                    f"{prop.key} needs {_range_text(field)}" + (f": {field.doc}" if field.doc else ""),
                    source=source)
    return value


def check_block(props: tuple[A.Prop, ...], schema: dict[str, Field], what: str,
                palette: dict[str, str], base: Path, source: str | None) -> dict[str, object]:
    """Validate a `{ … }` block against `schema`: known keys, no repeats, typed values."""
    out: dict[str, object] = {}
    for prop in props:
        if prop.key not in schema:
            home = _HOME.get(prop.key)
            hint = did_you_mean(prop.key, schema) or (
                f"'{prop.key}' belongs in {home}" if home else
                f"{what} knows: " + ", ".join(schema))
            raise error(f"unknown {what} property '{prop.key}'", prop.span, hint, source=source)
        if prop.key in out:
            raise error(f"'{prop.key}' is given twice", prop.span,
                        "remove one of them", source=source)
        out[prop.key] = check_value(prop, schema[prop.key], palette, base, source)
    return out


def check_decoration(kind: str, pairs, base: Path, source: str | None) -> dict[str, object]:
    """A decoration whose values arrive already read (a `.ggr` file's `key=value` pairs,
    each with the spans of its key and value), checked by the same table as a `.gg` decoration: `.ggr` values are
    edited by hand, and what they hold goes into SVG."""
    props = tuple(A.Prop(key, _as_value(value, at), span) for key, value, span, at in pairs)
    return check_block(props, DECORATIONS[kind], f"{kind} decoration", {}, base, source)


def _as_value(value: object, span) -> A.Value:
    if isinstance(value, bool):
        return A.Word("yes" if value else "no", "name", span)
    if isinstance(value, (int, float)):
        return A.Num(float(value), "", str(value), span)
    return A.Word(str(value), "string", span)
