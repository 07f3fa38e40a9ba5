"""Why a proposal was not applied: one name for each reason, counted in a run's summary.

It sits in geometry, the lower layer, because most reasons are the solver's (a placement that
breaks a length, crosses an edge, leaves the frame); the engine, which adds its own (the cost,
the dangling condition), imports it from here.

A `str` enum, so a reason prints, sorts, compares and hashes as its text ("edge length"),
which is what the summary, the REPL and scripts reading them see.
"""

from __future__ import annotations

from enum import Enum


class Rejection(str, Enum):
    TERMINAL = "terminal"                      # no move of any level applies
    COST = "cost"                              # the Metropolis coin refused it
    MOVES_FRAME = "moves the frame"            # it would remove a frame corner
    SPLITS = "splits the drawing"              # connected or framed: it would cut a part off
    OVER_CONSTRAINED = "over-constrained"      # A x = b has no solution
    LENGTH_FIXED = "length fixed out of range"  # the system fixes a length outside its class
    LENGTH_RANGE = "length out of range"       # no target in the sampling box can fit
    NO_ROOM = "stretch too short"              # a structure stood on a side's stretch: stands.py
    FRAME_ROOM = "no room before the frame"    # a part reaching past a side: stands.py
    TILES = "tile lengths"                     # no whole number of tiles fits
    EDGE_LENGTH = "edge length"                # a sample broke a class's range
    OUTSIDE_FRAME = "outside the frame"
    COINCIDENT = "coincident vertices"
    CROSSING = "crossing"                      # an edge crosses or touches another
    CLOSE = "close to a far part"              # within the gap of a part far in the graph
    FACE_LABELS = "face labels"                # a face would get the wrong label
    NO_PLACEMENT = "no placement"
    # hand-written productions (free_engine)
    EVALUATION = "evaluation"                  # an expression has no finite value
    COORDINATE = "coordinate not finite"       # a vertex placed beyond ±1e12, or not finite
    DANGLING = "dangling"                      # DPO: a deleted vertex keeps other edges
    NO_CHANGE = "no change"                    # the step would leave its match as it was

    __str__ = str.__str__
    __format__ = str.__format__
    __hash__ = str.__hash__
