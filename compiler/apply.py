"""Applying a rule destructively (L → R) to a graph, for `ggc verify` (§5.2, Fig. 7).

The i-th open slot of L and of R are the same interface point. Cutting L out leaves, at each
interface point, whatever L's slot was glued to: a slot of the context, or another of L's own
open slots (an edge between two interface points). R is glued in by joining each interface
point's R end to that. R's bare edges (wires) join their two interface points straight through.
"""

from __future__ import annotations

from grammar_lang import boundary as bd
from grammar_lang.graph import Side

from .gluing import Graph, items_to_gaps
from .occurrence import Host


def side_graph(side: Side) -> Graph:
    items = [it if isinstance(it, tuple) else (1 if it == bd.UP else -1) for it in side.boundary]
    return Graph(tuple(side.vertices), tuple(sorted(side.edges)),
                 items_to_gaps([it for it in items if not (isinstance(it, tuple) and it[0] < 0)]))


def wired_pairs(rhs: Side) -> tuple[tuple[int, int], ...]:
    """Pairs of interface points (open-slot indices) that R joins by a bare wire."""
    ends: dict[int, list[int]] = {}
    for k, (v, _) in enumerate(rhs.open_slots()):
        if v < 0:
            ends.setdefault(-1 - v, []).append(k)
    return tuple(sorted(tuple(ks) for ks in ends.values() if len(ks) == 2))


def apply(lhs: Side, rhs: Side, img: list[int], host: Host) -> None:
    """Replace the match `img` of lhs in host by rhs, in place."""
    l_open = lhs.open_slots()
    r_open = rhs.open_slots()
    where = {(v, i): k for k, (v, i) in enumerate(l_open)}
    inv = {h: v for v, h in enumerate(img)}
    ext: list = []
    for v, i in l_open:
        q = host.part[img[v]].get(i)
        if q is None:
            ext.append(None)
        elif q[0] in inv and (inv[q[0]], q[1]) in where:
            ext.append(("r", where[(inv[q[0]], q[1])]))
        else:
            ext.append(("c", q))
    for h in img:
        host.remove_vertex(h)
    new = [host.add_vertex(p) for p in rhs.vertices]
    for v, i, w, j in rhs.edges:
        host.glue((new[v], i), (new[w], j))
    # Link graph over interface ends: R ends ("r", k) and context slots ("c", slot).
    links: dict = {}

    def link(a, b) -> None:
        links.setdefault(a, []).append(b)
        links.setdefault(b, []).append(a)

    wire_pos: dict[int, list[int]] = {}
    for k, x in enumerate(ext):
        if x is None:
            continue
        if x[0] == "c" or k < x[1]:
            link(("r", k), x)
    for k, (v, i) in enumerate(r_open):
        if v < 0:
            wire_pos.setdefault(-1 - v, []).append(k)
    for ks in wire_pos.values():
        if len(ks) == 2:
            link(("r", ks[0]), ("r", ks[1]))

    def slot_of(node):
        if node[0] == "c":
            return node[1]
        v, i = r_open[node[1]]
        return None if v < 0 else (new[v], i)

    seen: set = set()
    for start in sorted(links, key=repr):
        if start in seen or slot_of(start) is None:
            continue
        prev, cur = None, start
        seen.add(cur)
        while True:
            nxt = [n for n in links.get(cur, ()) if n != prev]
            if not nxt:
                break
            prev, cur = cur, nxt[0]
            seen.add(cur)
            if slot_of(cur) is not None:
                break
        end = slot_of(cur)
        if end is not None and cur != start:
            host.glue(slot_of(start), end)
