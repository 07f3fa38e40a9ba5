"""DPO application: gluing a rule's replacement side into the hole its matched side leaves.

The i-th open slot of the two sides is the same interface point (grammar_lang.rules). Cutting
the matched side out leaves, outside each interface point k, its context: nothing (the slot was
open), a host slot, or another interface point k' (a host edge between two open slots of the
match). Inside it lies the replacement's end: a slot of a new vertex, or one end of a bare wire
whose other end is another interface point. Each maximal chain context–inside–context–… is
glued end to end; a chain with one end only leaves that slot open; a chain with none (a bare
loop) vanishes. Written once for the compiler's verifier (compiler.apply) and the runtime's
rewriting (runtime.engine.rewrite); how contexts are found (the dangling condition, SPO, wires of the
matched side) and how the gluing is applied (the runtime's undo journal and geometry) stay with
each caller.
"""

from __future__ import annotations

from typing import Sequence

Slot = tuple[int, int]
Context = Slot | int | None     # a host slot, another interface point, or open


def join_interface(contexts: Sequence[Context], ends: Sequence[Slot]
                   ) -> tuple[list[tuple[Slot, Slot]], list[Slot]]:
    """The slot pairs to glue and the slots left open, given each interface point's context
    and its end in the replacement (a wire's ends are (-1 - wire, 0 or 1)). Order: the chains
    from the replacement's slots in interface order, then those from wires, by wire number."""
    wire_at: dict[int, list[int]] = {}
    for k, (v, end) in enumerate(ends):
        if v < 0:
            wire_at.setdefault(-1 - v, [-1, -1])[end] = k

    def across(k: int, out: bool) -> Context:
        if out:
            return contexts[k]
        v, end = ends[k]
        return ends[k] if v >= 0 else wire_at[-1 - v][1 - end]

    seen: set[int] = set()

    def walk(k: int, out: bool) -> Slot | None:
        """The far end of the chain leaving interface point k outwards (or inwards)."""
        while True:
            seen.add(k)
            x = across(k, out)
            if x is None or isinstance(x, tuple):
                return x
            k, out = x, not out

    glue: list[tuple[Slot, Slot]] = []
    opened: list[Slot] = []

    def chain(start: Slot, k: int, out: bool) -> None:
        far = walk(k, out)
        if far is None:
            opened.append(start)
        else:
            glue.append((start, far))

    for k, end in enumerate(ends):
        if end[0] >= 0 and k not in seen:
            chain(end, k, True)
    for w in sorted(wire_at):
        for k in wire_at[w]:
            if k not in seen and isinstance(contexts[k], tuple):
                chain(contexts[k], k, False)
    return glue, opened
