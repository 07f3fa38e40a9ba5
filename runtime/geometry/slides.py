"""Slides: room made by moving a whole part of the drawing at once, along one direction.

When a round's samples fail because an edge cannot reach its length (a wall top too short for
the tower a rule stands on it, a stretch of ground too short for a castle's structure), the
room it needs is often further along the line: in a drawing of straight lines a vertex freed
alone is still held by its other edges, and freeing the nearest ones layer by layer (Solver
._nearest_held) runs out of rounds before it frees what has to move.

A slide takes everything beyond the edge's held end, along the edge's direction d, and moves
it as one rigid unit: a single free position in the system (its anchor, the held end), the
others following at fixed offsets. The part is closed under every edge that a translation
along d would bend or stretch wrongly, so that only edges parallel to d and of free length
join it to the rest of the drawing: moving it along d changes their lengths and nothing else.
Such an edge is left out of the part (a seam, where the drawing stretches or gives way) when
its other end lies on the near side of a cut through the held end, across d, or cannot move
(a pinned corner, a vertex on a side of the frame not parallel to d), and when its class lets
it take the length the failed edge lacked; otherwise its other end joins the part (where
that reaches a vertex that cannot move, or grows past `limit` vertices, and no part is found,
the search is made again with seams further beyond as well: FAR below). No slide is a part
that would need the failed edge's other end (or an old vertex on the near side that the new
part hangs from), a vertex that cannot move, or more than `limit` vertices, nor one without a
seam: held by the new part alone, it is a whole structure, and sliding it would only move it.
The projection charges the anchor as if each vertex of the part moved alone, and repairs the
round's samples (Solver._repairing), since the seams are kept lengths, soft in the projection.

On the paper's castle at its N (seeds 0-7) the drawings cover 53 % of the frame, against 42 %
without slides: its towers rise in tiers. The flowers, the village and the station draw
about as many vertices and cover about as much (docs/runtime.md has the table).
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import Enum
from typing import Callable

from .change import HostView
from .spatial import Point

# Above this many vertices a part is not slid. Parts up to 160 drew the paper's castle a
# little fuller (55 % of its frame covered, seeds 0-3, against 52 % at 40), but moved
# whole columns of the space station, whose trusses then shrank (34 % covered against 38 %),
# and took the station 9.0 s at its N against 6.9 s.
LIMIT = 40
# FAR: where no part is found and a search reached a vertex that cannot move (a village's
# surface runs from one side of the frame to the other, with its houses on it), a stretch
# further beyond may be a seam as well, and shrink by what the failed edge lacked: the part
# is then what lies between the cut and the nearest stretches that can give the room (a
# house and the stretch beyond it). Tried first everywhere, it drew the castle's towers lower
# (44 % of its frame covered against 50 %, seeds 0-4 at the paper's N), and as the fallback
# for every failed search, the station smaller (34 % against 41 %): docs/runtime.md.
# Since 2026-12-07 also where the part grew past LIMIT (a castle's row of structures joined
# along the ground): a structure is pushed along into the stretch beyond it instead. Over
# seeds 0-4 at the paper's N the castle drew 282 vertices and covered 57 % of its frame
# (260 and 48 % before), as a few wide castles with towers on them instead of a row of
# narrow ones; the flowers 270 vertices (260); the station 122 (130; 112 against 120 over
# seeds 0-9), whose trusses then take room from each other; the village 99 (100).
# Two directions closer than this (sine of the angle between them) are parallel.
PARALLEL = 1e-6


class NoPart(Enum):
    HELD = "a vertex that cannot move"      # pinned, or on a frame side across d
    LARGE = "too large"                       # more than `limit` vertices
    OTHER = "no part"                         # an end that must stay, no seam


@dataclass(frozen=True)
class Slide:
    anchor: int
    offsets: dict[int, Point]                 # member (anchor aside) → its place − anchor's
    edges: tuple[tuple[int, int], ...]        # the part's own edges, anchor included
    box: tuple[float, float, float, float] | None   # its vertices off the frame's sides


def sliding_part(host: HostView, adjacency: Callable, prim: Callable[[int], int],
                 bounds: Callable, held: int, others: set[int], d: Point, sign: int,
                 need: float, free: set[int], limit: int = LIMIT,
                 far: bool = False) -> Slide | NoPart:
    """The part of the drawing that slides with `held` along ±d (`sign`: which way is
    beyond it) to make the failed edge `need` longer (negative: shorter), or why none does.
    `adjacency(v)` lists (slot, (w, slot)) after the change; `bounds(v, slot, w, slot)` an
    existing edge's range and length; `others`: the failed edge's other end and the old
    vertices the free ones hang from, of which those on the near side must stay (a part that
    took them along would move both sides of the gap); `free`: the vertices the system moves
    already (new ones among them), whose edges it holds. `far`: a stretch further beyond
    may be a seam too, and shrink (see FAR)."""
    if not _movable(host, held, d):
        return NoPart.HELD
    t, pos = host.t, host.pos
    tol = 1e-6 * t.unit
    h0 = pos[held]
    ux, uy = sign * d[0], sign * d[1]
    part, todo = {held}, [held]
    # (The failed edge's other end may be new, with no place yet: free, it is never reached.)
    stay = {v for v in others if v not in free
            and (pos[v][0] - h0[0]) * ux + (pos[v][1] - h0[1]) * uy < -tol}
    while todo:
        x = todo.pop()
        px = prim(x)
        for i, (y, j) in adjacency(x):
            if y in free:
                continue
            if y in part:
                continue
            dx = t.direction[px][i]
            stretches = t.lengths[t.label[px][i]][2] is None \
                and abs(dx[0] * d[1] - dx[1] * d[0]) < PARALLEL
            py = pos[y]
            movable = _movable(host, y, d)
            if stretches and (far or not movable
                              or (py[0] - h0[0]) * ux + (py[1] - h0[1]) * uy < -tol):
                # The seam, if the edge can give the room: it grows by `need` when x lies
                # beyond y, and shrinks by it otherwise. One that cannot (a connector's top
                # across the cut) is taken into the part whole, or it would break.
                lo, hi, now = bounds(x, i, y, j)
                px0 = pos[x]
                grow = need if (px0[0] - py[0]) * ux + (px0[1] - py[1]) * uy > 0 else -need
                if lo <= now + grow <= hi:
                    continue
            if not movable:
                return NoPart.HELD
            if y in stay:
                return NoPart.OTHER
            if len(part) >= limit:
                return NoPart.LARGE
            part.add(y)
            todo.append(y)
    # Read off the part once it is whole: an edge taken for a seam when first met may join
    # two members in the end (a wall top reached again from its other end), and is then the
    # part's own, to be tested for crossings where it goes, and no seam.
    edges, seams = [], 0
    for x in sorted(part):
        for i, (y, j) in adjacency(x):
            if y in part:
                if (x, i) < (y, j):
                    edges.append((x, y))
            elif y not in free:
                seams += 1
    if len(part) < 2 or not seams:
        # Held by nothing but the new part, the part is a whole structure: sliding it would
        # only move it, not make room (a floating station moved aside for its own truss).
        return NoPart.OTHER
    offsets = {v: (pos[v][0] - h0[0], pos[v][1] - h0[1]) for v in sorted(part) if v != held}
    inner = [pos[v] for v in part if host.prim[v] not in host.on_border]
    box = (min(p[0] for p in inner), min(p[1] for p in inner),
           max(p[0] for p in inner), max(p[1] for p in inner)) if inner else None
    return Slide(held, offsets, tuple(edges), box)


def _movable(host: HostView, v: int, d: Point) -> bool:
    """Whether `v` may move along d: not pinned, and when it lies on a side of the frame, that
    side runs along d (a foot slides along the ground, a strip line's end does not leave the
    frame's side)."""
    if v in host.pinned:
        return False
    if host.prim[v] not in host.on_border:
        return True
    t = host.t
    p = host.prim[v]
    for i, s in enumerate(host.link[v]):
        if s is not None and t.label[p][i] in host.side_labels:
            dx = t.direction[p][i]
            if abs(dx[0] * d[1] - dx[1] * d[0]) >= PARALLEL:
                return False
    return True
