"""Algorithm 2: find simpler graphs whose boundaries, spliced together, equal a given boundary.

Boundaries are in the gap form of grammar_lang.boundary, over tokens: (half-edge token, net
turns after it). A piece R matches part of a
target T when its half-edges map in cyclic order onto some of T's half-edges with equal tokens,
and the net turns of T between two consecutive matched half-edges equal R's gap there. Each
run of unmatched half-edges between them is a closed substring of its own, found recursively:
its inner turns are T's, and its closing gap is whatever makes it wind once (P − N = 1). That is
the paper's `∨ⁿ ∂L ∧ⁿ` freedom: a splice `A|B → A∧ⁿB∨ⁿ⁺¹` may put any number of turns on either
side of the spliced-in substring, so only the total between matched half-edges is constrained.

This is matching of boundary strings; matching a rule side in a graph is
grammar_lang.algorithms.matching.
"""

from __future__ import annotations

import bisect
from collections import Counter
from dataclasses import dataclass, field

from grammar_lang import boundary as bd


@dataclass(frozen=True)
class Piece:
    """A graph usable on the simpler side: a hierarchy graph (`node` ≥ 0) or an edge graph
    (`node` = -1 - label). `rank` orders by complexity: (half-edges, insertion order)."""

    node: int
    gaps: bd.Gaps
    rank: tuple[int, int]
    counts: tuple[tuple[int, int], ...] = field(compare=False, default=())


Match = tuple[tuple[Piece, tuple[int, ...]], ...]   # piece, target index of each of its half-edges


class Matcher:
    """The pieces of the current hierarchy, indexed for Algorithm 2."""

    def __init__(self, splice: bool, budget: int = 4000):
        self.splice = splice          # False: no rule may splice several graphs (Appendix A)
        self.budget = budget
        self.pieces: dict[int, Piece] = {}
        # Pieces by their gaps in sorted order: any rotation of a target's string has the
        # same, and sorting is cheaper than finding its least rotation.
        self.by_gaps: dict[bd.Gaps, list[int]] = {}
        # Pieces grouped by their multiset of tokens: far fewer groups than pieces, and a
        # group fits a target or not as a whole.
        self.by_counts: dict[tuple[tuple[int, int], ...], list[int]] = {}
        # Each group under its smallest token, with its number of half-edges and the bit set
        # of its tokens: a target can only use groups whose tokens it has, so a search looks
        # only under its own tokens, and most groups fail on the bit sets alone.
        self.by_least: dict[int | None, list[tuple[tuple[tuple[int, int], ...], int, int]]] = {}
        self._cands: dict[tuple, tuple[int, list[Piece]]] = {}
        self.version = 0
        self._memo: dict[bd.Gaps, tuple[int, Match | None]] = {}
        self._targets: dict[bd.Gaps, _Target] = {}
        self._steps = 0

    def add(self, piece: Piece) -> None:
        c = Counter(t for t, _ in piece.gaps)
        piece = Piece(piece.node, piece.gaps, piece.rank, tuple(sorted(c.items())))
        self.pieces[piece.node] = piece
        self.by_gaps.setdefault(tuple(sorted(piece.gaps)), []).append(piece.node)
        if piece.counts not in self.by_counts:
            least = piece.counts[0][0] if piece.counts else None
            self.by_least.setdefault(least, []).append(
                (piece.counts, sum(n for _, n in piece.counts), _bits(c)))
        self.by_counts.setdefault(piece.counts, []).append(piece.node)
        self.version += 1

    def remove(self, node: int) -> None:
        # Lists keep the id; lookups skip ids no longer in `pieces`.
        self.pieces.pop(node, None)

    # --- the search ----------------------------------------------------------------------

    def find(self, target: bd.Gaps, rank: tuple[int, int]) -> Match | None:
        """A way to build `target` from pieces simpler than `rank`, or None."""
        for node in self.by_gaps.get(tuple(sorted(target)), ()):
            p = self.pieces.get(node)
            if p is not None and p.rank < rank:
                pos = _align_whole(p.gaps, target)
                if pos is not None:
                    return ((p, pos),)
        if not self.splice or len(target) < 2:
            return None
        self._steps = 0
        try:
            return self._solve(target, len(target) - 1)
        except _OutOfBudget:
            return None

    def _solve(self, target: bd.Gaps, max_half: int) -> Match | None:
        hit = self._memo.get((target, max_half))
        if hit is not None and (hit[1] is not None or hit[0] == self.version):
            return hit[1]
        self._steps += 1
        if self._steps > self.budget:
            raise _OutOfBudget
        res = self._search(target, max_half)
        self._memo[(target, max_half)] = (self.version, res)
        return res

    def _target(self, target: bd.Gaps) -> _Target:
        """The target prepared for searching; the same ones come back with every new piece."""
        tg = self._targets.get(target)
        if tg is None:
            tg = self._targets[target] = _Target(target)
        return tg

    def _candidates(self, tg: _Target, max_half: int) -> list[Piece]:
        key = (tg.counts, max_half)
        hit = self._cands.get(key)
        if hit is not None and hit[0] == self.version:
            return [p for p in hit[1] if p.node in self.pieces]
        out = []
        have = tg.have
        for least in (None, *have):
            for counts, size, need in self.by_least.get(least, ()):
                if size <= max_half and not need & ~tg.bits and all(
                        have[t] >= n for t, n in counts):
                    out.extend(self.pieces[i] for i in self.by_counts[counts]
                               if i in self.pieces)
        out.sort(key=lambda p: (-len(p.gaps), p.rank))    # a total order: ranks are unique
        self._cands[key] = (self.version, out)
        return out

    def _search(self, target: bd.Gaps, max_half: int) -> Match | None:
        m = len(target)
        tg = self._target(target)
        # Some piece holds target[0]; any piece of a splice may be taken as the outer one
        # (each closing gap, 1 − inner turns, is exactly the target's turns around the rest),
        # so only placements covering position 0 need trying.
        first = target[0][0]
        for piece in self._candidates(tg, min(max_half, m)):
            p = len(piece.gaps)
            for j0 in range(p):
                if piece.gaps[j0][0] != first:
                    continue
                r = piece.gaps[j0:] + piece.gaps[:j0]
                for pos in _placements(r, tg):
                    self._steps += 1
                    if self._steps > self.budget:
                        raise _OutOfBudget
                    rest = self._fill(target, pos, p)
                    if rest is not None:
                        own = tuple(pos[(q - j0) % p] for q in range(p))
                        return ((piece, own),) + rest
        return None

    def _fill(self, target: bd.Gaps, pos: tuple[int, ...], p: int) -> Match | None:
        m = len(target)
        out: Match = ()
        for j in range(p):
            a, b = pos[j], pos[(j + 1) % p]
            idx = [(a + d) % m for d in range(1, ((b - a) % m) or (m if p == 1 else 0))]
            if not idx:
                continue
            inner = [target[k][1] for k in idx[:-1]]
            sub = tuple((target[k][0], target[k][1]) for k in idx[:-1])
            sub += ((target[idx[-1]][0], 1 - sum(inner)),)
            found = self._solve(sub, len(sub))
            if found is None:
                return None
            out += tuple((pc, tuple(idx[q] for q in ps)) for pc, ps in found)
        return out


