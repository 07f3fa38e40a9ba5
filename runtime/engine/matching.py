"""Anchored matching of a rule side in the host: the kernel's walk (grammar_lang.algorithms.
matching) with the runtime's search over spliced sides on top.

A vertex's primitive fixes its whole ring, so once one pattern vertex is mapped to a host vertex
of the same primitive, following the pattern's glued slots through the host's links maps every
other vertex of that component, or fails, in time linear in the pattern (paper §6.1). Matching
starts from the pattern's primitive with the fewest host instances and never scans the drawing:
a random match tries candidates from a random offset of that primitive's index (or a few
random anchors, for a cheap probe), and the further components and wires of a spliced side are
looked for near the first, nearest first, through the grid. Whether spliced parts really share
a face is left to the placement, whose crossing and face-label tests decide it exactly.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Iterator

import numpy as np

from grammar_lang.algorithms.matching import extend, walk_plans
from grammar_lang.graph import Side, Slot

from .host import Host

# How far (in units) the components of a spliced side may lie from each other.
SPLICE_RADIUS = 2.0


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

    @staticmethod
    def build(side: Side, rings=()) -> "Pattern":
        partner = side.partner()
        comps = tuple(Component(tuple(verts), walk_plans(verts, partner))
                      for verts in side.components())
        opens = tuple(side.open_slots())
        wire_slots = tuple(
            tuple((p, i) for p, ring in enumerate(rings) for i, t in enumerate(ring) if t == tok ^ 1)
            for tok in side.wires)
        return Pattern(side, comps, opens, wire_slots)


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


def _comp_candidates(host: Host, pattern: Pattern, comp: Component, k: int,
                     near: dict | None):
    prim = pattern.side.vertices[comp.vertices[k]]
    if near is None:
        return host.by_prim[prim]
    # Later components of a splice: only vertices near the part already matched, nearest
    # first, found lazily (the first candidates are usually the ones taken).
    return _near(host, near, (prim,))


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


def _search(host: Host, pattern: Pattern, ci: int, vmap: dict, spo: bool,
            rng: np.random.Generator | None, budget: _Budget) -> Iterator[tuple[dict, tuple]]:
    if ci == len(pattern.components):
        if _glue_ok(host, pattern, vmap, spo):
            yield from _search_wires(host, pattern, 0, vmap, (), rng, budget)
        return
    comp = pattern.components[ci]
    k = _anchor(host, pattern, comp)
    cands = _comp_candidates(host, pattern, comp, k, vmap if ci else None)
    if ci:
        # Later parts of a splice: nearest first (as _comp_candidates gives them), since a
        # splice joins parts facing each other across one face, and the nearest candidates
        # are the likeliest to see the first part.
        order = cands
    else:
        n = len(cands)
        if n == 0:
            return
        if rng is None:
            order = sorted(cands)
        else:
            start = int(rng.integers(n))
            if budget.probes is not None:
                # A probe: random anchors only, so a failed try costs O(probes), not O(n).
                order = (cands[int(j)] for j in rng.integers(n, size=min(n, budget.probes)))
            else:
                order = (cands[(start + m) % n] for m in range(n))
    anchor = comp.vertices[k]
    for h in order:
        if ci and not budget.spend():
            return
        trial = dict(vmap)
        if extend(host.link, host.prim, pattern.side.vertices, comp.plans[k], anchor, h, trial):
            yield from _search(host, pattern, ci + 1, trial, spo, rng, budget)


def _search_wires(host: Host, pattern: Pattern, wi: int, vmap: dict, wires: tuple,
                  rng: np.random.Generator | None, budget: _Budget) -> Iterator[tuple[dict, tuple]]:
    if wi == len(pattern.wire_slots):
        yield vmap, wires
        return
    image = set(vmap.values())
    taken = {s for pair in wires for s in pair}
    placed = dict(vmap)
    placed.update({("w", k): s[0] for k, pair in enumerate(wires) for s in pair})
    if placed:
        # Beside parts already matched, look for the wire nearby only: the vertices the grid
        # finds there, nearest first (not a scan of the primitive's whole index).
        flat = _near_slots(host, placed, pattern.wire_slots[wi])
    else:
        lists = [(i, host.by_prim[p]) for p, i in pattern.wire_slots[wi]]
        total = sum(len(lst) for _, lst in lists)
        if total == 0:
            return
        if rng is not None:
            # Every host edge of the label, from a random one on: walked in place, since
            # listing them all would cost O(drawing) for a search that usually stops at the
            # first.
            flat = _rotated(lists, int(rng.integers(total)))
        else:
            flat = ((h, i) for i, lst in lists for h in lst)
    for h, i in flat:
        s1 = host.link[h][i]
        s0 = (h, i)
        if s1 is None or h in image or s1[0] in image or s0 in taken:
            continue
        if placed and not budget.spend():
            return
        yield from _search_wires(host, pattern, wi + 1, vmap, wires + ((s0, s1),), rng, budget)


def _near_slots(host: Host, placed: dict, wire_slots) -> Iterator[tuple[int, int]]:
    """The (vertex, slot) pairs of `wire_slots` ((primitive, slot) pairs) at the vertices near
    `placed`, in order of distance, vertex and slot."""
    slots: dict[int, list[int]] = {}
    for p, i in sorted(wire_slots, key=lambda pi: pi[1]):
        slots.setdefault(p, []).append(i)
    for h in _near(host, placed, list(slots)):
        for i in slots[host.prim[h]]:
            yield h, i


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


def _centroid(host: Host, placed: dict) -> tuple[float, float]:
    cx = sum(host.pos[v][0] for v in placed.values()) / len(placed)
    cy = sum(host.pos[v][1] for v in placed.values()) / len(placed)
    return cx, cy


def _near(host: Host, near: dict, prims) -> Iterator[int]:
    """The vertices of the primitives `prims` in the grid's cells within the splice radius of
    the box around the host vertices `near` (a superset of those within the radius), nearest
    first: by distance from their centroid, then id (so the grid's order does not matter)."""
    xs = [host.pos[h][0] for h in near.values()]
    ys = [host.pos[h][1] for h in near.values()]
    r = SPLICE_RADIUS * host.t.unit
    return host.grid.nearest_first(min(xs) - r, min(ys) - r, max(xs) + r, max(ys) + r,
                                   _centroid(host, near), prims)


def _match(pattern: Pattern, found) -> Match:
    vmap, wires = found
    return Match(tuple(vmap[v] for v in range(len(pattern.side.vertices))), wires)


def find_match(host: Host, pattern: Pattern, rng: np.random.Generator,
               spo: bool = False, probes: int | None = None) -> Match | None:
    """A random match, or None when none was found within the search budget (a budget only
    binds for spliced sides, whose later components multiply the candidates). With `probes`,
    only that many random anchors are tried: cheap, but None then proves nothing."""
    for found in _search(host, pattern, 0, {}, spo, rng, _Budget(RANDOM_BUDGET, probes)):
        return _match(pattern, found)
    return None


def iter_matches(host: Host, pattern: Pattern, spo: bool = False) -> Iterator[Match]:
    """Every match, in a deterministic order (ascending anchor vertex ids)."""
    seen = set()
    for found in _search(host, pattern, 0, {}, spo, None, _Budget(None)):
        m = _match(pattern, found)
        # Automorphic images of the same vertex set are distinct matches; only exact
        # duplicates (found through two anchors) are dropped.
        if (m.vmap, m.wmap) not in seen:
            seen.add((m.vmap, m.wmap))
            yield m
