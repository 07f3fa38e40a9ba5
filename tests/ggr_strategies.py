"""Hypothesis strategies for grammars whose headers and rules are consistent (.ggr tests).

Rules are built so that they pass every check of the parser: sides are grown by branch and
loop gluing as the compiler grows graphs, so glued slots carry opposite half-edges on
different vertices and the boundary is the walk the rotation system implies; components and
wires are spliced as A∧ⁿB∨ⁿ⁺¹. The two sides of a rule have equal boundary strings (the left
side is the right side with its vertices renumbered and renamed and its edges reordered).
Starters glue a random set of vertices completely, or a pair of opposite stubs.
"""

from __future__ import annotations

import math

from hypothesis import strategies as st

from grammar_lang import boundary as bd
from grammar_lang.vocabulary import EdgeLabel, Primitive, Vocabulary
from grammar_lang.gg_schema import DECORATIONS, Field
from grammar_lang.graph import Side, face_walk
from grammar_lang.rules import Grammar, Header, Rule
from grammar_lang.source import DEFAULT_CLASS, Decoration, EdgeClass, Limits, Options

def field_values(f: Field):
    """Values a `.gg` decoration property of this schema field accepts, as checked values."""
    if f.kind == "colour":
        return st.from_regex(r"#[0-9a-f]{6}", fullmatch=True)
    if f.kind == "bool":
        return st.booleans()
    if f.kind == "enum":
        return st.sampled_from(f.choices)
    lo = 0.0 if f.lo is None else f.lo
    hi = 1e6 if f.hi is None else f.hi
    return st.floats(lo, hi, exclude_min=f.lo_open, exclude_max=f.hi_open, allow_nan=False)


# Plain identifiers collide often (good for uniqueness handling); free text exercises quoting;
# the language's own words are names too.
WORDS = ("boundary", "class", "exterior", "face", "faces", "frame", "label", "let", "lhs",
         "limits", "primitive", "production", "rhs", "rule", "set", "starter", "unit",
         "where", "wire", "edges", "vertices", "attribute", "start", "mode", "status",
         "source", "hash", "compiler", "checksum", "options", "decorate", "ggr")
plain = st.from_regex(r"[a-zA-Z_][a-zA-Z0-9_₀₁]{0,4}", fullmatch=True)
names = st.one_of(plain, plain, st.text(min_size=1, max_size=6), st.sampled_from(WORDS))
positive = st.floats(min_value=1e-6, max_value=1e6, allow_nan=False, allow_infinity=False)
nonneg = st.floats(min_value=0, max_value=1e6, allow_nan=False, allow_infinity=False)
angles = st.one_of(st.sampled_from([0.0, 45.0, 90.0, 135.0, 22.5]),
                   st.floats(min_value=0.0, max_value=180.0, exclude_max=True, allow_nan=False))


def unique(strategy, min_size=0, max_size=4):
    return st.lists(strategy, min_size=min_size, max_size=max_size, unique=True)


@st.composite
def edge_classes(draw):
    out = []
    for name in draw(unique(names, 0, 3)):
        lo = draw(st.none() | positive)
        hi = draw(st.none() | positive)
        if lo is not None and hi is not None and lo > hi:
            lo, hi = hi, lo
        out.append(EdgeClass(name, lo, hi, draw(st.none() | positive), draw(st.none() | positive),
                             draw(st.booleans()), draw(st.booleans())))
    return tuple(out)