def _bits(tokens) -> int:
    """The set of (non-negative) tokens as the bits of an int."""
    out = 0
    for t in tokens:
        out |= 1 << t
    return out


class _OutOfBudget(Exception):
    pass


class _Target:
    """A target boundary prepared for searches: its tokens counted (which pieces can fit at
    all) and its half-edges indexed for placing pieces. `prefix[k]` is the net turns before
    target[k] (from target[0] on), and `at[(token, prefix[k])]` the positions k in order, so
    the next half-edge of a piece, a given number of turns after the last placed one, is
    looked up rather than searched for."""

    def __init__(self, target: bd.Gaps):
        self.have = Counter(t for t, _ in target)
        self.counts = tuple(sorted(self.have.items()))
        self.bits = _bits(self.have)
        self.prefix = [0]
        self.at: dict[tuple[int, int], list[int]] = {}
        for k, (t, n) in enumerate(target):
            self.at.setdefault((t, self.prefix[-1]), []).append(k)
            self.prefix.append(self.prefix[-1] + n)


def _placements(r: bd.Gaps, tg: _Target):
    """Increasing placements of r's half-edges in the target, r[0] at position 0, each next
    one the piece's gap of turns after the last."""
    prefix, p = tg.prefix, len(r)
    m = len(prefix) - 1
    pos = [0]

    def rec(j: int):
        last = pos[-1]
        if j == p:
            if prefix[m] - prefix[last] == r[-1][1] if p > 1 else r[0][1] == 1:
                yield tuple(pos)
            return
        ks = tg.at.get((r[j][0], prefix[last] + r[j - 1][1]), ())
        for k in ks[bisect.bisect_right(ks, last):]:
            if k > m - (p - j):     # the rest of r would not fit after k
                break
            pos.append(k)
            yield from rec(j + 1)
            pos.pop()

    yield from rec(1)


def _align_whole(r: bd.Gaps, target: bd.Gaps) -> tuple[int, ...] | None:
    m = len(target)
    for k in range(m):
        if all(target[(k + j) % m] == r[j] for j in range(m)):
            return tuple((k + j) % m for j in range(m))
    return None
