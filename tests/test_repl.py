"""The REPL (`ggrun --repl`): scripted sessions, the transcript in docs/repl.md, errors that
never end a session, and undo back to the start after any sequence of commands."""

from __future__ import annotations

import io
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from report.ggrun import compile_example, main
from runtime.cli import build_parser
from runtime.repl.session import Output, Session, execute, repl_command
from runtime.repl.commands import COMMANDS
from runtime.repl.complete import completions
from runtime.verifier import check_drawing

from runtime_grammars import cut_pair, filled_square, lines, lines_with_wire

ROOT = Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "repl.md"
GRAMMAR = ROOT / "examples" / "square-walls.ggr"


def script(commands: str, *flags: str, file: str | None = str(GRAMMAR), echo: bool = False):
    """Run a REPL script in-process: (exit status, stdout, stderr)."""
    args = build_parser().parse_args(([file] if file else []) + ["--repl", *flags])
    args.compile_example = compile_example      # as the ggrun command hands it in
    out, err = io.StringIO(), io.StringIO()
    rc = repl_command(args, io.StringIO(commands), out, err, echo)
    return rc, out.getvalue(), err.getvalue()


def session(grammar, name: str = "g.ggr") -> tuple[Session, io.StringIO]:
    buf = io.StringIO()
    s = Session(Output(buf, buf, colour=False), compile_example=compile_example)
    s.use(grammar, name)
    return s, buf


# --- the transcript ---------------------------------------------------------------------------

def _transcript() -> tuple[str, str, str]:
    """(text before the block, the block, text after) of the session in docs/repl.md."""
    text = DOC.read_text(encoding="utf-8")
    m = re.search(r"## A session\n.*?```text\n(.*?)```\n", text, re.S)
    assert m, "docs/repl.md has no session block"
    return text[:m.start(1)], m.group(1), text[m.end(1):]


def _replay(block: str, where: Path) -> str:
    first, *rest = block.split("\n")
    assert first.startswith("$ ggrun --repl ")
    argv = first.split()[1:]
    commands = "".join(line[len("gg> "):] + "\n" for line in rest if line.startswith("gg> "))
    (where / "examples").mkdir()
    shutil.copy(GRAMMAR, where / "examples" / GRAMMAR.name)
    old = os.getcwd()
    os.chdir(where)
    try:
        args = build_parser().parse_args(argv[1:])
        args.compile_example = compile_example
        out = io.StringIO()
        repl_command(args, io.StringIO(commands), out, out, echo=True)
    finally:
        os.chdir(old)
    return first + "\n" + out.getvalue()


def test_docs_transcript_replays(tmp_path):
    head, block, tail = _transcript()
    got = _replay(block, tmp_path)
    if os.environ.get("GG_REGENERATE_DOCS"):
        DOC.write_text(head + got + tail, encoding="utf-8")
        return
    assert got == block
    # The session shows what it claims to: a failure, an error with a hint, a check.
    assert "hint: did you mean 'apply'?" in got and "ok: " in got
    assert (tmp_path / "session.svg").read_text().startswith("<")


# --- scripts ----------------------------------------------------------------------------------

def test_script_exit_status_and_errors_on_stderr():
    rc, out, err = script("rules\nshow\n")
    assert rc == 0 and err == "" and "square" in out
    rc, out, err = script("show\nfrobnicate\nshow\n")
    assert rc == 1
    assert "unknown command 'frobnicate'" in err and "hint:" in err
    # The session went on: show ran twice, with the same state.
    shows = [l for l in out.splitlines() if l.startswith("square-walls.ggr:")]
    assert len(shows) == 2 and shows[0] == shows[1]


def test_quit_stops_and_comments_are_skipped():
    rc, out, _ = script("# a comment\nrules  # trailing\nquit\nbogus\n")
    assert rc == 0 and "square" in out


def test_without_a_file_commands_ask_for_one():
    rc, _, err = script("rules\n", file=None)
    assert rc == 1 and "no grammar loaded" in err and "load" in err
    rc, out, err = script(f"load {GRAMMAR}\nrules\n", file=None)
    assert rc == 0, err
    assert "loaded square-walls.ggr" in out


def test_bad_load_keeps_the_session(tmp_path):
    bad = tmp_path / "bad.ggr"
    bad.write_text("ggr 1\nthis is not a grammar\n")
    rc, out, err = script(f"apply square --backward\nload {bad}\nload nosuch.txt\nshow\n")
    assert rc == 1
    assert "bad.ggr:2" in err and "nosuch.txt" in err
    assert "square-walls.ggr: 4 vertices" in out


