"""The faces a complete graph can close through one gap of a unit, listed when they are few.

A face of a complete graph is a closed walk of moves (pruning.TurnAnalysis) that turns +1 (the
outer face) or −1 (an inner one). Through gap k of unit u (from its open slot k to slot k+1)
it is a walk that leaves u along slot k+1 and comes back by a move landing on slot k. The walk
pins its instances down: each move lands on the instance that the next one leaves, and the
walk closes on the instance it left. So a face that visits L distinct units is one ring of L
instances glued along its L edges, the same in every complete graph that has it.

Listing them is a depth-first search over live moves, cut by the turning bounds of the
analysis (the least and greatest turns of the walks that could close it). It gives up, and
says so with None, when a walk could still close after FACE_MOVES moves (a cycle that turns
0 makes a gap's faces endless) or after FACE_STEPS steps: limits count work, not seconds.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from .gluing import Graph, branch_glue, loop_glue, loop_gluable

if TYPE_CHECKING:
    from .pruning import TurnAnalysis

FACE_MOVES = 6
FACE_STEPS = 400
Walk = tuple[int, ...]      # move indices, the one landing on the gap last


def faces_through(turns: "TurnAnalysis", u: int, k: int, end: int | None = None
                  ) -> list[Walk] | None:
    """Every walk of live moves that can be a face through gap k of unit u (turns ±1), or None
    when the search cannot list them all; with `end`, only those that land on the gap by that
    move (a gap may have endless faces, as many as siblings on a line, but few by one move)."""
    found = []
    for walk in iter_faces(turns, u, k, end):
        if walk is None:
            return None
        found.append(walk)
    return found


def iter_faces(turns: "TurnAnalysis", u: int, k: int, end: int | None = None):
    """The walks of `faces_through` one by one, then None if the search gave up: a caller
    that needs one face of some kind can stop at the first."""
    ring = len(turns.rings[u])
    ends = [b for b in turns.landing.get((u, k), ())
            if b not in turns.dead and end in (None, b)]
    steps = 0
    comp = turns.comp_of
    # Per component: the least and greatest turns from each move on to a closing move.
    bounds: dict[int, list] = {}
    stack = [((a,), turns.turns[a]) for a in reversed(turns.live_leaving(u, (k + 1) % ring))]
    while stack:
        walk, total = stack.pop()
        steps += 1
        if steps > FACE_STEPS:
            yield None
            return
        last, home = walk[-1], comp[walk[0]]
        if last in ends and total in (-1, 1):
            yield walk
        if home not in bounds:
            bounds[home] = [turns.closing(e) for e in ends if comp[e] == home]
        for b in reversed(turns.follow(last)):
            if comp[b] != home:
                continue
            # (A loop, not any() over a generator: this is the search's inner test.)
            for lo, hi in bounds[home]:
                least, most = lo[b] + total, hi[b] + total
                if least <= -1 <= most or least <= 1 <= most:
                    break
            else:
                continue
            if len(walk) == FACE_MOVES:
                yield None
                return
            stack.append((walk + (b,), total + turns.turns[b]))


def face_units(turns: "TurnAnalysis", walk: Walk) -> list[int]:
    """The units a face visits, from the one it passes the gap of (landed on last)."""
    return [turns.moves[walk[-1]][2]] + [turns.moves[m][2] for m in walk[:-1]]


def face_graph(turns: "TurnAnalysis", walk: Walk) -> Graph | None:
    """The ring of units an inner face glues together, closed; None when its units are not
    distinct (instances of one unit could then be one or several) or it is not an inner face
    (an outer face closes no loop that the hierarchy's graphs could show)."""
    units = face_units(turns, walk)
    if len(set(units)) != len(units):
        return None
    blocks, rings = turns.blocks, turns.prim_rings
    g = blocks[units[0]]
    first = [0]
    for n, m in enumerate(walk[:-1]):
        p, i, q, j = turns.moves[m]
        (v, a), t = blocks[p].gaps[i][0], blocks[q].gaps[j][0]
        if (first[n] + v, a) not in {s for s, _ in g.gaps}:
            return None     # it leaves a unit by the slot it came in by (a stub): no ring
        first.append(len(g.verts))
        g = branch_glue(g, (first[n] + v, a), blocks[q], t, rings, q)
    p, i, q, j = turns.moves[walk[-1]]
    (v, a), (w, c) = blocks[p].gaps[i][0], blocks[q].gaps[j][0]
    ends = {(first[-1] + v, a), (w, c)}
    m = len(g.gaps)
    for n in range(m):
        if {g.gaps[n][0], g.gaps[(n + 1) % m][0]} == ends and loop_gluable(g, n, rings):
            return loop_glue(g, n)
    return None
