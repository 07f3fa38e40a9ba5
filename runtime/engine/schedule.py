"""Which rule to try next: priorities, weights and step limits (Pogrzebacz & Ilčík §3.1).

Each step looks at the priority levels in ascending order (a lower value runs first) and uses
the first level that (a) has not reached its own step limit and (b) has a rule with a match.
Within that level a move (a rule in one direction) is drawn with probability proportional to
its weight; if it has no match it is set aside for this step and another is drawn, so a level
is passed over only when none of its moves applies (moves needing a primitive the drawing
lacks are skipped at once). To keep a step's cost independent of the drawing's size, the draw
is made twice: first each move is tried at a few random anchors only, and only when all moves
fail that way are they searched exhaustively. A level that has been passed over is looked at
again on the next step, since later rewrites can make it applicable again. Generation ends
when the global limit of applied steps is reached or no level applies (a terminal drawing).

Merrell's grammars use every rule in both directions with no preference (paper §6.1): each
direction is a move with the rule's weight. Grammars written in SPO mode are hand-written
productions and only run forward (lhs → rhs) unless asked otherwise; there a starter rule
creates its component (it runs ∅ → lhs) and never deletes one.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Callable

import numpy as np

from grammar_lang.rules import Grammar

from .host import Host
from .matching import Match, find_match
from .rewrite import DirectedRule


# Random anchors tried per move in the cheap first pass.
PROBES = 8


@dataclass(frozen=True)
class Level:
    priority: int
    moves: tuple[DirectedRule, ...]
    weights: tuple[float, ...]
    limit: int | None = None
    requires: np.ndarray | None = None     # move × primitive: the pattern uses that primitive

    @functools.cached_property
    def inverse_weights(self) -> np.ndarray:
        return 1.0 / np.asarray(self.weights, dtype=float)

    @functools.cached_property
    def _allowed(self) -> dict:
        return {}

    def allowed(self, absent: tuple[int, ...]) -> list[int]:
        """The moves whose pattern needs no primitive of `absent` (host primitives with no
        vertex, Host.absent), in move order; kept per set of absent primitives, which rarely
        changes."""
        ks = self._allowed.get(absent)
        if ks is None:
            blocked = self.requires[:, list(absent)].any(axis=1).tolist()
            ks = self._allowed[absent] = [k for k in range(len(self.moves)) if not blocked[k]]
        return ks


@dataclass(frozen=True)
class Schedule:
    levels: tuple[Level, ...]
    spo: bool
    # With `connected` (Appendix A): the starters, applied once at the start instead of as
    # moves, so that the drawing is one structure (plus the frame it stands in).
    opening: tuple[tuple[DirectedRule, float], ...] = ()
    # With `connected` or in a frame: the moves, as (rule name, forward), whose side could
    # cut the drawing in two (`_splits`); the engine tests each such step on the drawing
    # (Engine._cuts) and refuses the ones that do.
    guarded: frozenset[tuple[str, bool]] = frozenset()

    @staticmethod
    def build(grammar: Grammar, bidirectional: bool | None = None,
              limits: dict[int, int] | None = None) -> "Schedule":
        spo = grammar.header.mode == "spo"
        both = (not spo) if bidirectional is None else bidirectional
        rings = grammar.rings
        connected = grammar.header.options.connected
        # In a frame, structures stand on it: no step may cut a part off to float in the
        # space (a roof lifted off its tower), though a starter may still make a part the
        # example has free-standing (a window). Whether a step cuts is a question about the
        # drawing, not the rule: taking the village's notch out of a strip line leaves two
        # pieces of line, each still held by the frame. Left out as rules, such moves could
        # never clear a strip for a new one, and the village stalled after 16 steps.
        whole = connected or grammar.header.frame is not None
        by_level: dict[int, list[tuple[DirectedRule, float]]] = {}
        opening, guarded = [], set()
        for rule in grammar.rules:
            if rule.weight <= 0:
                continue
            if connected and rule.is_starter:
                opening.append((DirectedRule.build(rule, False, rings), float(rule.weight)))
                continue
            # Forward only, a starter is used to create its component (rhs ∅ → lhs).
            dirs = (True, False) if both else ((False,) if rule.is_starter else (True,))
            for fwd in dirs:
                if whole and not rule.is_starter and _splits(rule, fwd):
                    guarded.add((rule.name, fwd))
                by_level.setdefault(rule.priority, []).append(
                    (DirectedRule.build(rule, fwd, rings), float(rule.weight)))
        limits = limits or {}
        levels = []
        for p in sorted(by_level):
            moves = tuple(m for m, _ in by_level[p])
            req = np.zeros((len(moves), len(rings)), dtype=bool)
            for k, m in enumerate(moves):
                req[k, list(m.pattern.side.vertices)] = True
            levels.append(Level(p, moves, tuple(w for _, w in by_level[p]), limits.get(p), req))
        levels = tuple(levels)
        return Schedule(levels, spo, tuple(opening), frozenset(guarded))

    def opening_move(self, rng: np.random.Generator) -> DirectedRule | None:
        """One starter, drawn by weight, for a connected grammar's first step."""
        if not self.opening:
            return None
        w = np.asarray([w for _, w in self.opening], dtype=float)
        return self.opening[int(rng.choice(len(w), p=w / w.sum()))][0]

    def moves(self) -> list[DirectedRule]:
        return [m for lv in self.levels for m in lv.moves]

    def choose(self, host: Host, rng: np.random.Generator, applied: dict[int, int],
               screen: Callable[[DirectedRule], bool] | None = None,
               ) -> tuple[Level, DirectedRule, Match, bool] | None:
        """The level, move and match for the next step, or None when nothing applies; the flag
        says the move was refused by `screen` (the cost's coin, tossed before any search).

        A screened-out move is set aside without a search, and moves are screened one at a
        time, in draw order, only until one passes and matches: a step with many rules pays for
        the coins it needs, not one per rule. Only when no other move of the level applies are
        the set-aside ones searched, and then the first with a match is returned flagged as
        refused: so a level is still passed over only when none of its moves applies, and the
        cost's refusals no longer pay for a match search each.
        """
        for level in self.levels:
            if level.limit is not None and applied.get(level.priority, 0) >= level.limit:
                continue
            kept: list[int] = []
            refused: list[int] = []
            # First cheap probes (a few random anchors per move), then exact searches, so a
            # step costs O(moves) and a level is still only passed over when nothing applies.
            for k in self._order(level, host, rng):
                move = level.moves[k]
                if screen is not None and not screen(move):
                    refused.append(k)
                    continue
                kept.append(k)
                match = find_match(host, move.pattern, rng, self.spo, PROBES)
                if match is not None:
                    return level, move, match, False
            found = self._draw(level, kept, host, rng, None)
            if found is not None:
                return level, found[0], found[1], False
            for probes in (PROBES, None):
                found = self._draw(level, refused, host, rng, probes)
                if found is not None:
                    return level, found[0], found[1], True
        return None

    @staticmethod
    def _order(level: Level, host: Host, rng: np.random.Generator) -> list[int]:
        # Weighted sampling without replacement in one go: sorting by u^(1/w) draws the same
        # order as repeated weighted draws (Efraimidis & Spirakis). Moves needing a primitive
        # the host does not have are left out without a search.
        # Sorted in Python: a level holds a few dozen moves, and Python's sort is stable as
        # numpy's "stable" argsort of -keys is, so ties keep the move order either way.
        keys = (rng.random(len(level.weights)) ** level.inverse_weights).tolist()
        return sorted(level.allowed(host.absent), key=keys.__getitem__, reverse=True)

    def _draw(self, level: Level, ks: list[int], host: Host, rng: np.random.Generator,
              probes: int | None):
        for k in ks:
            match = find_match(host, level.moves[k].pattern, rng, self.spo, probes)
            if match is not None:
                return level.moves[k], match
        return None


def _splits(rule, forward: bool) -> bool:
    """Whether the side a move produces has more pieces than the side it replaces: such a
    move could cut a connected drawing in two. A piece is a connected group of vertices, or a
    wire (a bare edge, which joins the two things it is glued to)."""
    made, matched = (rule.rhs, rule.lhs) if forward else (rule.lhs, rule.rhs)
    return len(made.components()) + len(made.wires) > \
        len(matched.components()) + len(matched.wires)

