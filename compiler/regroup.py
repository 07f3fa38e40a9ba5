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
"""

from __future__ import annotations

from typing import Sequence

from .gluing import Graph, Slot
from .pruning import TurnAnalysis

Pair = tuple[int, Slot, int, Slot]      # block, its open slot, block, its open slot


def regroup(turns: TurnAnalysis, blocks: Sequence[Graph]) -> tuple[list[int], list[Pair]] | None:
    """The live blocks and the forced pairs between them, or None when no pair is forced."""
    dead_moves = set(turns.dead)
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
    if not pairs:
        return None     # dead blocks alone: the turning analysis knows them already
    return [u for u in range(len(blocks)) if u not in dead], pairs


def _live(turns: TurnAnalysis, u: int, k: int, dead_moves: set[int],
          dead: set[int]) -> list[tuple[int, int]]:
    """The (block, open slot) ends of the live edges from open slot k of block u."""
    out = []
    for m in turns.leaving.get((u, k), ()):
        q, j = turns.moves[m][2:]
        if m not in dead_moves and q not in dead:
            out.append((q, j))
    return out
