"""Write a `Grammar` as `.ggr` text (docs/ggr-language.md), so that `parse_ggr` gives it back.

The output is deterministic: it follows the order of the grammar's tuples and contains no
time stamps. Numbers are written exactly (the shortest text that reads back as the same
float), names that are not plain identifiers are quoted, and comments show what a reader would
otherwise work out by hand: boundary strings in Unicode and the directions of primitives.
"""

from __future__ import annotations

import math
import re
import unicodedata

from . import boundary as bd
from .ggr_file import stamp
from .expr_ast import show
from .ggr_parser import FORMAT_VERSION, unicode
from .graph import Side
from .rules import Grammar, Header, Rule
from .source import DEFAULT_CLASS, Options

WIDTH = 96   # wrap vertex and edge lists at this many columns

# Words that compete with names inside a side (`boundary` starts a line, `wire` follows a
# colon); a name spelled like one is quoted so that it is never misread. Elsewhere keywords
# and names never compete, because the lexer only looks for what may come next.
KEYWORDS = frozenset({"boundary", "wire"})
_PLAIN = re.compile(r"[^\W\d]\w*")
_KEY = re.compile(r"[^\W\d][\w-]*")    # a setting key (NAME in the grammar)


def emit_ggr(grammar: Grammar) -> str:
    h = grammar.header
    names = [l.name for l in h.labels]
    out: list[str] = []
    out.append("# Graph grammar rules written by ggc. Format: docs/ggr-language.md")
    out.append("# Edit freely: once edited, `ggc compile` will not overwrite this file without --force.")
    out.append(f"ggr {FORMAT_VERSION}")
    out.append("")
    out.extend(_header(h, names))
    if h.frame is not None and h.frame.start is not None:
        out.append("")
        out.append("# What generation starts from: the frame's sides change label, so it cannot be bare.")
        out.extend(line[2:] for line in _side("frame-start", h.frame.start, h, names))
    for rule in grammar.rules:
        out.append("")
        out.extend(_rule(rule, h, names))
    out.extend(_free(grammar))
    return stamp("\n".join(out) + "\n")


# --- hand-written productions (free_rules) ----------------------------------------------------

def _free(grammar: Grammar) -> list[str]:
    h, out = grammar.header, []
    if h.vertex_labels:
        out.append("vertices " + " ".join(name(x) for x in h.vertex_labels))
    if h.edge_labels:
        out.append("edges " + " ".join(name(x) for x in h.edge_labels))
    out += [f"attribute {a.kind} {name(a.name)} = {show(a.default)}" for a in h.attributes]
    if grammar.start is not None:
        d = grammar.start.daughters[0]
        out += ["", "start {"] + _free_items(d.side, None) + _sets(d) + ["}"]
    for p in grammar.productions:
        flags = "".join([f" priority={p.priority}", f" weight={num(p.weight)}",
                         f" match={p.match}", " spatial" if p.spatial else ""])
        out += ["", f"production {name(p.name)}{flags} {{", "  lhs {"]
        out += _free_items(p.lhs, None, "    ") + ["  }"]
        out += [f"  where {show(c.expr)}" for c in p.conditions]
        out += [f"  let {l.name} = {show(l.expr)}" for l in p.lets]
        for d in p.daughters:
            out += [f"  rhs weight={num(d.weight)} {{"] + _free_items(d.side, p.lhs, "    ")
            out += ["  }"] + [f"  let {l.name} = {show(l.expr)}" for l in d.lets]
            out += _sets(d)
        out.append("}")
    return out


def _free_items(side, lhs, indent: str = "  ") -> list[str]:
    items = []
    for v in side.vertices:
        at = f" ({num(v.pattern[0])}, {num(v.pattern[1])})" if v.pattern is not None else ""
        if lhs is not None and v.kept:
            if lhs.vertex(v.name).label == v.label:     # kept (a wildcard too), same label
                items.append(f"{v.name}{at}")
                continue
        items.append(f"{name(v.name)}: {'*' if v.label is None else name(v.label)}{at}")
    for e in side.edges:
        label = "*" if e.label is None else name(e.label)
        items.append(f"{e.name + ' = ' if e.name else ''}{e.u} {'->' if e.directed else '--'} "
                     f"{e.v} {label}")
    for f in side.faces:
        label = "*" if f.label is None else name(f.label)
        items.append(f"{f.name + ' = ' if f.name else ''}face {label} ({' '.join(f.cycle)})")
    return _wrap(items, indent) if items else []