BAD_LINES = [
    "", "   ", "apply", "apply nosuch", "apply squar --backward", "apply square 0 --backward",
    "apply square 99 --backward", "apply square x", "apply square --backwards",
    "matches", "matches split extra", "step -1", "step x", "step 1 2", "run", "run -5",
    "run 1e3", "undo x", "undo 0", "redo", "seed", "seed -1", "seed 1.5", "render",
    "render x.png", "save x.svg", "open x.svg", "open /nonexistent/x.json", "watch x.txt",
    "help nosuch", "help a b", "quit now", "show x", "check x", "rules x", "primitives x",
    "load", "load a b", "'unclosed", "apply \"square", "\x00", "é", "run 99999999999999999999x",
]


@pytest.mark.parametrize("line", BAD_LINES)
def test_bad_input_is_an_error_with_a_hint_never_a_crash(line):
    s, buf = session(filled_square())
    assert execute(s, "apply rect --backward")
    before = s.engine.host.to_drawing()
    ok = execute(s, line)
    text = buf.getvalue()
    assert "internal error" not in text and "Traceback" not in text
    if not ok:
        assert "hint:" in text or "error" in text
    assert s.engine.host.to_drawing() == before or line.startswith(("undo", "redo"))
    assert s.engine.host.check_consistency() == []


def test_did_you_mean_for_commands_rules_and_options():
    s, buf = session(filled_square())
    for line, want in [("aply rect", "'apply'"), ("apply rec", "'rect'"),
                       ("matches rect --backwrd", "'--backward'"), ("hlp", "'help'")]:
        assert not execute(s, line)
        assert want in buf.getvalue(), line


# --- the same engine and verifier ---------------------------------------------------------------

def test_run_then_save_is_what_ggrun_writes(tmp_path):
    a, b = tmp_path / "a.json", tmp_path / "b.json"
    rc, out, err = script(f"run 15\nsave {a}\n", "--seed", "3", "--steps", "15")
    assert rc == 0, err
    assert main([str(GRAMMAR), "--seed", "3", "--steps", "15", "--out", str(b), "--quiet"]) == 0
    assert a.read_bytes() == b.read_bytes()


def test_check_is_the_verifier():
    s, buf = session(cut_pair("spo"))
    assert execute(s, "apply segment --backward") and execute(s, "check")
    assert "ok: 2 vertices, 1 edge" in buf.getvalue()
    assert check_drawing(s.grammar, s.drawing()) == []
    execute(s, "apply segment --backward")
    assert execute(s, "apply cut 1")
    assert not execute(s, "check")          # two lone ends: rings the example does not have
    assert "failed: 2 problem(s): 2 ring" in buf.getvalue()


def test_show_gives_boundary_strings_of_open_parts():
    s, buf = session(cut_pair("spo"))
    for line in ["apply segment --backward", "apply cut 1", "show"]:
        assert execute(s, line), buf.getvalue()
    text = buf.getvalue()
    assert "2 open half-edges" in text
    assert "boundary ∧ x\n" in text and "boundary ∧ x̄\n" in text


def test_show_component_lists_vertices_slot_by_slot():
    s, buf = session(cut_pair("spo"))
    for line in ["apply segment --backward", "apply segment --backward", "apply cut 1"]:
        assert execute(s, line)
    comps = s.engine.host.components()
    lone = next(k for k, c in enumerate(comps) if len(c) == 1)
    assert execute(s, f"show {lone + 1}")
    assert re.search(rf"^v{comps[lone][0]}\s+[LR]\s+\(.*\)\s+x̄?→-$", buf.getvalue(), re.M)
    assert not execute(s, f"show {len(comps) + 1}") and "'show' lists them" in buf.getvalue()


def test_interrupt_stops_between_steps_and_keeps_them():
    s, buf = session(filled_square())
    s.interrupted = True          # what Ctrl-C does during a command on a terminal
    assert not execute(s, "run 50")
    assert "interrupted" in buf.getvalue()
    assert len(s.engine.history) <= 1 and s.engine.host.check_consistency() == []
    assert execute(s, "run 3") and len(s.engine.history) >= 1


def test_file_flags_of_ggrun_are_refused_with_the_repl():
    for flags in (["--out", "x.svg"], ["--count", "2"], ["--jobs", "2"]):
        assert main([str(GRAMMAR), "--repl", *flags]) == 2


def test_matches_are_numbered_and_apply_takes_the_number():
    s, buf = session(lines())
    for _ in range(2):
        assert execute(s, "apply segment --backward")
    assert execute(s, "matches grow --backward")
    listed = re.findall(r"^\s+(\d+)  v0=v(\d+)", buf.getvalue(), re.M)
    assert [k for k, _ in listed] == ["1", "2"]
    before = set(s.engine.host.vertices())
    assert execute(s, "apply grow 2 --backward")
    removed = before - set(s.engine.host.vertices())
    assert removed == {int(listed[1][1])}


