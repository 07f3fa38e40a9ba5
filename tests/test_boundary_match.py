"""Algorithm 2: building a boundary from simpler graphs' boundaries by splicing (§5.3)."""

from hypothesis import given, settings, strategies as st

from compiler.boundary_match import Matcher, Piece
from grammar_lang import boundary as bd


def gaps(tokens):
    return tuple(bd.gaps(tokens))


def piece(node, tokens, order):
    g = gaps(tokens)
    return Piece(node, g, (len(g), order))


def spliced(match, target):
    """Rebuild the target's half-edges from the match: each exactly once."""
    used = sorted(k for _, pos in match for k in pos)
    assert used == list(range(len(target)))
    for p, pos in match:
        assert [target[k][0] for k in pos] == [t for t, _ in p.gaps]


def test_paper_example_abcdefghi():
    # ∂L = abcdefghi∧ matched by acg∧, b∧, d∧, ef∧ and hi∧ (the paper's illustration).
    a, b, c, d, e, f, g, h, i = (2 * k for k in range(9))
    up = bd.UP
    m = Matcher(splice=True)
    for n, toks in enumerate([(a, c, g, up), (b, up), (d, up), (e, f, up), (h, i, up)]):
        m.add(piece(n, toks, n))
    target = gaps((a, b, c, d, e, f, g, h, i, up))
    match = m.find(target, (9, 100))
    assert match is not None
    spliced(match, target)
    assert {p.node for p, _ in match} == {0, 1, 2, 3, 4}


def test_turns_between_matched_half_edges_must_agree():
    # acg∧ does not fit a∧cg... (a full turn between a and c) unless the unmatched part
    # between them absorbs it: here there is none, so no match.
    a, c, g = 0, 2, 4
    up = bd.UP
    m = Matcher(splice=True)
    m.add(piece(0, (a, c, g, up), 0))
    assert m.find(gaps((a, up, c, g)), (3, 100)) is None
    assert m.find(gaps((a, c, g, up)), (3, 100)) is not None


def test_spliced_substring_may_carry_any_turns_at_its_ends():
    # ∂L = x y∧ȳ∨ ... : the piece x∧ plus a substring y∧ȳ∨ whose closing turns are free
    # (A|B → A∧ⁿB∨ⁿ⁺¹): it is matched by the graph ȳy∧ spliced in.
    x, y, yb = 0, 2, 3
    up, down = bd.UP, bd.DOWN
    m = Matcher(splice=True)
    m.add(piece(0, (x, up), 0))
    m.add(piece(1, (yb, y, up), 1))
    target = gaps((x, up, y, up, yb, down))
    assert bd.winding(bd.from_gaps(target)) == 1
    match = m.find(target, (3, 100))
    assert match is not None
    spliced(match, target)


def test_without_splicing_only_equal_boundaries_match():
    a, b = 0, 2
    up = bd.UP
    m = Matcher(splice=False)
    m.add(piece(0, (a, up), 0))
    m.add(piece(1, (b, up), 1))
    assert m.find(gaps((a, b, up)), (2, 100)) is None
    m.add(piece(2, (b, up, a), 2))     # the same cyclic string as ab∧
    assert m.find(gaps((a, b, up)), (2, 100)) is not None
    # Only simpler graphs: a graph never matches itself or a later graph.
    assert m.find(gaps((a, b, up)), (2, 2)) is None


def _splice(a, b, at, lead):
    """A|B spliced after A's half-edge `at` with `lead` turns before B (the ∧ⁿ…∨ⁿ⁺¹ freedom):
    the turns from A[at] to A[at + 1] stay what they were."""
    inner = sum(n for _, n in b[:-1])
    tok, n = a[at]
    out = list(a[:at]) + [(tok, lead)] + list(b[:-1]) + [(b[-1][0], n - lead - inner)]
    return tuple(out) + tuple(a[at + 1:])


def _turns_between(target, a, b):
    m = len(target)
    return sum(target[(a + d) % m][1] for d in range((b - a) % m or m))


@settings(max_examples=60, deadline=None)
@given(st.data())
def test_any_splice_of_pieces_is_found(data):
    n = data.draw(st.integers(2, 4))
    pieces = []
    for k in range(n):
        size = data.draw(st.integers(1, 3))
        toks = data.draw(st.lists(st.integers(0, 5), min_size=size, max_size=size))
        turns = data.draw(st.lists(st.integers(-1, 1), min_size=size - 1, max_size=size - 1))
        turns.append(1 - sum(turns))
        pieces.append(tuple(zip(toks, turns)))
    target = pieces[0]
    for b in pieces[1:]:
        at = data.draw(st.integers(0, len(target) - 1))
        target = _splice(target, b, at, data.draw(st.integers(-2, 2)))
    m = Matcher(splice=True)
    for k, p in enumerate(pieces):
        m.add(Piece(k, p, (len(p), k)))
    match = m.find(target, (len(target) + 1, 0))
    assert match is not None
    spliced(match, target)
    for p, pos in match:
        # Between consecutive half-edges of a piece the target turns as the piece does.
        for q in range(len(pos)):
            if len(pos) > 1:
                assert _turns_between(target, pos[q], pos[(q + 1) % len(pos)]) == p.gaps[q][1]
