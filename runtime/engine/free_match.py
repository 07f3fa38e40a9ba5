"""Anchored matching of a production's mother graph in the host (free_host).

The mother graph is compiled once into a plan: an anchor element (an edge if it has one, else
a face, else a vertex), then each further element reached from one already bound, through the
host's incidence lists. Only the anchor is looked up by label; everything else is found next
to it, so the cost of a match does not grow with the host. Disconnected parts of a mother graph
each start from their label index again. Matches are injective and respect labels, edge
directions (`--` matches either way) and face cycles (up to rotation).

`matches` yields bindings in the production's match order: `oldest` tries anchors by age
(breadth-first over generations), `random` tries random anchors first and then all of them from
a random offset, so a match is found whenever one exists.
"""

from __future__ import annotations

from dataclasses import dataclass

from grammar_lang.free_rules import FSide

from .free_host import FreeHost, LabelIndex

RANDOM_PICKS = 8        # random anchors tried before scanning all of them


@dataclass(frozen=True)
class Step:
    kind: str           # 'edge', 'face' or 'vertex'
    index: int          # into lhs.edges / lhs.faces, or lhs.vertices


@dataclass
class Binding:
    vertices: dict[str, int]
    edges: list[int | None]
    faces: list[int | None]
    used: set[int]

    def copy(self) -> "Binding":
        return Binding(dict(self.vertices), list(self.edges), list(self.faces), set(self.used))


def plan(lhs: FSide, anchor: Step | None = None) -> tuple[Step, ...]:
    steps: list[Step] = []
    bound: set[str] = set()
    edges, faces = set(range(len(lhs.edges))), set(range(len(lhs.faces)))
    vertices = [v.name for v in lhs.vertices]
    while edges or faces or any(v not in bound for v in vertices):
        near_e = [k for k in sorted(edges) if {lhs.edges[k].u, lhs.edges[k].v} & bound]
        near_f = [k for k in sorted(faces) if set(lhs.faces[k].cycle) & bound]
        if anchor is not None and not steps:
            step = anchor
        elif near_e or near_f:
            step = Step("edge", near_e[0]) if near_e else Step("face", near_f[0])
        elif edges or faces:    # a new anchor: a labelled edge first, it is the most selective
            labelled = [k for k in sorted(edges) if lhs.edges[k].label is not None]
            step = (Step("edge", (labelled or sorted(edges))[0]) if edges
                    else Step("face", min(faces)))
        else:
            k = next(k for k, v in enumerate(vertices) if v not in bound)
            step = Step("vertex", k)
        steps.append(step)
        if step.kind == "edge":
            edges.discard(step.index)
            bound |= {lhs.edges[step.index].u, lhs.edges[step.index].v}
        elif step.kind == "face":
            faces.discard(step.index)
            bound |= set(lhs.faces[step.index].cycle)
        else:
            bound.add(vertices[step.index])
    return tuple(steps)


