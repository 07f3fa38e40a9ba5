"""Anchored matching of a rule side in the host: the kernel's walk (grammar_lang.algorithms.
matching) with the runtime's search over spliced sides on top.

A vertex's primitive fixes its whole ring, so once one pattern vertex is mapped to a host vertex
of the same primitive, following the pattern's glued slots through the host's links maps every
other vertex of that component, or fails, in time linear in the pattern (paper §6.1). Matching
starts from the pattern's primitive with the fewest host instances and never scans the drawing:
a random match tries candidates from a random offset of that primitive's index (or a few
random anchors, for a cheap probe). The further components and wires of a spliced side are
looked for along the host face the boundary says they face (`_on_face`): the face is walked
from the part already matched, so parts that face each other across it are found at any
distance, and a place on the wrong side of a line is never proposed. Only what the walk cannot
tell (a face's holes, other components) is looked for near the parts through the grid and left
to the placement's crossing and face-label tests.
"""

from __future__ import annotations

import functools
import heapq
from dataclasses import dataclass
from typing import Iterator

import numpy as np

from grammar_lang.algorithms.faces import FaceWalk
from grammar_lang.algorithms.matching import extend, walk_plans
from grammar_lang.graph import Side, Slot

from ..geometry.spatial import Point
from .host import Host

@dataclass(frozen=True)
class Component:
    vertices: tuple[int, ...]
    # For each possible anchor vertex: the walk that maps the rest, as (u, i, w, j) steps: from
    # mapped u follow slot i to a host slot that must be (h, j) with h a w-primitive vertex.
    plans: tuple[tuple[tuple[int, int, int, int], ...], ...]


@dataclass(frozen=True)
class Pattern:
    side: Side
    components: tuple[Component, ...]
    open_slots: tuple[Slot, ...]                 # boundary order; wire ends are (-1 - e, end)
    # A wire (bare edge) matches a host edge of its label: per wire, the (primitive, slot)
    # pairs where its end-0 partner, a barred half-edge, can sit.
    wire_slots: tuple[tuple[tuple[int, int], ...], ...] = ()
    # The parts (components 0.., then wires: len(components) + e) in the order they are
    # matched: the first component (else wire), then the others as the boundary meets them.
    order: tuple[int, ...] = ()
    # For each part of `order` after the first: the boundary item before its first item, and
    # that item (the part is looked for on the host face between them); None for a part with
    # no open slot, looked for anywhere.
    entries: tuple[tuple[Slot, Slot] | None, ...] = ()
    # The other steps of the boundary from one part to the next: each crosses one host face.
    jumps: tuple[tuple[Slot, Slot], ...] = ()

    @staticmethod
    def build(side: Side, rings=()) -> "Pattern":
        partner = side.partner()
        verts = side.components()
        comps = tuple(Component(tuple(vs), walk_plans(vs, partner)) for vs in verts)
        opens = tuple(side.open_slots())
        wire_slots = tuple(
            tuple((p, i) for p, ring in enumerate(rings) for i, t in enumerate(ring) if t == tok ^ 1)
            for tok in side.wires)
        order, entries, jumps = _splice_plan(side, verts, opens)
        return Pattern(side, comps, opens, wire_slots, order, entries, jumps)


def _splice_plan(side: Side, verts: list[list[int]], opens: tuple[Slot, ...]):
    """`order`, `entries` and `jumps` of a Pattern: how the parts of a spliced side follow
    each other along its boundary (paper §4.2: one walk, the parts facing each other)."""
    comp_of = {v: c for c, vs in enumerate(verts) for v in vs}
    part = [comp_of[v] if v >= 0 else len(verts) - 1 - v for v, _ in opens]
    n_parts = len(verts) + len(side.wires)
    if n_parts == 0:
        return (), (), ()
    order, entries = [0], [None]
    n = len(opens)
    start = part.index(0) if 0 in part else 0
    if n and 0 not in part:         # the first part has no open slot: the next is anywhere too
        order.append(part[0])
        entries.append(None)
    for j in range(start + 1, start + n):
        p = part[j % n]
        if p not in order:
            order.append(p)
            entries.append((opens[(j - 1) % n], opens[j % n]))
    entered = set(entries)
    jumps = tuple((opens[j - 1], opens[j]) for j in range(n) if part[j - 1] != part[j]
                  and (opens[j - 1], opens[j]) not in entered)
    for p in range(n_parts):        # parts without an open slot: anywhere
        if p not in order:
            order.append(p)
            entries.append(None)
    return tuple(order), tuple(entries), jumps


