"""Blocks regrouped by the rules found so far (companion §3.3 again, over the live blocks).

A rule whose left side is a whole block, or two blocks joined by one edge, tells the turning
analysis that an irreducible graph holds no such block or edge (pruning.TurnAnalysis.dead). That
can leave an open slot of a block with no edge left at all: every complete graph holding the
block is reducible, so the block is dead too, and so are the edges into it. What is left may
pair slots off anew: a slot whose only live edge goes to a slot of another block, whose only
live edge comes back, is forced, just as between primitives. So every complete graph that no
rule found so far reduces is glued from the live blocks with those pairs glued: the hierarchy
can start again from them (merged as `grouping.merge` does, forced cycles closed), keeping the
rules found so far. The space station's module is the example: once its blocks with rigid trims
are reduced, its left, right and lower corners pair off into one block, and the rule that adds a
module under a connector is a few gluings away instead of six.

When no slot pair is forced, a face may be: the only face a complete graph can close through
some gap of a unit is one ring of units (faces.py), which then becomes one block. The station's
closed top and connector each come with the module body below them so.
"""

from __future__ import annotations

from typing import Sequence

from .faces import face_units, faces_through
from .gluing import Graph, Slot
from .pruning import TurnAnalysis

Pair = tuple[int, Slot, int, Slot]      # part, its open slot, part, its open slot


def regroup(turns: TurnAnalysis, blocks: Sequence[Graph], faces: bool = True
            ) -> tuple[list[int], list[Pair], bool] | None:
    """The parts to merge (blocks, a block once per instance it is merged as), the forced
    pairs between them (by part) and whether faces forced them, or None when nothing is
    forced: forced pairs of slots if there are any, else (with `faces`) forced faces."""
    dead_moves = set(turns.dead)
    dead = _dead_blocks(turns, dead_moves)
    pairs = []
    for u, ring in enumerate(turns.rings):
        if u in dead:
            continue
        for k in range(len(ring)):
            ends = _live(turns, u, k, dead_moves, dead)
            if len(ends) != 1:
                continue
            q, j = ends[0]
            if q > u and _live(turns, q, j, dead_moves, dead) == [(u, k)]:
                pairs.append((u, blocks[u].gaps[k][0], q, blocks[q].gaps[j][0]))
    live = [u for u in range(len(blocks)) if u not in dead]
    if pairs:
        at = {u: n for n, u in enumerate(live)}
        return live, [(at[p], s, at[q], t) for p, s, q, t in pairs], False
    # Dead blocks alone: the turning analysis knows them already.
    found = _forced_faces(turns, blocks, live) if faces else None
    return None if found is None else (*found, True)


def _dead_blocks(turns: TurnAnalysis, dead_moves: set[int]) -> set[int]:
    """Blocks with an open slot that no live move leaves from, and so on."""
    dead: set[int] = set()
    changed = True
    while changed:
        changed = False
        for u, ring in enumerate(turns.rings):
            if u in dead:
                continue
            if any(not _live(turns, u, k, dead_moves, dead) for k in range(len(ring))):
                dead.add(u)
                changed = True
    return dead


def _forced_faces(turns: TurnAnalysis, blocks: Sequence[Graph],
                  live: list[int]) -> tuple[list[int], list[Pair]] | None:
    """Gaps through which a complete graph can close only one face, a ring of distinct units:
    every instance of the unit comes with that ring glued round it, so the ring is one block
    (faces.py). A unit stays a block of its own unless each of its instances is in such a
    ring; it is then in exactly one when all the rings that hold it pass the same gap of it
    (an instance has one face through each gap). Else nothing is merged."""
    if not live:
        return None
    turns.solve()
    alive = set(live)

    listed: dict[tuple[int, int], list | None] = {}

    def faces(u: int, k: int) -> list[tuple[int, ...]] | None:
        """The faces through the gap, but for those through dead blocks (no such face);
        each gap searched once (the claims below ask again for gaps listed already)."""
        if (u, k) not in listed:
            walks = faces_through(turns, u, k)
            listed[u, k] = None if walks is None else \
                [w for w in walks if alive.issuperset(face_units(turns, w))]
        return listed[u, k]

    forced: dict[tuple, tuple[int, ...]] = {}
    for u in live:
        for k in range(len(turns.rings[u])):
            walks = faces(u, k)
            if walks and len(walks) == 1 and len(walks[0]) > 1 and \
                    len(set(face_units(turns, walks[0]))) == len(walks[0]):
                forced.setdefault(_rotation_key(walks[0]), walks[0])
    if not forced:
        return None
    gap_of: dict[int, set[int]] = {}
    for w in forced.values():
        for m in w:
            gap_of.setdefault(turns.moves[m][2], set()).add(turns.moves[m][3])
    if any(len(g) > 1 for g in gap_of.values()):
        return None
    claimed = set()
    for u, gaps in gap_of.items():
        walks = faces(u, next(iter(gaps)))
        if walks is not None and all(_rotation_key(w) in forced for w in walks):
            claimed.add(u)
    parts = [u for u in live if u not in claimed]
    if len(parts) + len(forced) >= len(live):
        return None     # a restart costs the graphs met so far: only for fewer blocks
    pairs = []
    for key in sorted(forced):
        w = forced[key]
        base = len(parts)
        units = face_units(turns, w)
        parts.extend(units)
        at = {u: base + n for n, u in enumerate(units)}
        for m in w:
            p, i, q, j = turns.moves[m]
            pairs.append((at[p], blocks[p].gaps[i][0], at[q], blocks[q].gaps[j][0]))
    return parts, pairs


def _rotation_key(walk: tuple[int, ...]) -> tuple[int, ...]:
    """One face walk, whichever gap it was listed from."""
    return min(walk[n:] + walk[:n] for n in range(len(walk)))


def _live(turns: TurnAnalysis, u: int, k: int, dead_moves: set[int],
          dead: set[int]) -> list[tuple[int, int]]:
    """The (block, open slot) ends of the live edges from open slot k of block u."""
    out = []
    for m in turns.leaving.get((u, k), ()):
        q, j = turns.moves[m][2:]
        if m not in dead_moves and q not in dead:
            out.append((q, j))
    return out