class Matcher:
    def __init__(self, lhs: FSide, oldest: bool):
        self.lhs, self.oldest = lhs, oldest
        self.labels = {v.name: v.label for v in lhs.vertices}
        # One plan per labelled element that could anchor it; each match starts from the one
        # whose label is rarest in the host at that moment.
        anchors = ([(Step("edge", k), "edge", e.label) for k, e in enumerate(lhs.edges)]
                   + [(Step("face", k), "face", f.label) for k, f in enumerate(lhs.faces)]
                   + [(Step("vertex", k), "vertex", v.label) for k, v in enumerate(lhs.vertices)])
        self.plans = [(kind, label, plan(lhs, step)) for step, kind, label in anchors
                      if label is not None] or [(None, None, plan(lhs))]
        self.steps = self.plans[0][2]

    def matches(self, host: FreeHost, rng):
        if len(self.plans) > 1:
            self.steps = min(self.plans, key=lambda p: len(host.labelled(p[0], p[1])))[2]
        if not self.steps:      # an empty mother graph matches once, anywhere
            yield Binding({}, [], [], set())
            return
        yield from self._extend(host, rng, 0, Binding({}, [None] * len(self.lhs.edges),
                                                      [None] * len(self.lhs.faces), set()))

    def _extend(self, host: FreeHost, rng, k: int, b: Binding):
        if k == len(self.steps):
            yield b
            return
        step = self.steps[k]
        for cand in self._candidates(host, rng, step, b):
            nb = self._bind(host, step, cand, b)
            if nb is not None:
                yield from self._extend(host, rng, k + 1, nb)

    def _candidates(self, host: FreeHost, rng, step: Step, b: Binding):
        lhs = self.lhs
        if step.kind == "vertex":
            return self._anchors(host, rng, "vertex", lhs.vertices[step.index].label)
        item = lhs.edges[step.index] if step.kind == "edge" else lhs.faces[step.index]
        names = (item.u, item.v) if step.kind == "edge" else item.cycle
        start = next((b.vertices[n] for n in names if n in b.vertices), None)
        if start is None:
            return self._anchors(host, rng, step.kind, item.label)
        return list(host.incident[start])

    def _anchors(self, host: FreeHost, rng, kind: str, label: str | None):
        found = host.labelled(kind, label)
        indexes = [found] if isinstance(found, LabelIndex) else found
        if self.oldest:
            return _by_age(indexes)
        return _at_random(indexes, rng)

    def _bind(self, host: FreeHost, step: Step, cand: int, b: Binding) -> Binding | None:
        el = host.elements.get(cand)
        if el is None or el.kind != step.kind or cand in b.used:
            return None
        if step.kind == "vertex":
            v = self.lhs.vertices[step.index]
            return self._vertex(host, b.copy(), v.name, cand, extra=cand)
        if step.kind == "edge":
            e = self.lhs.edges[step.index]
            if e.label is not None and el.label != e.label:
                return None
            ways = [(e.u, e.v)] if e.directed else [(e.u, e.v), (e.v, e.u)]
            for u, v in ways:
                nb = self._pair(host, b, (u, v), el.ends)
                if nb is not None:
                    nb.edges[step.index] = cand
                    nb.used.add(cand)
                    return nb
            return None
        f = self.lhs.faces[step.index]
        if (f.label is not None and el.label != f.label) or len(el.ends) != len(f.cycle):
            return None
        n = len(f.cycle)
        for r in range(n):
            nb = self._pair(host, b, f.cycle, el.ends[r:] + el.ends[:r])
            if nb is not None:
                nb.faces[step.index] = cand
                nb.used.add(cand)
                return nb
        return None

    def _pair(self, host: FreeHost, b: Binding, names, ids) -> Binding | None:
        nb = b.copy()
        for name, vid in zip(names, ids):
            nb = self._vertex(host, nb, name, vid)
            if nb is None:
                return None
        return nb

    def _vertex(self, host: FreeHost, b: Binding, name: str, vid: int, extra=None):
        if name in b.vertices:
            return b if b.vertices[name] == vid else None
        if vid in b.used:
            return None
        want = self.labels[name]
        if want is not None and host.elements[vid].label != want:
            return None
        b.vertices[name] = vid
        b.used.add(vid)
        return b


def _by_age(indexes: list[LabelIndex]):
    if len(indexes) == 1:
        first = indexes[0].oldest()
        if first is None:
            return
        yield first
        for i in indexes[0].in_age_order():
            if i != first:
                yield i
        return
    yield from sorted(i for ix in indexes for i in ix.items)


def _at_random(indexes: list[LabelIndex], rng):
    items = [ix.items for ix in indexes if ix.items]
    total = sum(len(x) for x in items)
    if total == 0:
        return
    flat = items[0] if len(items) == 1 else [i for x in items for i in x]
    for _ in range(min(RANDOM_PICKS, total)):
        yield flat[rng.randrange(total)]
    start = rng.randrange(total)
    for k in range(total):
        yield flat[(start + k) % total]
