"""The boundary-string algebra of paper §3.3."""

from hypothesis import given, strategies as st

from grammar_lang import boundary as bd

halves = st.integers(min_value=0, max_value=11)
tokens = st.lists(st.one_of(halves, st.sampled_from([bd.UP, bd.DOWN])), max_size=16)


def closed(ts):
    """Pad a token list with turns so that P − N = 1, as every closed boundary has."""
    return tuple(ts) + bd.turns(1 - bd.winding(ts))


@given(tokens, st.integers(0, 20))
def test_rotations_have_one_canonical_form(ts, k):
    ts = closed(ts)
    k = k % len(ts)
    assert bd.canonical(ts) == bd.canonical(ts[k:] + ts[:k])


@given(tokens)
def test_cancellation_keeps_winding_and_half_edges(ts):
    r = bd.reduce(ts)
    assert bd.winding(r) == bd.winding(ts)
    assert bd.halves(r) == bd.halves(ts)
    # No adjacent opposite turns remain, including across the wrap-around.
    for a, b in zip(r, r[1:] + r[:1]):
        if len(r) > 1:
            assert not (a < 0 and b < 0 and a != b)


@given(tokens, st.integers(0, 5))
def test_inserting_cancelling_pairs_changes_nothing(ts, where):
    ts = closed(ts)
    where = where % (len(ts) + 1)
    padded = ts[:where] + (bd.UP, bd.DOWN) + ts[where:]
    assert bd.canonical(padded) == bd.canonical(ts)


@given(st.lists(st.tuples(st.floats(-180, 179.99), halves), min_size=1, max_size=8,
                unique_by=lambda p: p[1]))
def test_primitive_boundaries_turn_once(items):
    b = bd.primitive_boundary(items)
    assert bd.winding(b) == 1
    assert sorted(bd.halves(b)) == sorted(t for _, t in items)


@given(tokens)
def test_gaps_round_trip(ts):
    ts = closed(ts)
    if bd.halves(ts):
        assert bd.canonical(bd.from_gaps(bd.gaps(ts))) == bd.canonical(ts)


@given(tokens, st.integers(0, 7))
def test_the_gap_form_is_the_same_over_slots_as_over_tokens(ts, vertex):
    # Name each half-edge by a slot (its position), as a graph's boundary does: the gap form
    # over slots, read back through the slots' tokens, is the gap form over tokens.
    slots = [(vertex, k) if t >= 0 else t for k, t in enumerate(ts)]
    token_of = {(vertex, k): t for k, t in enumerate(ts) if t >= 0}
    assert tuple((token_of[s], n) for s, n in bd.gaps(slots)) == bd.gaps(ts)
    back = bd.from_gaps(bd.gaps(slots))
    assert bd.winding(back) == (bd.winding(ts) if bd.halves(ts) else 0)
    assert [it for it in back if isinstance(it, tuple)] == [it for it in slots
                                                           if isinstance(it, tuple)]


def test_the_string_form_tells_the_complete_graph_from_the_empty_one():
    assert bd.gaps((bd.UP,)) == bd.gaps(()) == ()
    assert bd.from_gaps((), complete=True) == (bd.UP,)
    assert bd.from_gaps(()) == ()
    assert bd.from_gaps(((0, 2), (1, -1)), complete=True) == (0, bd.UP, bd.UP, 1, bd.DOWN)


def test_paper_examples():
    # ∂G₁ = y∧b̄ā: shifted strings are equal (§3.3) and ∧x∨ cancels inside a string.
    y, b, a = 0, 2, 4
    g1 = (y, bd.UP, b | 1, a | 1)
    assert bd.canonical(g1) == bd.canonical((bd.UP, b | 1, a | 1, y))
    assert bd.reduce_linear((a, bd.UP, bd.DOWN, 6)) == (a, 6)
    assert bd.winding(g1) == 1


def test_text_forms_round_trip():
    names = ["x", "y"]
    ts = (bd.half(1, True), bd.DOWN, bd.half(0, False), bd.UP)
    assert bd.format_tokens(ts, names) == "y\u0304∨x∧"
    text = bd.format_tokens(ts, names, ascii=True)
    assert text == "~y - x +"
    assert bd.parse_tokens(text, {"x": 0, "y": 1}) == ts
