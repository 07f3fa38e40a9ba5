"""Boundary strings (paper §3.3), in the two forms the project writes them in.

A token `t >= 0` is a half-edge: label `t >> 1`, barred (`ā`, pointing in [-180°, 0°)) when
`t & 1`. `UP` is a positive turn ∧ and `DOWN` a negative turn ∨. A boundary string is cyclic:
rotations are equal, and adjacent ∧∨ cancel, also across the wrap-around. `canonical` gives one
representative per class, so it can be hashed. Every closed boundary has P − N = 1.

The half-edges of a boundary are named by token where only their labels matter (a primitive, a
class of graphs, what a `.ggr` file says), and by slot `(vertex, ring index)` where they belong
to one graph (`graph.Side.boundary`, a compiler hierarchy graph); a slot stands where a token
would. Either way a boundary takes one of two forms, and each has its job:

- **string form** (`Tokens` for tokens): half-edges and `UP`/`DOWN` marks in walking order, the
  paper's notation. It is what a `.ggr` file writes and a person reads; it is the only form
  that tells the complete graph (∧) from the empty one (); `canonical` hashes it.
- **gap form** (`Gaps`): one (half-edge, net turns ∧ minus ∨ after it) pair per half-edge, from
  a half-edge on. It is the reduced string, with the turns between two half-edges as one count,
  so splicing and gluing (§4.2) and Algorithm 2's turn totals are small arithmetic on it.

`gaps` and `from_gaps` convert between them, for tokens and slots alike.
"""

from __future__ import annotations

from typing import Hashable, Iterable, Sequence, TypeVar

UP = -1     # ∧
DOWN = -2   # ∨

H = TypeVar("H", bound=Hashable)      # a half-edge: a token (int >= 0) or a slot (vertex, index)
Tokens = tuple[int, ...]
Gaps = tuple[tuple[H, int], ...]


def half(label: int, bar: bool) -> int:
    return (label << 1) | int(bar)


def label_of(token: int) -> int:
    return token >> 1


def is_bar(token: int) -> bool:
    return bool(token & 1)


def opposite(token: int) -> int:
    """The half-edge a token glues to: a ↔ ā."""
    return token ^ 1


def turns(n: int) -> Tokens:
    """∧ⁿ for n > 0, ∨⁻ⁿ for n < 0."""
    return (UP,) * n if n >= 0 else (DOWN,) * (-n)


def winding(tokens: Iterable[int]) -> int:
    """P − N: the number of positive minus negative turns."""
    return sum(1 if t == UP else -1 if t == DOWN else 0 for t in tokens)


def halves(tokens: Iterable[int]) -> Tokens:
    return tuple(t for t in tokens if t >= 0)


def reduce_linear(tokens: Iterable[int]) -> Tokens:
    """Cancel adjacent opposite turns in an open (non-cyclic) string."""
    out: list[int] = []
    for t in tokens:
        if t < 0 and out and out[-1] < 0 and out[-1] != t:
            out.pop()
        else:
            out.append(t)
    return tuple(out)


def reduce(tokens: Iterable[int]) -> Tokens:
    """Cancel adjacent opposite turns cyclically, so the result has one kind of turn per gap."""
    out = list(reduce_linear(tokens))
    # After the linear pass only the two ends can still cancel with each other.
    while len(out) >= 2 and out[0] < 0 and out[-1] < 0 and out[0] != out[-1]:
        out.pop()
        out.pop(0)
    return tuple(out)


def rotations(tokens: Sequence[int]) -> Iterable[Tokens]:
    n = len(tokens)
    t = tuple(tokens)
    for i in range(n):
        yield t[i:] + t[:i]


def canonical(tokens: Iterable[int]) -> Tokens:
    """The least rotation of the reduced string: equal for equal cyclic boundary strings."""
    return least_rotation(reduce(tokens))


def least_rotation(seq: Sequence) -> tuple:
    """The least of the rotations of `seq`; () for an empty one."""
    return min(rotations(seq)) if seq else ()


def gaps(string: Iterable) -> Gaps:
    """The gap form of a string (of tokens or of slots): (half-edge, net turns after it) pairs,
    starting at the first half-edge. Turns before the first half-edge wrap around to the last
    pair; turns need not be reduced. A string with no half-edges gives ().
    """
    items = list(string)
    for first, t in enumerate(items):
        if t != UP and t != DOWN:
            break
    else:
        return ()
    out: list[list] = []
    for t in items[first:] + items[:first]:
        if t == UP:
            out[-1][1] += 1
        elif t == DOWN:
            out[-1][1] -= 1
        else:
            out.append([t, 0])
    return tuple((h, n) for h, n in out)


def from_gaps(pairs: Iterable[tuple[H, int]], complete: bool = False) -> tuple:
    """The string form of a gap form. With no pairs, a `complete` graph's string is ∧ and any
    other's (the empty graph's) is ()."""
    out: list = []
    for h, n in pairs:
        out.append(h)
        out.extend(turns(n))
    return tuple(out) if out or not complete else (UP,)


def primitive_boundary(angled_halves: Iterable[tuple[float, int]]) -> Tokens:
    """The boundary of one vertex with its half-edges, given as (angle in [-180, 180), token).

    Walking counter-clockwise around the vertex visits the half-edges by increasing angle; the
    tangent wraps past 180° once, between the last and the first, which is the ∧.
    """
    ring = [t for _, t in sorted(angled_halves)]
    return tuple(ring) + (UP,)


# --- text forms ---------------------------------------------------------------------------

UNICODE_UP, UNICODE_DOWN, MACRON = "∧", "∨", "\u0304"


def format_tokens(tokens: Iterable[int], names: Sequence[str], ascii: bool = False) -> str:
    """Readable form: `ȳ∨x∧` in Unicode, or `~y - x +` in ASCII (what `.ggr` files use)."""
    parts = []
    for t in tokens:
        if t == UP:
            parts.append("+" if ascii else UNICODE_UP)
        elif t == DOWN:
            parts.append("-" if ascii else UNICODE_DOWN)
        else:
            name = names[t >> 1]
            if t & 1:
                parts.append("~" + name if ascii else _bar(name))
            else:
                parts.append(name)
    return (" " if ascii else "").join(parts)


def _bar(name: str) -> str:
    # Put the macron over the first character so that subscripts stay readable: x̄₀₁.
    return name[0] + MACRON + name[1:]


class BoundarySyntaxError(ValueError):
    def __init__(self, message: str, position: int):
        super().__init__(message)
        self.position = position


def parse_tokens(text: str, ids: dict[str, int]) -> Tokens:
    """Parse the ASCII form written by `format_tokens(..., ascii=True)`.

    Raises `BoundarySyntaxError` with the 0-based character position of the bad word; callers
    turn it into a diagnostic with their own file position.
    """
    out: list[int] = []
    pos = 0
    for word in text.split():
        pos = text.index(word, pos)
        if word == "+":
            out.append(UP)
        elif word == "-":
            out.append(DOWN)
        else:
            bar = word.startswith("~")
            name = word[1:] if bar else word
            if name not in ids:
                raise BoundarySyntaxError(f"unknown edge label '{name}'", pos)
            out.append(half(ids[name], bar))
        pos += len(word)
    return tuple(out)
