"""Whether a move's late rounds pay: a proposal's rounds after two in a row had no room.

A round ends when its part has no room while only its free vertices move (crowded at one size,
too short at the next smaller; see Solver.placements), and the next round frees more old
vertices. When two rounds in a row ended that way, freeing more rarely makes room on the
simple grammars: curl at 20,000 vertices placed 10 of 157 such proposals later, for 30 % of
the samples of the window, where a fresh proposal places for about 8 samples. On others it
does: the castle scene's r3 placed 6 of 10. So each move keeps its own record, counted as the
run goes (deterministic: counts, never time), and its late rounds are skipped only once they
have been tried TRIAL times and placed in fewer than PAYS of them; one in PROBE of the later
asks still goes on, so that the record follows the drawing as it changes.
"""

from __future__ import annotations

TRIAL = 20
PAYS = 0.1
PROBE = 10


class LateRounds:
    def __init__(self) -> None:
        # (rule name, forward) → [late rounds tried, placed by them, asked once tried]
        self.record: dict[tuple[str, bool], list[int]] = {}

    def go_on(self, key: tuple[str, bool]) -> bool:
        """Whether the proposal of move `key` that has just had two rounds with no room goes
        on with its further rounds (then `placed` is told if they place it)."""
        rec = self.record.setdefault(key, [0, 0, 0])
        tried, placed, asked = rec
        if tried >= TRIAL and placed < PAYS * tried:
            rec[2] += 1
            if asked % PROBE:
                return False
        rec[0] += 1
        return True

    def placed(self, key: tuple[str, bool]) -> None:
        self.record[key][1] += 1
