"""`ggc verify`: finds every complete graph, passes sound grammars and catches broken ones."""

from dataclasses import replace

import pytest

from conftest import CORPUS, ILLUSTRATIONS
from hand_examples import RECTANGLE, make
from compiler.cli import main
from compiler.infer import compile_example
from compiler.canon import canonical_key
from compiler.verify import complete_graphs, frame_graph, verify
from grammar_lang.loader import load_example


def test_enumerates_rectangles_and_their_composites():
    rings = [p.ring for p in make(RECTANGLE).primitives]
    graphs, capped = complete_graphs(rings, 4)
    assert not capped and len(graphs) == 1 and len(graphs[0].verts) == 4
    graphs, _ = complete_graphs(rings, 8)
    # With 8 corners: the rectangle, and the L and other 6- and 8-corner outlines.
    assert len(graphs) > 3 and all(g.is_complete for g in graphs)


def test_a_grammar_missing_a_rule_fails():
    res = compile_example(make(RECTANGLE))
    rules = res.grammar.rules
    # Without the starter nothing reduces to ∅; without the x rules, no wide rectangle does.
    for keep in (lambda r: not r.is_starter,
                 lambda r: r.is_starter or r.rhs.wires != (0,)):
        broken = replace(res.grammar, rules=tuple(r for r in rules if keep(r)))
        v = verify(broken, 8)
        assert not v.ok and v.failed
    assert verify(res.grammar, 8).ok


def test_cli_compile_then_verify(tmp_path, capsys):
    out = tmp_path / "sq.ggr"
    report = tmp_path / "sq.json"
    src = str(CORPUS / "square-hollow.svg")
    assert main(["compile", src, "-o", str(out), "--report", str(report)]) == 0
    assert out.exists() and '"complete": true' in report.read_text()
    assert "complete" in capsys.readouterr().out
    assert main(["verify", str(out), "--max-primitives", "8"]) == 0
    text = capsys.readouterr().out
    assert "0 failed" in text
    # Recompiling over an unedited file is fine; over an edited one it needs --force.
    assert main(["compile", src, "-o", str(out)]) == 0
    out.write_text(out.read_text().replace("weight=1", "weight=2", 1))
    assert main(["compile", src, "-o", str(out)]) == 2
    assert main(["compile", src, "-o", str(out), "--force"]) == 0