@dataclass(frozen=True)
class Match:
    """Host vertex of each pattern vertex, and host edge of each wire as (end-0 partner,
    end-1 partner): the barred and the unbarred host slot of that edge."""

    vmap: tuple[int, ...]
    wmap: tuple[tuple[Slot, Slot], ...] = ()

    def partner_of(self, host: Host, s: Slot) -> Slot | None:
        """The host slot an open slot of the pattern is glued to."""
        if s[0] < 0:
            return self.wmap[-1 - s[0]][s[1]]
        return host.link[self.vmap[s[0]]][s[1]]


def _glue_ok(host: Host, pattern: Pattern, vmap: dict, spo: bool) -> bool:
    """DPO dangling condition: an interface slot must not be glued into the match itself."""
    if spo:
        return True
    image = set(vmap.values())
    for v, i in pattern.open_slots:
        if v < 0:
            continue
        s = host.link[vmap[v]][i]
        if s is not None and s[0] in image:
            return False
    return True


def _anchor(host: Host, pattern: Pattern, comp: Component) -> int:
    """Index into comp.vertices of the vertex whose primitive is rarest in the host."""
    counts = [len(host.by_prim[pattern.side.vertices[v]]) for v in comp.vertices]
    return min(range(len(counts)), key=lambda k: (counts[k], k))


class _Budget:
    """How many candidate extensions a random search may try before it gives up (spliced
    sides can otherwise multiply candidates); exhaustive searches have no budget."""

    def __init__(self, n: int | None, probes: int | None = None):
        self.n = n if probes is None or n is None else min(n, PROBE_BUDGET)
        self.probes = probes            # how many anchor candidates of the first part to try

    def spend(self) -> bool:
        if self.n is None:
            return True
        self.n -= 1
        return self.n >= 0


RANDOM_BUDGET = 300
PROBE_BUDGET = 40
# How far (in units) the components of a spliced side may lie from each other when the face
# walk cannot tell whether they face each other (see _on_face).
SPLICE_RADIUS = 2.0
# How many corners of a face a random search walks to find the next part of a splice: a
# bound on the work of one proposal in a drawing with a huge face (a tree's outer face).
FACE_WALK = 600


def _search(host: Host, pattern: Pattern, k: int, vmap: dict, wmap: dict, spo: bool,
            rng: np.random.Generator | None, budget: _Budget) -> Iterator[tuple[dict, dict]]:
    """Matches extending `vmap` (pattern vertex → host vertex) and `wmap` (wire → its host
    edge's slots) by the parts of pattern.order from the k-th on. Wires may share end
    vertices, not slots; no wire ends on a vertex of the match."""
    if k == len(pattern.order):
        if _glue_ok(host, pattern, vmap, spo) and _faces_shared(host, pattern, vmap, wmap,
                                                                _walk_limit(host, rng)):
            yield vmap, wmap
        return
    part, n_comps = pattern.order[k], len(pattern.components)
    if k and pattern.entries[k] is not None:
        found = _on_face(host, pattern, k, vmap, wmap, rng)
    elif part < n_comps:
        found = _any_instance(host, pattern, part, rng, budget if not k else _Budget(None))
    else:
        found = _any_wire(host, pattern, part - n_comps, rng)
    image = set(vmap.values())
    ends = {s[0] for pair in wmap.values() for s in pair}
    for cand in found:
        if k and not budget.spend():
            return
        if part < n_comps:
            anchor, h = cand
            comp = pattern.components[part]
            trial = dict(vmap)
            if extend(host.link, host.prim, pattern.side.vertices,
                      comp.plans[comp.vertices.index(anchor)], anchor, h, trial) \
                    and ends.isdisjoint(trial[v] for v in comp.vertices):
                yield from _search(host, pattern, k + 1, trial, wmap, spo, rng, budget)
        elif cand[0][0] not in image and cand[1][0] not in image \
                and all(cand[0] not in pair for pair in wmap.values()):
            yield from _search(host, pattern, k + 1, vmap, {**wmap, part - n_comps: cand},
                               spo, rng, budget)


def _any_instance(host: Host, pattern: Pattern, part: int, rng, budget: _Budget):
    """(anchor, host vertex) candidates for a component found anywhere: every instance of
    its rarest primitive, from a random one on (or a few random ones, for a probe)."""
    comp = pattern.components[part]
    anchor = comp.vertices[_anchor(host, pattern, comp)]
    cands = host.by_prim[pattern.side.vertices[anchor]]
    n = len(cands)
    if n == 0:
        return ()
    if rng is None:
        order = sorted(cands)
    else:
        start = int(rng.integers(n))
        if budget.probes is not None:
            # A probe: random anchors only, so a failed try costs O(probes), not O(n).
            order = (cands[int(j)] for j in rng.integers(n, size=min(n, budget.probes)))
        else:
            order = (cands[(start + m) % n] for m in range(n))
    return ((anchor, h) for h in order)


