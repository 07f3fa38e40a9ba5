"""The kernel: graph algorithms that the compiler and the runtime both call, written once.

One module per algorithm family, in the manner of networkx: `components` (union-find and
connected components), `faces` (walking the faces of a rotation system), `matching` (anchored
matching of a rule side, with a feasibility hook), `dpo` (gluing a replacement side into the
hole its match leaves, wires included) and `canon` (canonical forms: one key per isomorphism
class of labelled planar graphs). The modules know
nothing of either package; they work on plain vertex numbers, pairs and arrays.
"""