def _sets(d) -> list[str]:
    return [f"  set {a.element}.{a.key} = {show(a.expr)}" for a in d.sets]


def _header(h: Header, names: list[str]) -> list[str]:
    out = []
    if h.source or h.source_hash:
        out.append(f"source {quote(h.source)}" + (f" hash {quote(h.source_hash)}"
                                                  if h.source_hash else ""))
    if h.compiler_version:
        out.append(f"compiler {quote(h.compiler_version)}")
    out.append(f"mode {h.mode}")
    status = {True: "complete", False: "limited", None: "unknown"}[h.complete]
    out.append(f"status {status}")
    out.append("options " + _options(h.options))
    lim = h.options.limits
    seconds = "" if lim.seconds is None else f" seconds={num(lim.seconds)}"
    out.append(f"limits generations={lim.generations} half_edges={lim.half_edges} "
               f"graphs={lim.graphs}{seconds}")
    out.append(f"unit {num(h.unit)}")
    if h.frame is not None:
        out.append("frame " + "  ".join(f"{name(h.primitives[c.prim].name)} {num(c.x)} {num(c.y)}"
                                        for c in h.frame.corners))
    out.append("")
    out.append(f"exterior {name(h.exterior)}")
    if h.face_labels:
        out.append("faces " + " ".join(name(f) for f in h.face_labels))
    if h.classes:
        out.append("")
    for c in h.classes:
        parts = [f"class {name(c.name)}"]
        for key, value in (("min", c.min_length), ("max", c.max_length), ("fixed", c.fixed),
                           ("tile", c.tile)):
            # An unbounded max (a border class's default) is written as none given.
            if value is not None and math.isfinite(value):
                parts.append(f"{key}={num(value)}")
        parts += [flag for flag, on in (("rigid", c.rigid), ("border", c.border)) if on]
        out.append(" ".join(parts))
    if h.labels:
        out.append("")
    for l in h.labels:
        line = f"label {name(l.name)} angle={num(l.angle)} left={name(l.left)} right={name(l.right)}"
        if l.cls != DEFAULT_CLASS:
            line += f" class={name(l.cls)}"
        if l.length is not None:
            line += f" length={num(l.length)}"
        if l.typical is not None:
            line += f" typical={num(l.typical)}"
        if l.shortest is not None:
            line += f" shortest={num(l.shortest)}"
        out.append(line)
    if h.primitives:
        out.append("")
    for p in h.primitives:
        line = f"primitive {name(p.name)} = {ring(p.ring, names)}"
        if p.count != 1:
            line += f" count={p.count}"
        dirs = " ".join(f"{num(h.labels[bd.label_of(t)].direction(bd.is_bar(t)))}°" for t in p.ring)
        out.append(f"{line}  # {_safe(unicode(p.boundary, names))}  ({dirs})")
    if h.decorations:
        out.append("")
    for d in h.decorations:
        target = "*" if d.target == "*" else name(d.target)
        props = "".join(f" {k if _KEY.fullmatch(k) else quote(k)}={_value(v)}" for k, v in d.props)
        out.append(f"decorate {d.kind} {target}{props}")
    return out


def _options(o: Options) -> str:
    def auto(v):
        return "auto" if v is None else num(v)

    return (f"angle_tolerance={num(o.angle_tolerance)} snap_angle={num(o.snap_angle)} "
            f"merge_distance={auto(o.merge_distance)} unit={auto(o.unit)} "
            f"connected={str(o.connected).lower()} no_loops={str(o.no_loops).lower()}")