def _any_wire(host: Host, pattern: Pattern, e: int, rng):
    """(barred, unbarred) host slot candidates for wire `e` found anywhere: every host edge
    of its label, walked in place from a random one on (listing them all would cost
    O(drawing) for a search that usually stops at the first)."""
    lists = [(i, host.by_prim[p]) for p, i in pattern.wire_slots[e]]
    total = sum(len(lst) for _, lst in lists)
    if total == 0:
        return
    flat = _rotated(lists, int(rng.integers(total))) if rng is not None else \
        ((h, i) for i, lst in lists for h in lst)
    for h, i in flat:
        s1 = host.link[h][i]
        if s1 is not None:
            yield (h, i), s1


def _on_face(host: Host, pattern: Pattern, k: int, vmap: dict, wmap: dict, rng):
    """Candidates for the k-th part of a splice: where its first boundary item can follow the
    item before it across one host face (the parts of a spliced side face each other, paper
    §4.2). Places on the walk of that face come first, nearest first, at any distance (a
    village's strip faces a line 160 px across it); then places near the parts matched, seen
    through the grid, unless their own face walk shows them on another face: what walks
    cannot tell (a face's holes: other structures) is left to the placement's crossing and
    face-label tests."""
    prev, item = pattern.entries[k]
    limit = _walk_limit(host, rng)
    wire = pattern.order[k] >= len(pattern.components)
    entry = FaceWalk(host.link, host.pos, _corner(host, prev, vmap, wmap, True), limit)
    placed = {**vmap, **{("w", e, j): s[0] for e, pair in wmap.items()
                         for j, s in enumerate(pair)}}
    pts = [host.pos[h] for h in placed.values()]
    centre = (sum(p[0] for p in pts) / len(pts), sum(p[1] for p in pts) / len(pts))
    on_walk = _on_walk(host, pattern, item, wire, entry)
    near = _facing(host, item, wire, entry, limit,
                   _near_candidates(host, pattern, item, wire, placed, centre))
    # One order for both kinds, nearest first: a place in another structure beside the parts
    # is as good as one far along the face's walk.
    key = functools.partial(_distance_key, host.pos, centre, wire)
    yield from heapq.merge(sorted(on_walk, key=key), near, key=key)


def _on_walk(host: Host, pattern: Pattern, item: Slot, wire: bool, entry: FaceWalk) -> list:
    """The candidates for `item` at the corners of the walk `entry`."""
    v, i = item
    t, link, prim = host.t, host.link, host.prim
    tok = pattern.side.wires[-1 - v] ^ i if wire else None    # the token a wire item carries
    out = []
    for u, c in entry.corners:
        nxt = (c + 1) % len(link[u])
        if wire:
            # The face reaches a wire item just before the host slot at the edge's far end,
            # which carries the item's own token: the unbarred end for item (e, 0).
            if t.rings[prim[u]][nxt] == tok and link[u][nxt] is not None:
                s = (u, nxt)
                out.append((link[u][nxt], s) if i == 0 else (s, link[u][nxt]))
        elif nxt == i and prim[u] == pattern.side.vertices[v]:
            out.append((v, u))
    return out


def _near_candidates(host: Host, pattern: Pattern, item: Slot, wire: bool, placed: dict,
                     centre: Point) -> Iterator:
    """The candidates for `item` near the parts `placed`, through the grid, nearest first."""
    v, _ = item
    if wire:
        slots = _near_slots(host, placed, centre, pattern.wire_slots[-1 - v])
        return (((h, j), host.link[h][j]) for h, j in slots if host.link[h][j] is not None)
    return ((v, h) for h in _near(host, placed, centre, (pattern.side.vertices[v],)))


def _facing(host: Host, item: Slot, wire: bool, entry: FaceWalk, limit: int, cands) -> Iterator:
    """The candidates off the walk `entry` whose own walk is not known to bound another face."""
    v, _ = item
    for cand in cands:
        ends = (cand[0][0], cand[1][0]) if wire else (cand[1],)
        if not entry.vertices.isdisjoint(ends):
            continue                # on the walk, but not where the item goes
        at = _corner(host, item, {v: cand[1]} if not wire else {},
                     {-1 - v: cand} if wire else {}, False)
        if entry.shares_face(FaceWalk(host.link, host.pos, at, limit)) is not False:
            yield cand


def _distance_key(pos, centre, wire: bool, cand) -> tuple:
    """A candidate's order: its distance from the parts matched (squared), then its vertex and
    slot, so that the grid's order does not matter (the order Grid.nearest_first gives)."""
    h = cand[0] if wire else (cand[1], 0)
    p = pos[h[0]]
    return (p[0] - centre[0]) ** 2 + (p[1] - centre[1]) ** 2, h


