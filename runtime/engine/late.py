"""Whether a move's late rounds pay: the rounds of a proposal after its first.

A proposal's first round moves only the new part; when none of its samples places, the
next rounds free old vertices around it (Solver.placements). Those rounds pay very
differently from move to move. On the paper's castle at its N (seed 80) they took 58,000 of
the run's 83,000 samples for 73 placements: the three `stand` moves taken backwards drew
13,700 of them and placed none, while `r0` backwards placed once per 57 and `r24` once per 35,
where the run as a whole placed once per 285 samples. On h-complex they placed once per 15 to
once per 130 samples, against once per 7 for the run.

So each move keeps a record of its late rounds, counted as the run goes (deterministic:
counts, never time): the samples they drew and how often they placed. They go on while
they may place at least 1/WORSE as often per sample as the run does as a whole, reading the
record as if it held PRIOR more placements: a move is given up on only once it has drawn
enough to be sure (at the castle's 1 in 285, about 3,400 samples without a placement), not
after a short bad run; otherwise one ask in PROBE still goes on, so that the record follows
the drawing as it changes. A proposal given up there leaves its iteration to a fresh
proposal, which on average places sooner. Moves that place rarely but build what a scene's
rare parts stand on keep their late rounds this way: with a plain trial of 100 samples
instead of the prior, the castle's `r15` (a slope beside a block, 1 placement in 217 late
samples) was cut off before its first placement, and the castle lacked its keep at three
seeds of 0-4 (at two with WORSE = 16); with the prior and WORSE = 2, at one.

The record is not asked when the change lowers the cost's proportions (Engine._wanted): a
part under its share is often one that is hard to place (a castle's gates), and without
that the castle scene's gates fell to 0.77 of their share (mean over seeds 0-11; 0.90
before the record, 0.89 with it and the exemption). Over castle seeds 0-39 at the paper's N,
one drawing lacks a face label both before the record (seed 13) and with it (seed 0).
"""

from __future__ import annotations

PRIOR = 3
WORSE = 4
PROBE = 10


class LateRounds:
    def __init__(self) -> None:
        # (rule name, forward) → [late samples, placed by late rounds, asks refused so far]
        self.record: dict[tuple[str, bool], list[int]] = {}
        self.samples = self.placed = 0        # the run's, every round

    def go_on(self, key: tuple[str, bool]) -> bool:
        """Whether the proposal of move `key` whose first round did not place goes on with
        its further rounds (then `spent` is told what they drew and whether they placed)."""
        rec = self.record.setdefault(key, [0, 0, 0])
        drawn, placed, _ = rec
        if WORSE * (placed + PRIOR) * self.samples < drawn * self.placed:
            rec[2] += 1
            return rec[2] % PROBE == 1
        return True

    def spent(self, key: tuple[str, bool] | None, samples: int, late: int,
              placed: bool) -> None:
        """A proposal's end: `samples` drawn in all, `late` of them in the rounds after the
        first (for move `key`, which was asked and went on), and whether it placed."""
        self.samples += samples
        self.placed += placed
        if key is not None and late:
            rec = self.record.setdefault(key, [0, 0, 0])
            rec[0] += late
            rec[1] += placed