def test_open_reads_back_what_save_wrote(tmp_path):
    s, buf = session(filled_square())
    for line in ["seed 4", "run 6", f"save {tmp_path / 'a.json'}", "reset",
                 f"open {tmp_path / 'a.json'}", f"save {tmp_path / 'b.json'}"]:
        assert execute(s, line), buf.getvalue()
    a = json.loads((tmp_path / "a.json").read_text())
    b = json.loads((tmp_path / "b.json").read_text())
    assert (a["vertices"], a["edges"]) == (b["vertices"], b["edges"])
    assert s.engine.host.check_consistency() == []
    assert execute(s, "undo 2") and len(s.engine.host) == len(a["vertices"])


def test_open_refuses_a_drawing_of_another_grammar(tmp_path):
    s, buf = session(filled_square())
    execute(s, "apply rect --backward")
    assert execute(s, f"save {tmp_path / 'sq.json'}")
    t, tbuf = session(lines())
    assert not execute(t, f"open {tmp_path / 'sq.json'}")
    assert "does not have" in tbuf.getvalue() and len(t.engine.host) == 0


def test_open_refuses_a_drawing_spread_too_wide_to_file(tmp_path):
    """One vertex moved to 10^12 (found by benchmarks/fuzz.py): the engine would file its
    edges in 10^10 grid cells. It is refused at once, and the session keeps its drawing."""
    s, buf = session(filled_square())
    assert execute(s, "seed 4") and execute(s, "run 6")
    assert execute(s, f"save {tmp_path / 'a.json'}")
    d = json.loads((tmp_path / "a.json").read_text())
    d["vertices"][0]["y"] = 1e12
    (tmp_path / "far.json").write_text(json.dumps(d))
    before = len(s.engine.host)
    assert not execute(s, f"open {tmp_path / 'far.json'}")
    assert "spans 1e+12" in buf.getvalue() and len(s.engine.host) == before


def test_watch_rerenders_after_every_change(tmp_path):
    s, buf = session(filled_square())
    svg = tmp_path / "w.svg"
    assert execute(s, f"watch {svg}")
    empty = svg.read_text()
    assert execute(s, "apply rect --backward")
    one = svg.read_text()
    assert one != empty
    assert execute(s, "undo") and svg.read_text() == empty
    assert execute(s, "watch off") and execute(s, "redo")
    assert svg.read_text() == empty


def test_completion_of_commands_rules_and_flags():
    s, _ = session(filled_square())
    assert completions(s, "ap") == ["apply"]
    assert completions(s, "") == list(COMMANDS)
    assert completions(s, "apply r") == ["rect"]
    assert completions(s, "matches ") == ["rect", "bottom", "--backward"]
    assert completions(s, "apply rect --b") == ["--backward"]
    assert completions(s, "help un") == ["undo"]
    assert completions(s, "watch o") == ["off"]


def test_help_covers_every_command():
    s, buf = session(filled_square())
    for name in COMMANDS:
        assert execute(s, f"help {name}")
        assert COMMANDS[name].usage in buf.getvalue()


def test_corpus_examples_load_and_explore():
    # A compiled example, in memory: the same commands work on it and undo leads back.
    s, buf = session(filled_square())
    path = str(ROOT / "examples" / "tree.gg")
    for line in [f"load {path}", "rules", "seed 2", "run 8", "show", "check", "undo all"]:
        execute(s, line)
    text = buf.getvalue()
    assert "internal error" not in text and "loaded tree.gg" in text
    assert len(s.engine.host) == 0 and s.engine.host.check_consistency() == []


def test_stdin_not_a_terminal_end_to_end(tmp_path):
    # The installed entry point, with real pipes: plain text, no escape codes.
    proc = subprocess.run([sys.executable, "-m", "report.ggrun", str(GRAMMAR), "--repl"],
                          input="rules\nnosuch\n", capture_output=True, text=True,
                          cwd=tmp_path, timeout=120)
    assert proc.returncode == 1
    assert "\x1b[" not in proc.stdout + proc.stderr
    assert "square" in proc.stdout and "unknown command 'nosuch'" in proc.stderr


# --- never lose state -------------------------------------------------------------------------

GRAMMARS = {"square": filled_square(), "lines": lines(), "wire": lines_with_wire("spo"),
            "cut": cut_pair("spo")}
TMP = Path(tempfile.mkdtemp(prefix="gg-repl-test-"))