def _near(host: Host, near: dict, centre: Point, prims) -> Iterator[int]:
    """The vertices of the primitives `prims` in the grid's cells within the splice radius of
    the box around the host vertices `near` (a superset of those within the radius), nearest
    first: by distance from `centre` (their centroid), then id (so the grid's order does not
    matter), found lazily (the first few are usually all a search takes)."""
    xs = [host.pos[h][0] for h in near.values()]
    ys = [host.pos[h][1] for h in near.values()]
    r = SPLICE_RADIUS * host.t.unit
    return host.grid.nearest_first(min(xs) - r, min(ys) - r, max(xs) + r, max(ys) + r,
                                   centre, prims)


def _near_slots(host: Host, placed: dict, centre: Point,
                wire_slots) -> Iterator[tuple[int, int]]:
    """The (vertex, slot) pairs of `wire_slots` ((primitive, slot) pairs) at the vertices near
    `placed`, in order of distance, vertex and slot."""
    slots: dict[int, list[int]] = {}
    for p, i in sorted(wire_slots, key=lambda pi: pi[1]):
        slots.setdefault(p, []).append(i)
    for h in _near(host, placed, centre, list(slots)):
        for i in slots[host.prim[h]]:
            yield h, i


def _corner(host: Host, item: Slot, vmap: dict, wmap: dict, after: bool) -> Slot:
    """The host corner a boundary item's walk leaves into (`after`) or comes from. A wire
    item (e, 0) is glued to the barred end of its host edge, (e, 1) to the other."""
    v, i = item
    if v >= 0:
        h = vmap[v]
        return (h, i) if after else (h, (i - 1) % len(host.link[h]))
    s = wmap[-1 - v][0 if (i == 0) == after else 1]
    return s[0], (s[1] - 1) % len(host.link[s[0]])


def _faces_shared(host: Host, pattern: Pattern, vmap: dict, wmap: dict, limit: int) -> bool:
    """Whether no step of the boundary from one part to another is known to cross between
    two faces (see FaceWalk.shares_face)."""
    for a, b in pattern.jumps:
        goal = _corner(host, b, vmap, wmap, False)
        # Walked only as far as the goal: most jumps reach it within a few corners.
        walk = FaceWalk(host.link, host.pos, _corner(host, a, vmap, wmap, True), limit, goal)
        if goal not in walk.at and \
                walk.shares_face(FaceWalk(host.link, host.pos, goal, limit)) is False:
            return False
    return True


def _walk_limit(host: Host, rng) -> int:
    # An exhaustive search walks whole faces; a random one a bounded stretch of each.
    return FACE_WALK if rng is not None else 2 * host.n_edges + 2


def _rotated(lists: list[tuple[int, list]], start: int) -> Iterator[tuple[int, int]]:
    """The (vertex, slot) pairs of `lists` laid end to end, from position `start` round to
    the one before it."""
    ends, offset = [], 0
    for i, lst in lists:
        ends.append((i, lst, offset))
        offset += len(lst)
    for lo, hi in ((start, offset), (0, start)):
        for i, lst, o in ends:
            for k in range(max(lo - o, 0), min(hi - o, len(lst))):
                yield lst[k], i


def _match(pattern: Pattern, found) -> Match:
    vmap, wmap = found
    return Match(tuple(vmap[v] for v in range(len(pattern.side.vertices))),
                 tuple(wmap[e] for e in range(len(pattern.side.wires))))


def find_match(host: Host, pattern: Pattern, rng: np.random.Generator,
               spo: bool = False, probes: int | None = None) -> Match | None:
    """A random match, or None when none was found within the search budget (a budget only
    binds for spliced sides, whose later components multiply the candidates). With `probes`,
    only that many random anchors are tried: cheap, but None then proves nothing."""
    for found in _search(host, pattern, 0, {}, {}, spo, rng, _Budget(RANDOM_BUDGET, probes)):
        return _match(pattern, found)
    return None


def iter_matches(host: Host, pattern: Pattern, spo: bool = False) -> Iterator[Match]:
    """Every match, in a deterministic order (ascending anchor vertex ids)."""
    seen = set()
    for found in _search(host, pattern, 0, {}, {}, spo, None, _Budget(None)):
        m = _match(pattern, found)
        # Automorphic images of the same vertex set are distinct matches; only exact
        # duplicates (found through two anchors) are dropped.
        if (m.vmap, m.wmap) not in seen:
            seen.add((m.vmap, m.wmap))
            yield m