@st.composite
def headers(draw) -> Header:
    faces = tuple(draw(unique(names, 1, 4)))
    exterior = draw(st.sampled_from(faces) | names)
    sides = sorted(set(faces) | {exterior})
    classes = draw(edge_classes())
    class_names = [c.name for c in classes] + [DEFAULT_CLASS]
    labels = tuple(EdgeLabel(n, draw(st.sampled_from(sides)), draw(st.sampled_from(sides)),
                             draw(angles), draw(st.sampled_from(class_names)),
                             draw(st.none() | positive), draw(st.none() | positive))
                   for n in draw(unique(names, 1, 4)))
    if any(l.cls == DEFAULT_CLASS for l in labels) and DEFAULT_CLASS not in \
            {c.name for c in classes}:
        classes += (EdgeClass(DEFAULT_CLASS),)     # every class a label uses is declared
    tokens = [bd.half(i, bar) for i in range(len(labels)) for bar in (False, True)]
    prim_names = draw(unique(names, 2, 6))
    prims = []
    for k, name in enumerate(prim_names):
        if k == 0:      # opposite stubs, so that some starters exist
            ring = (bd.half(0, False),)
        elif k == 1:
            ring = (bd.half(0, True),)
        else:
            chosen = draw(st.lists(st.sampled_from(tokens), min_size=1, max_size=4, unique=True))
            by_dir: dict[float, int] = {}
            for t in chosen:   # at most one half-edge per direction
                by_dir.setdefault(labels[bd.label_of(t)].direction(bd.is_bar(t)), t)
            ring = tuple(by_dir[d] for d in sorted(by_dir))
        prims.append(Primitive(name, ring, draw(st.integers(0, 9))))
    targets = {"face": sides, "edge": class_names, "vertex": [p.name for p in prims]}
    decorations = []
    for _ in range(draw(st.integers(0, 3))):
        kind = draw(st.sampled_from(sorted(targets)))
        schema = {k: f for k, f in DECORATIONS[kind].items() if f.kind != "file"}
        keys = draw(st.lists(st.sampled_from(sorted(schema)), max_size=3, unique=True))
        decorations.append(Decoration(kind, draw(st.sampled_from(["*"] + list(targets[kind]))),
                                      tuple((k, draw(field_values(schema[k]))) for k in keys)))
    options = Options(draw(nonneg), draw(nonneg), draw(st.none() | nonneg),
                      draw(st.none() | positive), draw(st.booleans()), draw(st.booleans()),
                      Limits(draw(st.integers(0, 10**6)), draw(st.integers(0, 100)),
                             draw(st.integers(0, 10**9)), draw(nonneg | st.just(math.inf))))
    return Header(source=draw(st.text(max_size=12)), source_hash=draw(st.text(max_size=12)),
                  compiler_version=draw(st.text(max_size=6)),
                  vocabulary=Vocabulary(exterior, faces, classes, labels, tuple(prims),
                                        draw(positive)),
                  options=options, decorations=tuple(decorations),
                  mode=draw(st.sampled_from(["dpo", "spo"])),
                  complete=draw(st.sampled_from([True, False, None])))


def _glue(draw, rings, vertices, eager: bool):
    """Randomly glue opposite slots of different vertices; returns (edges, open slots)."""
    slots = [(v, i) for v, p in enumerate(vertices) for i in range(len(rings[p]))]
    order = draw(st.permutations(slots))
    free = set(slots)
    edges = []
    for s in order:
        if s not in free:
            continue
        want = bd.opposite(rings[vertices[s[0]]][s[1]])
        partners = [t for t in order if t in free and t[0] != s[0]
                    and rings[vertices[t[0]]][t[1]] == want]
        if partners and (eager or draw(st.booleans())):
            t = partners[draw(st.integers(0, len(partners) - 1))]
            free -= {s, t}
            edges.append(s + t if s < t else t + s)
    return edges, [s for s in order if s in free]


def _names(draw, n):
    if draw(st.booleans()):
        return ()
    chosen = tuple(draw(st.lists(names, min_size=n, max_size=n, unique=True)))
    # The default names v0, v1, … are how a file spells "no names"; the parser gives back ().
    return () if chosen == tuple(f"v{k}" for k in range(n)) else chosen


def _component(draw, rings, labels, vertices: list[int], edges: list) -> list[tuple]:
    """Grow one component into `vertices`/`edges`: a tree by branch gluing, then a few loop
    gluings of consecutive slots, as the compiler builds graphs. Returns its face walk."""
    if draw(st.integers(0, 4)) == 0:   # a wire; the caller numbers it
        return [("wire", bd.half(draw(st.integers(0, len(labels) - 1)), False))]
    first = len(vertices)
    vertices.append(draw(st.integers(0, len(rings) - 1)))
    glued: set = set()
    for _ in range(draw(st.integers(0, 3))):
        open_slots = [(v, i) for v in range(first, len(vertices))
                      for i in range(len(rings[vertices[v]])) if (v, i) not in glued]
        if not open_slots:
            break
        s = draw(st.sampled_from(open_slots))
        want = bd.opposite(rings[vertices[s[0]]][s[1]])
        fits = [(p, r.index(want)) for p, r in enumerate(rings) if want in r]
        if not fits:
            continue
        p, j = draw(st.sampled_from(fits))
        t = (len(vertices), j)
        vertices.append(p)
        edges.append(s + t)
        glued |= {s, t}
    while True:
        side = Side(tuple(vertices), tuple(edges), ())
        open_slots = [(v, i) for v in range(first, len(vertices))
                      for i in range(len(rings[vertices[v]])) if (v, i) not in glued]
        if not open_slots:      # complete (two opposite stubs): its walk is just ∧
            return []
        walk = face_walk(side, open_slots[0], rings)
        loops = [k for k, ((s1, n1), (s2, _)) in enumerate(zip(walk, walk[1:] + walk[:1]))
                 if len(walk) > 2 and s1[0] != s2[0]
                 and rings[vertices[s2[0]]][s2[1]] == bd.opposite(rings[vertices[s1[0]]][s1[1]])
                 and n1 == (-1 if bd.is_bar(rings[vertices[s1[0]]][s1[1]]) else 0)]
        if not loops or not draw(st.booleans()):
            return walk
        k = draw(st.sampled_from(loops))
        s1, s2 = walk[k][0], walk[(k + 1) % len(walk)][0]
        edges.append(s1 + s2 if s1 < s2 else s2 + s1)
        glued |= {s1, s2}