def _rule(rule: Rule, h: Header, names: list[str]) -> list[str]:
    rings = [p.ring for p in h.primitives]
    kind = "starter" if rule.is_starter else "rule"
    lhs_tokens = rule.lhs.tokens(rings)
    comment = f"{'∂L' if rule.is_starter else '∂'} = {unicode(lhs_tokens, names) or 'ε'}"
    out = [f"{kind} {name(rule.name)} priority={rule.priority} weight={num(rule.weight)} {{"
           f"  # {_safe(comment)}"]
    out += _side("lhs", rule.lhs, h, names)
    if not rule.is_starter:
        out += _side("rhs", rule.rhs, h, names)
    out.append("}")
    return out


def _side(which: str, side: Side, h: Header, names: list[str]) -> list[str]:
    rings = [p.ring for p in h.primitives]
    vname = [name(side.vertex_name(v)) for v in range(len(side.vertices))]
    # Wires have no stored names: call them w0, w1, … unless a vertex already is.
    taken = set(vname)
    wname = []
    for e in range(len(side.wires)):
        cand = f"w{e}"
        while cand in taken:
            cand += "_"
        taken.add(cand)
        wname.append(cand)

    def slot(v: int, i: int) -> str:
        label = ring([side.slot_token((v, i), rings)], names)
        return f"{wname[-1 - v] if v < 0 else vname[v]}.{label}"

    out = [f"  {which} {{"]
    out += _wrap([f"{vname[v]}: {name(h.primitives[p].name)}" for v, p in enumerate(side.vertices)]
                 + [f"{wname[e]}: wire {name(names[bd.label_of(t)])}"
                    for e, t in enumerate(side.wires)])
    out += _wrap([f"{slot(v, i)} -- {slot(w, j)}" for v, i, w, j in side.edges])
    if side.boundary:
        items = [slot(*it) if isinstance(it, tuple) else ("+" if it == bd.UP else "-")
                 for it in side.boundary]
        out.append("    boundary " + " ".join(items))
    out.append("  }")
    return out


def _wrap(items: list[str], indent: str = "    ") -> list[str]:
    lines, cur = [], ""
    for item in items:
        if cur and len(indent) + len(cur) + 3 + len(item) > WIDTH:
            lines.append(indent + cur)
            cur = ""
        cur = f"{cur}   {item}" if cur else item
    if cur:
        lines.append(indent + cur)
    return lines


def ring(tokens, names: list[str]) -> str:
    return " ".join(("~" if bd.is_bar(t) else "") + name(names[bd.label_of(t)]) for t in tokens)


def name(text: str) -> str:
    """A name as the language spells it: bare when it is a plain identifier, else quoted."""
    if _PLAIN.fullmatch(text) and text not in KEYWORDS:
        return text
    return quote(text)


def quote(text: str) -> str:
    parts = ['"']
    for ch in text:
        if ch in '"\\':
            parts.append("\\" + ch)
        elif ch == "\n":
            parts.append("\\n")
        elif ch == "\t":
            parts.append("\\t")
        elif ch == "\r":
            parts.append("\\r")
        elif unicodedata.category(ch)[0] in "CZ" and ch != " ":
            # Control, format and separator characters would be invisible or break lines.
            code = ord(ch)
            parts.append(f"\\u{code:04x}" if code <= 0xFFFF else f"\\U{code:08x}")
        else:
            parts.append(ch)
    parts.append('"')
    return "".join(parts)


def _safe(text: str) -> str:
    """Text for a comment: control and line-separator characters escaped, nothing else."""
    return "".join(quote(ch)[1:-1] if unicodedata.category(ch) in ("Cc", "Cf", "Zl", "Zp")
                   else ch for ch in text)


def num(x: float) -> str:
    """The shortest exact text for a number: 90 rather than 90.0, else repr."""
    if isinstance(x, bool):
        raise TypeError("a flag is not a number")
    if isinstance(x, int):
        return str(x)
    if math.isinf(x) and x > 0:
        return "inf"
    if x == int(x) and abs(x) < 2 ** 53:
        return str(int(x))
    return repr(x)


def _value(v: object) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return num(v)
    return quote(str(v))