def test_cli_errors_are_diagnostics(tmp_path, capsys):
    assert main(["verify", str(tmp_path / "missing.ggr")]) == 2
    assert main(["compile", str(tmp_path / "x.txt")]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_a_match_never_closes_wires_into_a_loop_without_vertices():
    # Cut one edge of a complete graph: the rest, as a left side whose right side is one bare
    # wire, matches the complete graph only by closing that wire on itself; that is no match.
    from grammar_lang.algorithms.components import glued_components
    from compiler.gluing import Graph
    from grammar_lang.graph import Side, face_walk
    from compiler.occurrence import Host, Pattern, contains
    from compiler.verify import complete_graphs
    from hand_examples import RECTANGLE, make
    rings = [p.ring for p in make(RECTANGLE).primitives]
    graphs, _ = complete_graphs(rings, 6, True, 1000)
    assert graphs
    for g in graphs:
        host = Host(g.verts, g.edges)
        for e in g.edges:
            rest = tuple(x for x in g.edges if x != e)
            if len(glued_components(range(len(g.verts)), rest)) != 1:
                continue
            cut = Graph(g.verts, rest, tuple(face_walk(Side(g.verts, rest, ()), (e[0], e[1]),
                                                          rings)))
            assert len(cut.gaps) == 2
            assert contains(Pattern.of(cut), host)
            assert not contains(Pattern.of(cut, ((0, 1),)), host)


def test_a_time_limit_gives_an_honest_partial_check(tmp_path, capsys):
    res = compile_example(make(RECTANGLE))
    whole = verify(res.grammar, 8)
    assert not whole.stopped and whole.checked == whole.enumerated > 3
    # A limit already spent: nothing is claimed beyond what was checked.
    part = verify(res.grammar, 8, seconds=1e-9)
    assert part.stopped == "time limit" and part.checked < whole.checked and part.ok
    # The command says the check is partial, and refuses a limit that is not positive.
    out = tmp_path / "sq.ggr"
    assert main(["compile", str(CORPUS / "square-hollow.svg"), "-o", str(out)]) == 0
    capsys.readouterr()
    assert main(["verify", str(out), "--seconds", "1e-9"]) == 0
    got = capsys.readouterr()
    assert "partial" in got.out and "not a complete check" in got.err
    assert main(["verify", str(out), "--seconds", "0"]) == 2
    assert "must be positive" in capsys.readouterr().err


@pytest.mark.parametrize("name,n", [("star-crossing", 4), ("triangle-complex", 5),
                                     ("x-box-square", 4), ("h-complex", 5), ("square-hollow", 8),
                                     ("flowers.gg", 5), ("space-station.gg", 5),
                                     ("space-station.gg", 6)])
def test_the_size_prefilter_keeps_exactly_the_same_graphs(name, n):
    # The illustrations have forced groups: the flowers' rigid blossoms of nine primitives are
    # left out at 5; the station's complete graphs of 5 and 6 hold groups of four.
    path = ILLUSTRATIONS / name if name.endswith(".gg") else CORPUS / f"{name}.svg"
    rings = [p.ring for p in load_example(path).primitives]
    keys = []
    for prefilter in (True, False):
        graphs, stopped = complete_graphs(rings, n, prefilter=prefilter)
        assert not stopped
        keys.append(sorted(canonical_key(g, [len(r) for r in rings]) for g in graphs))
    assert keys[0] == keys[1]


def test_side_graph_keeps_every_slot_and_refuses_wires():
    # A wired side has no Graph form: side_graph says so instead of dropping the wires.
    from compiler.apply import side_graph
    from grammar_lang import boundary as bd
    res = compile_example(load_example(CORPUS / "diagonal-box.svg"))
    rings = res.grammar.rings
    wired = [s for r in res.grammar.rules for s in (r.lhs, r.rhs) if s.wires]
    assert wired
    for side in wired:
        with pytest.raises(ValueError, match="wires"):
            side_graph(side)
    for r in res.grammar.rules:
        for side in (r.lhs, r.rhs):
            if side.wires:
                continue
            g = side_graph(side)
            assert (g.verts, set(g.edges)) == (side.vertices, set(side.edges))
            assert bd.canonical(g.side().tokens(rings)) == bd.canonical(side.tokens(rings))


def test_a_framed_grammar_reduces_to_its_frame():
    # Generation starts from the frame and no rule creates or deletes it, so the frame is
    # where a scene's reductions end (the paper's flowers are complete: nothing else fails).
    ex = load_example(CORPUS.parent / "illustrations" / "flowers.gg")
    grammar = compile_example(ex).grammar
    frame = frame_graph(grammar)
    assert frame is not None and frame.is_complete
    assert len(frame.verts) == len(grammar.header.frame.corners)
    res = verify(grammar, 8)
    assert res.checked >= 1 and res.ok, res.failed


def test_verify_says_why_a_frame_start_grammar_fails_smaller_scenes(tmp_path, capsys):
    # The village starts from its frame's start graph (two strips of land): a frame with one
    # strip is locally similar but unreachable, and verify says so instead of leaving it bare.
    from conftest import ROOT
    ggr = tmp_path / "village.ggr"
    assert main(["compile", str(ROOT / "examples" / "village.gg"), "-o", str(ggr)]) == 0
    capsys.readouterr()
    assert main(["verify", str(ggr), "--max-primitives", "6"]) == 1
    captured = capsys.readouterr()
    assert "reduce to ∅ or the frame" in captured.out
    assert "hold the frame but are not its start graph" in captured.err