def _as_items(walk, start: int) -> list:
    return list(bd.from_gaps(walk[start:] + walk[:start]))


@st.composite
def sides(draw, header: Header) -> Side:
    """A side of one or more components spliced as A∧ⁿB∨ⁿ⁺¹ (paper §4.2), with a boundary
    that follows its rotation system."""
    rings = [p.ring for p in header.primitives]
    vertices: list[int] = []
    edges: list = []
    wires: list[int] = []
    items: list = []
    for c in range(draw(st.integers(1, 3))):
        walk = _component(draw, rings, header.labels, vertices, edges)
        if walk and walk[0][0] == "wire":
            wires.append(walk[0][1])
            e = -len(wires)
            walk = [((e, 1), 0), ((e, 0), 1)]
        block = _as_items(walk, draw(st.integers(0, len(walk) - 1))) if walk else [bd.UP]
        if c:
            n = draw(st.integers(-1, 2))
            block = list(bd.turns(n)) + block + list(bd.turns(-n - 1))
        at = draw(st.integers(0, len(items)))
        items[at:at] = block
    shift = draw(st.integers(0, len(items) - 1))
    items = items[shift:] + items[:shift]
    edges = [(v, i, w, j) if (v, i) < (w, j) else (w, j, v, i) for v, i, w, j in edges]
    return Side(tuple(vertices), tuple(draw(st.permutations(edges))), tuple(items),
                _names(draw, len(vertices)), tuple(wires))


@st.composite
def renumbered(draw, side: Side) -> Side:
    """The same graph with vertices renumbered, renamed and edges reordered: same boundary."""
    n = len(side.vertices)
    perm = draw(st.permutations(range(n)))      # old vertex → new vertex
    vertices = [0] * n
    for old, new in enumerate(perm):
        vertices[new] = side.vertices[old]
    edges = []
    for v, i, w, j in draw(st.permutations(side.edges)):
        a, b = (perm[v], i), (perm[w], j)
        edges.append(a + b if a < b else b + a)
    items = tuple((perm[it[0]], it[1]) if isinstance(it, tuple) and it[0] >= 0 else it
                  for it in side.boundary)
    return Side(tuple(vertices), tuple(edges), items, _names(draw, n), side.wires)


@st.composite
def starter_sides(draw, header: Header) -> Side:
    rings = [p.ring for p in header.primitives]
    vertices = draw(st.lists(st.integers(0, len(rings) - 1), min_size=2, max_size=6))
    edges, open_slots = _glue(draw, rings, vertices, eager=True)
    if open_slots:     # fall back on the two opposite stubs of the header
        vertices, edges = [0, 1], [(0, 0, 1, 0)]
    return Side(tuple(vertices), tuple(edges), (bd.UP,), _names(draw, len(vertices)))


@st.composite
def grammars(draw) -> Grammar:
    header = draw(headers())
    rules = []
    for name in draw(unique(names, 0, 5)):
        priority = draw(st.integers(-5, 5))
        weight = draw(st.one_of(st.just(1.0), nonneg))
        if draw(st.integers(0, 3)) == 0:
            rules.append(Rule(name, draw(starter_sides(header)), Side((), (), ()),
                              priority, weight))
        else:
            rhs = draw(sides(header))
            rules.append(Rule(name, draw(renumbered(rhs)), rhs, priority, weight))
    return Grammar(header, tuple(rules))