def _command(rules: list[str]):
    rule = st.sampled_from(rules + ["nosuch"])
    num = st.integers(-1, 4).map(str) | st.sampled_from(["x", "all", ""])
    back = st.sampled_from(["", " --backward", " --back"])
    return st.one_of(
        st.builds(lambda r, k, b: f"apply {r} {k}{b}", rule, num, back),
        st.builds(lambda r, b: f"matches {r}{b}", rule, back),
        st.builds(lambda k: f"step {k}", st.sampled_from(["", "1", "3"])),
        st.builds(lambda k: f"run {k}", st.sampled_from(["0", "2", "5"])),
        st.builds(lambda k: f"undo {k}", num), st.builds(lambda k: f"redo {k}", num),
        st.builds(lambda k: f"seed {k}", num),
        st.sampled_from(["reset", "show", "check", "rules", "primitives", "help",
                         f"save {TMP / 'h.json'}", f"open {TMP / 'h.json'}",
                         f"render {TMP / 'h.svg'}", "bogus", "'"]),
        st.text(max_size=12),
    )


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.data())
def test_random_sessions_never_crash_and_undo_reaches_the_start(data):
    name = data.draw(st.sampled_from(sorted(GRAMMARS)))
    s, buf = session(GRAMMARS[name], name)
    cmds = data.draw(st.lists(_command([r.name for r in GRAMMARS[name].rules]), max_size=12))
    for line in cmds:
        if "\n" in line or "\r" in line:
            continue
        execute(s, line)
        assert s.engine.host.check_consistency() == []
    text = buf.getvalue()
    assert "internal error" not in text, text
    host = s.engine.host
    end = host.to_drawing()
    n = len(s.engine.history)
    execute(s, "undo all")
    assert len(host) == 0 and host.n_edges == 0 and host.check_consistency() == []
    if n:
        execute(s, f"redo {n}")
    assert host.to_drawing() == end and len(s.engine.history) == n


def test_loading_an_example_shows_its_warnings_as_ggrun_does(tmp_path):
    """An example whose border ends in the air runs unframed, and one of pieces under
    `connected` draws one piece: the REPL says so when it loads them, to stderr."""
    open_border = tmp_path / "open.gg"
    open_border.write_text('example "open"\nface a #cc8\nclass frame { border }\n'
                           "polyline (0,0) (400,0) (400,200) (0,200) class frame\n"
                           "polygon a rect (100,0) (200,80)\n")
    pieces = tmp_path / "pieces.gg"
    pieces.write_text('example "pieces"\noptions { connected }\nface a #cc8\nface b #8cc\n'
                      "polygon a rect (0,0) (100,100)\npolygon b rect (300,0) (400,100)\n")
    rc, out, err = script(f"load {pieces}\nquit\n", file=str(open_border))
    assert rc == 0 and "loaded open.gg" in out and "loaded pieces.gg" in out
    assert "open.gg:4:1: warning: this border line ends in the air" in err
    assert "warning: with `connected`" in err and "never holds face label b" in err


def test_the_extent_flag_sizes_the_repls_frame(tmp_path):
    """`ggrun --repl FILE --extent W×H` builds its engine as ggrun does: the frame at that
    size (it was left at the example's own, the flag read and dropped)."""
    out = tmp_path / "r.json"
    rc, _, err = script(f"save {out}\nquit\n", "--extent", "2400x900",
                        file=str(ROOT / "examples" / "castle-scene.gg"))
    assert rc == 0, err
    xs = sorted({v["x"] for v in json.loads(out.read_text())["vertices"]})
    ys = sorted({v["y"] for v in json.loads(out.read_text())["vertices"]})
    assert (xs[0], xs[-1], ys[0], ys[-1]) == (0.0, 2400.0, 0.0, 900.0)
    # With the same flags, `run N` and `save` write the file ggrun writes.
    flags = ["--extent", "2400x900", "--seed", "4", "--steps", "30"]
    rc, _, err = script(f"run 30\nsave {out}\nquit\n", *flags,
                        file=str(ROOT / "examples" / "castle-scene.gg"))
    assert rc == 0, err
    direct = tmp_path / "g.json"
    assert main([str(ROOT / "examples" / "castle-scene.gg"), *flags, "--out", str(direct),
                 "--quiet"]) == 0
    assert out.read_bytes() == direct.read_bytes()
    from grammar_lang.diagnostics import UserError
    with pytest.raises(UserError, match="--extent sizes a frame, and this grammar has none"):
        script("quit\n", "--extent", "2400x900", file=str(ROOT / "examples" / "house.gg"))


def test_a_limit_on_a_level_no_rule_has_is_refused_as_ggrun_refuses_it():
    from grammar_lang.diagnostics import UserError
    with pytest.raises(UserError, match="no rule of this grammar has priority 7"):
        script("quit\n", "--limit", "7=5")
